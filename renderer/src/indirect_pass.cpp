#include "indirect_pass.hpp"

#include <array>
#include <cstdint>

namespace luxel::renderer {
namespace {

// Bits of the variants, in the order of the features.
constexpr std::uint32_t kBicubic = 1u;
constexpr std::uint32_t kProbes = 2u;

}  // namespace

IndirectPass::IndirectPass(const ShaderLibrary& shaders)
    : programs_(shaders, "post/fullscreen.vert", "render/indirect.frag",
                {"IIM_BICUBIC", "PROBES"}) {}

void IndirectPass::run(const FrameTargets& targets, const FrameCamera& camera, double now_seconds,
                       bool bicubic, const lighting::LightmapTextures& lightmaps,
                       const lighting::IrradianceProbeTextures& probes) {
    const GLuint fbo = targets.indirect_target.id();
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    glViewport(0, 0, targets.width, targets.height);
    const std::array<float, 4> zero = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearNamedFramebufferfv(fbo, GL_COLOR, 0, zero.data());
    glBindTextureUnit(0, targets.albedo.id());
    glBindTextureUnit(1, targets.normal.id());
    glBindTextureUnit(2, targets.position.id());
    glBindTextureUnit(3, targets.lightmap.id());
    lightmaps.bind();
    const auto draw = [&](std::uint32_t variant) {
        const gl::Program& program = programs_.get(variant);
        program.use();
        program.set("u_now", static_cast<float>(now_seconds));
        program.set("u_camera", camera.position);
        if ((variant & kProbes) != 0) {
            probes.bind(program);
        }
        glDrawArrays(GL_TRIANGLES, 0, 3);
    };
    // Every pixel from the light maps; then, with probes, the pixels the G-buffer's stencil
    // marks (no light map) with them.
    const std::uint32_t filter = bicubic ? kBicubic : 0u;
    draw(filter);
    if (!probes.empty()) {
        glEnable(GL_STENCIL_TEST);
        glStencilMask(0x00);
        glStencilFunc(GL_EQUAL, 1, 0xFF);
        draw(filter | kProbes);
        glDisable(GL_STENCIL_TEST);
        glStencilMask(0xFF);
    }
}

}  // namespace luxel::renderer
