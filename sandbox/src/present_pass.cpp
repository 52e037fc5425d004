#include "present_pass.hpp"

namespace luxel::sandbox {

PresentPass::PresentPass(const ShaderLibrary& shaders)
    : program_(shaders.build({{ShaderStage::Vertex, "post/fullscreen.vert"},
                              {ShaderStage::Fragment, "post/tone_map.frag"}})),
      empty_vertex_array_(gl::VertexArray::create()) {}

void PresentPass::draw(GLuint hdr_texture, int width, int height,
                       const ToneMapSettings& settings) const {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, width, height);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    program_.set("u_hdr", 0);
    program_.set("u_exposure", settings.exposure);
    program_.set("u_operator", static_cast<int>(settings.op));
    program_.use();
    glBindTextureUnit(0, hdr_texture);
    glBindVertexArray(empty_vertex_array_.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
}

}  // namespace luxel::sandbox
