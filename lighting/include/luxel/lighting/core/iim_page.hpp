#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/lighting/core/radiance_atlas.hpp"

namespace luxel::lighting {

/// One page of the indirect illumination map, double-buffered so that a texel's update fades
/// in over the blend time instead of popping: a texel shows
///     mix(previous, current, clamp((now - committed) / blend, 0, 1)).
/// When a texel is gathered anew, `previous` takes what it showed at that moment and `current`
/// the new value, so a texel updated again mid-fade continues smoothly. The renderer uploads
/// the three arrays for the dirty rectangle of `current` and does the mix in its shader.
struct IimPage {
    RadiancePage previous;
    RadiancePage current;
    std::vector<float> committed_seconds;  ///< per texel

    explicit IimPage(int page_size = 0);

    /// What texel (x, y) shows at `now_seconds` with a blend time of `blend_seconds`.
    [[nodiscard]] glm::vec3 shown(int x, int y, double now_seconds, double blend_seconds) const;
    /// Starts the fade of texel (x, y) to `value` at `now_seconds` (does not mark it dirty).
    void commit(int x, int y, const glm::vec3& value, double now_seconds, double blend_seconds);
};

}  // namespace luxel::lighting
