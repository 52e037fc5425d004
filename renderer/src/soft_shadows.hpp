#pragma once

#include <vector>

#include "frame_lights.hpp"
#include "frame_targets.hpp"
#include "light_batches.hpp"
#include "luxel/renderer/frame_camera.hpp"
#include "luxel/runtime/gl_objects.hpp"
#include "luxel/runtime/program.hpp"
#include "shadow_maps.hpp"

namespace luxel {
class ShaderLibrary;
}

namespace luxel::renderer {

/// A frame's lights split by who draws them: `soft`, those with a radius and a shadow map to
/// soften (while soft shadows are `enabled`), by SoftShadows; `hard`, the rest, by the direct
/// pass.
struct SplitLights {
    std::vector<FrameLight> hard;
    std::vector<FrameLight> soft;
};
[[nodiscard]] SplitLights split_soft(const std::vector<FrameLight>& lights,
                                     const ShadowMaps& shadows, bool enabled);

/// The direct light of lights with a radius, with soft shadows by image-space gathering
/// (R.-H. Yao's thesis; docs/METHOD.md §8.8): per light, its hard shadow and the nearest
/// occluder's distance per pixel (shaders/render/soft_shadow_inputs.frag) into a target of its
/// own, then that shadow averaged over the penumbra's width around each pixel and added to the
/// direct term (soft_shadow_gather.frag). FrameRenderer makes one only when a frame has such a
/// light, so levels of point lights allocate and run nothing for it.
class SoftShadows {
  public:
    explicit SoftShadows(const ShaderLibrary& shaders);

    /// Adds each light's direct light to targets.direct_target (which the caller has cleared
    /// and filled with the other lights). The caller binds the empty vertex array and restores
    /// state (FrameRenderer's StateGuard); `filtered` as FrameSettings::filtered_shadows.
    void draw(const std::vector<FrameLight>& lights, LightBatches& batches,
              const ShadowMaps& shadows, const FrameTargets& targets, const FrameCamera& camera,
              bool filtered);

  private:
    void draw_one(const FrameLight& light, LightBatches& batches, const ShadowMaps& shadows,
                  const FrameTargets& targets, const FrameCamera& camera, bool filtered);
    void resize(int width, int height);

    gl::Program inputs_program_;
    gl::Program gather_program_;
    gl::Texture shadow_;  ///< RG32F: lit, occluder gap (m, -1: none)
    gl::Framebuffer shadow_target_;
    int width_ = 0;
    int height_ = 0;
};

}  // namespace luxel::renderer
