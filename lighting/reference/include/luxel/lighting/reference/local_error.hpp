#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include <glm/glm.hpp>

/// Error where a user would see it (docs/METHOD.md §10.2): a global relRMSE over every texel of
/// a level cannot see one plainly wrong patch (a dark footprint where an object stood), so the
/// light maps are also judged region by region and texel by texel. Both measures are in units
/// of the level's RMS reference value, the relRMSE's own denominator, so that a dim region's
/// noise does not outweigh a bright region's real defect, and the global relRMSE is the
/// area-weighted RMS of the region errors.
namespace luxel::lighting::reference {

struct LocalError {
    /// The largest region error: sqrt(sum_region w |x - r|^2 / sum_region w) over the level's
    /// RMS reference, sqrt(sum_all w |r|^2 / sum_all w). Regions with fewer than the minimum
    /// texels are left out (a sliver at a chart's edge is a few texels' noise).
    double worst_region = 0.0;
    /// The region it was found in (its id as given); SIZE_MAX when no region counted.
    std::size_t worst_region_id = static_cast<std::size_t>(-1);
    /// The 99th percentile, by area, of the texels' |x - r| over the level's RMS reference.
    double texel_p99 = 0.0;
    std::size_t regions = 0;  ///< regions that counted
};

/// The local error of an estimate against a reference, texels grouped by `region` (one id per
/// texel, any numbering; light-map texels are grouped by 8x8 page blocks per surface by
/// luxel-bench). Throws luxel::Error when the spans differ in length or a weight is negative or
/// not finite. Guarded like relative_rmse: 0 when the reference and the estimate are black;
/// +infinity when the reference is black where the estimate is not, or a value is not finite.
[[nodiscard]] LocalError local_error(std::span<const glm::dvec3> estimate,
                                     std::span<const glm::dvec3> reference,
                                     std::span<const double> weights,
                                     std::span<const std::uint32_t> region,
                                     std::size_t min_region_texels = 16);

}  // namespace luxel::lighting::reference
