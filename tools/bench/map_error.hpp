#pragma once

// The real-time light maps as irradiance per reference texel, and their error (docs/METHOD.md
// §10.2).

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/lighting/core/lighting_system.hpp"
#include "luxel/lighting/reference/reference_scene.hpp"
#include "reference_cache.hpp"

namespace luxel::bench {

/// What the real-time path holds for each reference texel (global order), W/m^2.
struct RealTimeMaps {
    /// The IIM as shown at the time asked (fade-in included), as irradiance: Radiance-content
    /// texels hold albedo * E / pi and are divided back.
    std::vector<glm::dvec3> indirect;
    /// Caustic photons binned into the texel under each (power / texel area): the reference's
    /// own binning, so both are texel-area means.
    std::vector<glm::dvec3> caustic;
    /// The AIM at each texel as irradiance (its pages hold albedo * E / pi, divided back): what
    /// the photons say reaches the texel, direct and caustic light included, to compare with
    /// the reference's direct + indirect + caustic (--dump-maps; the gathers read the AIM, so a
    /// bias here is a bias in every IIM that sees the surface).
    std::vector<glm::dvec3> aim;
    std::size_t caustic_photons = 0;
    std::size_t caustic_unbinned = 0;  ///< on a surface without a light map, or lost
};

[[nodiscard]] RealTimeMaps read_real_time(const lighting::LightingSystem& lighting,
                                          const lighting::reference::ReferenceScene& scene,
                                          double now_seconds);

struct MapErrors {
    double indirect = 0.0;  ///< relRMSE, texel areas as weights
    double caustic = 0.0;
    /// The indirect light's local error (lighting::reference::local_error): the worst 8x8-texel
    /// region of a surface, and the 99th-percentile texel, in units of the level's RMS
    /// reference indirect irradiance.
    double indirect_region = 0.0;
    double indirect_p99 = 0.0;
};

/// The side of the square page blocks the local error groups texels by.
inline constexpr int kRegionTexels = 8;

/// Per reference texel (global order), the id of its region: the kRegionTexels-square block of
/// its page it lies in, per surface (so a region never mixes two surfaces), numbered densely.
[[nodiscard]] std::vector<std::uint32_t> texel_regions(
    const lighting::reference::ReferenceScene& scene);

[[nodiscard]] MapErrors map_errors(const RealTimeMaps& maps, const ReferenceMaps& reference,
                                   const std::vector<std::uint32_t>& regions);

/// Per texel: surface, x, y, area, and real-time and reference indirect and caustic (and the
/// reference's direct, and the real-time AIM), for looking at where an error comes from
/// (--dump-maps).
void write_maps_json(const std::filesystem::path& path,
                     const lighting::reference::ReferenceScene& scene, const RealTimeMaps& maps,
                     const ReferenceMaps& reference);

}  // namespace luxel::bench
