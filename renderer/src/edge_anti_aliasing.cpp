#include "edge_anti_aliasing.hpp"

#include "luxel/runtime/shader_library.hpp"

namespace luxel::renderer {

EdgeAntiAliasing::EdgeAntiAliasing(const ShaderLibrary& shaders)
    : mask_(shaders.build({{ShaderStage::Vertex, "post/fullscreen.vert"},
                           {ShaderStage::Fragment, "post/edge_mask.frag"}})),
      program_(shaders.build({{ShaderStage::Vertex, "post/fullscreen.vert"},
                              {ShaderStage::Fragment, "post/edge_aa.frag"}})) {}

void EdgeAntiAliasing::run(const FrameTargets& targets, bool sky_resolved) const {
    const GLuint fbo = targets.frame_target.id();
    const int w = targets.width;
    const int h = targets.height;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    glViewport(0, 0, w, h);
    // Every pixel as composed; the filter below rewrites the marked ones.
    glBlitNamedFramebuffer(targets.composed_target.id(), fbo, 0, 0, w, h, 0, 0, w, h,
                           GL_COLOR_BUFFER_BIT, GL_NEAREST);
    // The mask: 1 where the G-buffer shows an edge (the other fragments are discarded).
    const GLint clear = 0;
    glStencilMask(0xFF);
    glClearNamedFramebufferiv(fbo, GL_STENCIL, 0, &clear);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, 1, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glBindTextureUnit(0, targets.composed.id());
    glBindTextureUnit(1, targets.position.id());
    glBindTextureUnit(2, targets.normal.id());
    mask_.use();
    mask_.set("u_sky_resolved", sky_resolved ? 1 : 0);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    // The filter where marked.
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glStencilFunc(GL_EQUAL, 1, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    program_.use();
    program_.set("u_sky_resolved", sky_resolved ? 1 : 0);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_STENCIL_TEST);
}

}  // namespace luxel::renderer
