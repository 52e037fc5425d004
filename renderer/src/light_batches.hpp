#pragma once

#include <cstddef>
#include <vector>

#include "frame_lights.hpp"
#include "luxel/runtime/gl_objects.hpp"
#include "shadow_maps.hpp"

namespace luxel::renderer {

/// Feeds shaders/render/direct_lights.glsl: the lights in batches of kLightsPerBatch, each
/// batch one uniform block plus its shadow maps on texture units 4-7 (cube) and 8-11 (2D).
/// Four lights a batch keep the direct shader within GL 4.5's 16 guaranteed texture units
/// alongside the G-buffer's; passes that need every light draw one batch after another,
/// blended additively.
class LightBatches {
  public:
    static constexpr std::size_t kLightsPerBatch = 4;

    LightBatches();

    [[nodiscard]] static std::size_t batch_count(std::size_t lights) {
        return (lights + kLightsPerBatch - 1) / kLightsPerBatch;
    }
    /// Uploads batch `batch` of `lights` and binds it with its shadow maps. Slots a light does
    /// not use get 1 x 1 unused maps, so every sampler always has a complete texture.
    void bind(const std::vector<FrameLight>& lights, std::size_t batch, const ShadowMaps& shadows);

  private:
    gl::Buffer block_;
    gl::Texture unused_cube_;
    gl::Texture unused_map_;
};

}  // namespace luxel::renderer
