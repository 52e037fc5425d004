#include "composite_pass.hpp"

#include <glm/glm.hpp>

#include "luxel/runtime/shader_library.hpp"
#include "stencil_mask.hpp"

namespace luxel::renderer {
namespace {

// Bits of the composite's variants, in the order of its features.
constexpr std::uint32_t kCausticLayer = 1u;
constexpr std::uint32_t kSky = 2u;
constexpr std::uint32_t kSkyMask = 4u;

}  // namespace

CompositePass::CompositePass(const ShaderLibrary& shaders)
    : programs_(shaders, "post/fullscreen.vert", "render/composite.frag",
                {"CAUSTIC_LAYER", "SKY", "SKY_MASK"}),
      fill_mask_(shaders.build({{ShaderStage::Vertex, "post/fullscreen.vert"},
                                {ShaderStage::Fragment, "render/sky_fill_mask.frag"}})) {}

void CompositePass::run(FrameTargets& targets, GLuint framebuffer, const FrameCamera& camera,
                        const CompositeInputs& in) {
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
    glViewport(0, 0, targets.width, targets.height);
    const bool caustic = in.caustics != 0;
    const bool layer = caustic && in.caustic_layer != nullptr && in.lightmaps != nullptr;
    const bool sky = in.sky != 0;
    const bool masked = in.sky_mask != 0 && in.sky_mask_scale > 0;
    if (layer) {
        in.lightmaps->bind();  // the page sizes
        in.caustic_layer->bind();
    }
    glBindTextureUnit(0, targets.albedo.id());
    glBindTextureUnit(2, targets.position.id());
    glBindTextureUnit(3, targets.lightmap.id());
    glBindTextureUnit(4, targets.emission.id());
    glBindTextureUnit(5, targets.direct.id());
    glBindTextureUnit(6, targets.indirect.id());
    glBindTextureUnit(7, caustic ? in.caustics : in.black);
    glBindTextureUnit(8, in.specular ? targets.specular_term.id() : in.black);
    glBindTextureUnit(9, sky ? in.sky : in.black);
    glBindTextureUnit(10, masked ? in.sky_mask : in.black);

    const glm::mat4 inverse_view_projection = glm::inverse(camera.projection * camera.view);
    const auto draw = [&](std::uint32_t variant) {
        const gl::Program& program = programs_.get(variant);
        program.use();
        program.set("u_terms", glm::vec4(in.direct ? 1.0f : 0.0f, in.indirect ? 1.0f : 0.0f,
                                         caustic ? 1.0f : 0.0f, in.specular ? 1.0f : 0.0f));
        program.set("u_emission_on", in.emission ? 1.0f : 0.0f);
        program.set("u_caustics_irradiance", in.caustics_irradiance ? 1 : 0);
        program.set("u_caustic_layer", layer ? 1 : 0);
        program.set("u_sky_on", sky ? 1 : 0);
        program.set("u_inverse_view_projection", inverse_view_projection);
        program.set("u_camera", camera.position);
        program.set("u_viewport", glm::vec2(static_cast<float>(targets.width),
                                            static_cast<float>(targets.height)));
        program.set("u_coverage_scale", masked ? in.sky_mask_scale : 0);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    };
    const std::uint32_t variant = (layer ? kCausticLayer : 0u) | (sky ? kSky : 0u);
    draw(variant);
    if (!masked) {
        return;
    }
    // The pixels the mask mixes, marked in the stencil, then drawn again with the mixing.
    targets.ensure_stencil();
    shade_marked(
        framebuffer,
        [&] {
            fill_mask_.use();
            fill_mask_.set("u_sky_on", sky ? 1 : 0);
            fill_mask_.set("u_coverage_scale", in.sky_mask_scale);
            glDrawArrays(GL_TRIANGLES, 0, 3);
        },
        [&] { draw(variant | kSkyMask); });
}

}  // namespace luxel::renderer
