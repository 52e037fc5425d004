#include "soft_shadows.hpp"

#include <string>
#include <vector>

#include "luxel/runtime/shader_library.hpp"
#include "luxel/runtime/texture_sampling.hpp"

namespace luxel::renderer {
namespace {

std::string batch_define() {
    return "#define LIGHTS_PER_BATCH " + std::to_string(LightBatches::kLightsPerBatch) + "\n";
}

}  // namespace

SplitLights split_soft(const std::vector<FrameLight>& lights, const ShadowMaps& shadows,
                       bool enabled) {
    SplitLights split;
    for (const FrameLight& light : lights) {
        const ShadowMap* map = shadows.find(light.entity);
        const bool soft = enabled && light.radius > 0.0f && map != nullptr && map->valid;
        (soft ? split.soft : split.hard).push_back(light);
    }
    return split;
}

SoftShadows::SoftShadows(const ShaderLibrary& shaders)
    : inputs_program_(shaders.build({{ShaderStage::Vertex, "post/fullscreen.vert"},
                                     {ShaderStage::Fragment, "render/soft_shadow_inputs.frag"}},
                                    batch_define())),
      gather_program_(shaders.build({{ShaderStage::Vertex, "post/fullscreen.vert"},
                                     {ShaderStage::Fragment, "render/soft_shadow_gather.frag"}},
                                    batch_define())) {}

void SoftShadows::resize(int width, int height) {
    if (width == width_ && height == height_) {
        return;
    }
    shadow_ = gl::Texture::create_2d(GL_RG32F, width, height);
    gl::set_sampling(shadow_.id(), gl::Sampling::Exact);
    shadow_target_ = gl::Framebuffer::create();
    shadow_target_.attach(GL_COLOR_ATTACHMENT0, shadow_);
    glNamedFramebufferDrawBuffer(shadow_target_.id(), GL_COLOR_ATTACHMENT0);
    shadow_target_.check_complete("soft shadow target");
    width_ = width;
    height_ = height;
}

void SoftShadows::draw(const std::vector<FrameLight>& lights, LightBatches& batches,
                       const ShadowMaps& shadows, const FrameTargets& targets,
                       const FrameCamera& camera, bool filtered) {
    for (const FrameLight& light : lights) {
        draw_one(light, batches, shadows, targets, camera, filtered);
    }
}

void SoftShadows::draw_one(const FrameLight& light, LightBatches& batches,
                           const ShadowMaps& shadows, const FrameTargets& targets,
                           const FrameCamera& camera, bool filtered) {
    resize(targets.width, targets.height);
    batches.bind(std::vector<FrameLight>{light}, 0, shadows);
    glBindTextureUnit(0, targets.albedo.id());
    glBindTextureUnit(1, targets.normal.id());
    glBindTextureUnit(2, targets.position.id());

    glDisable(GL_BLEND);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, shadow_target_.id());
    glViewport(0, 0, width_, height_);
    inputs_program_.use();
    inputs_program_.set("u_filtered", filtered ? 1 : 0);
    glDrawArrays(GL_TRIANGLES, 0, 3);

    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, targets.direct_target.id());
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    gather_program_.use();
    gather_program_.set("u_camera", camera.position);
    // The view direction is the view matrix's third row, negated (GL looks down -z).
    gather_program_.set("u_forward",
                        -glm::vec3(camera.view[0][2], camera.view[1][2], camera.view[2][2]));
    // A perspective projection divides by the view depth (its w row is (0, 0, -1, 0)); an
    // orthographic one keeps w = 1, so a metre spans the same pixels at every depth.
    const bool perspective = camera.projection[2][3] != 0.0f;
    gather_program_.set("u_perspective", perspective ? 1 : 0);
    gather_program_.set("u_pixels_per_metre",
                        camera.projection[1][1] * 0.5f * static_cast<float>(targets.height));
    gather_program_.set("u_radius", light.radius);
    gather_program_.set("u_view_projection", camera.projection * camera.view);
    glBindTextureUnit(3, shadow_.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_BLEND);
}

}  // namespace luxel::renderer
