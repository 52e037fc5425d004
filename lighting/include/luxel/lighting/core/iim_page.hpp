#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/lighting/core/radiance_atlas.hpp"

namespace luxel::lighting {

/// One texel's fade: when its value was committed and over how many seconds it fades in.
/// Per texel, not one blend time for the map: a texel re-gathered because geometry moved next
/// to it (a crate's footprint) should show its new light within frames, while a refinement
/// pass's small correction fades in slowly so noise does not flicker.
struct IimFade {
    float committed_seconds = -1e30f;
    float fade_seconds = 0.0f;  ///< 0: shown at once
};

/// One page of the indirect illumination map, double-buffered so that a texel's update fades
/// in instead of popping: a texel shows
///     mix(previous, current, clamp((now - committed) / fade, 0, 1)).
/// When a texel is gathered anew, `previous` takes what it showed at that moment and `current`
/// the new value, so a texel updated again mid-fade continues smoothly. The renderer uploads
/// the three arrays for the dirty rectangle of `current` and does the mix in its shader.
struct IimPage {
    RadiancePage previous;
    RadiancePage current;
    std::vector<IimFade> fades;  ///< per texel

    explicit IimPage(int page_size = 0);

    /// What texel (x, y) shows at `now_seconds`.
    [[nodiscard]] glm::vec3 shown(int x, int y, double now_seconds) const;
    /// Starts the fade of texel (x, y) to `value` at `now_seconds`, over `fade_seconds` (0 or
    /// less: at once), or by the end of a shorter fade still in progress; does not mark it
    /// dirty.
    void commit(int x, int y, const glm::vec3& value, double now_seconds, double fade_seconds);
};

}  // namespace luxel::lighting
