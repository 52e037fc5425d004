#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/lighting/core/map_surface.hpp"
#include "luxel/lighting/core/surface_texels.hpp"

namespace luxel::lighting {

/// Which texels' light a new full gather pass shows changed, against the mean of the passes
/// they have averaged (docs/METHOD.md §6.9). A pass that the photons' change starts
/// (delta_i over the threshold) used to restart every texel of the surface at one pass, even
/// the texels the change never reached: 90 frames after cornell's cube moved at 4 ms, the
/// light maps were back to single, noisier passes almost everywhere (docs/RESULTS.md). Here a
/// texel restarts only where the new pass disagrees with its mean by more than the noise
/// explains; the others fold the pass into their mean and keep their refinement.
///
/// One texel's difference is too noisy to decide on (a 64-ray gather is 10-20% noisy), so the
/// test is over a neighbourhood: the tent-weighted mean difference D of the texels within
/// `radius` texels, against its variance from each texel's measured noise (the pass's and
/// the mean's). A texel is changed where |D|^2 > sigmas^2 Var(D), or where any texel of its
/// neighbourhood has no noise measured yet. The tent sums are separable: two passes over the
/// surface's rectangle, O(texels x radius), so a large surface's test costs about what
/// filtering it does. A uniform change that no neighbourhood resolves (the whole surface a few
/// percent brighter) is caught by the same test over every texel the neighbourhoods kept.
[[nodiscard]] std::vector<std::uint8_t> texels_changed(const std::vector<SurfaceTexel>& texels,
                                                       const std::vector<glm::vec3>& pass,
                                                       const RefinementStats& refinement,
                                                       int radius, double sigmas);

}  // namespace luxel::lighting
