#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "frame_lights.hpp"
#include "luxel/runtime/gl_objects.hpp"
#include "shadow_maps.hpp"

namespace luxel::renderer {

/// Feeds shaders/render/direct_lights.glsl: the lights in batches of kLightsPerBatch, each
/// batch one uniform block; the shadow maps of every light are bound once, as ShadowMaps' two
/// array textures on units 4 (cubes) and 8 (2D), each light's record naming its layer. Passes
/// that need every light draw one batch after another, blended additively.
class LightBatches {
  public:
    static constexpr std::size_t kLightsPerBatch = 4;

    LightBatches();

    [[nodiscard]] static std::size_t batch_count(std::size_t lights) {
        return (lights + kLightsPerBatch - 1) / kLightsPerBatch;
    }
    /// Uploads batch `batch` of `lights` and binds it with the shadow maps. A shape with no map
    /// gets a 1 x 1 unused array, so both samplers always have a complete texture.
    void bind(const std::vector<FrameLight>& lights, std::size_t batch, const ShadowMaps& shadows);

    /// The shadow-map shapes the lights of `batch` read, as bind() describes them: kCubeShadows,
    /// kMapShadows (a perspective or orthographic map), or neither. direct_lights.glsl's
    /// variants compile the other shape out.
    static constexpr std::uint32_t kCubeShadows = 1u;
    static constexpr std::uint32_t kMapShadows = 2u;
    [[nodiscard]] static std::uint32_t shadow_shapes(const std::vector<FrameLight>& lights,
                                                     std::size_t batch, const ShadowMaps& shadows);

  private:
    gl::Buffer block_;
    gl::Texture unused_cube_;
    gl::Texture unused_map_;
};

}  // namespace luxel::renderer
