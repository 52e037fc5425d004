#include "edge_anti_aliasing.hpp"

#include "luxel/runtime/shader_library.hpp"

namespace luxel::renderer {

EdgeAntiAliasing::EdgeAntiAliasing(const ShaderLibrary& shaders)
    : program_(shaders.build({{ShaderStage::Vertex, "post/fullscreen.vert"},
                              {ShaderStage::Fragment, "post/edge_aa.frag"}})) {}

void EdgeAntiAliasing::run(const FrameTargets& targets, bool sky_resolved) const {
    const GLuint fbo = targets.frame_target.id();
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    glViewport(0, 0, targets.width, targets.height);
    program_.use();
    program_.set("u_sky_resolved", sky_resolved ? 1 : 0);
    glBindTextureUnit(0, targets.composed.id());
    glBindTextureUnit(1, targets.position.id());
    glBindTextureUnit(2, targets.normal.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

}  // namespace luxel::renderer
