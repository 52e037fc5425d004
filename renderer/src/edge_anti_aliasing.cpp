#include "edge_anti_aliasing.hpp"

#include "luxel/runtime/shader_library.hpp"
#include "stencil_mask.hpp"

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
    glBindTextureUnit(0, targets.composed.id());
    glBindTextureUnit(1, targets.position.id());
    glBindTextureUnit(2, targets.normal.id());
    // The mask (1 where the G-buffer shows an edge), then the filter where marked.
    const auto full_screen = [sky_resolved](const gl::Program& program) {
        program.use();
        program.set("u_sky_resolved", sky_resolved ? 1 : 0);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    };
    shade_marked(
        fbo, [&] { full_screen(mask_); }, [&] { full_screen(program_); });
}

}  // namespace luxel::renderer
