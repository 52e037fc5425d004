#pragma once

// Reference light maps for luxel-bench: computed with the reference integrator (indirect by
// IndirectPhotons) and cached on disk, keyed by level, pose and reference settings.

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bench_options.hpp"
#include "luxel/lighting/reference/reference_integrator.hpp"
#include "luxel/lighting/reference/reference_scene.hpp"
#include "luxel/runtime/jobs.hpp"

namespace luxel::bench {

/// Per-texel reference irradiance in the ReferenceScene's global texel order.
struct ReferenceMaps {
    std::string key;   ///< what the cache entry is for (level, pose, settings, texels)
    std::string hash;  ///< FNV-1a of the key: the cache file's name
    std::vector<double> area;
    std::array<std::vector<glm::dvec3>, 3> value;  ///< direct, indirect, caustic (W/m^2)
    std::array<double, 3> relative_standard_error{};
    double seconds = 0.0;  ///< to compute it
    bool from_cache = false;

    [[nodiscard]] const std::vector<glm::dvec3>& indirect() const { return value[1]; }
    [[nodiscard]] const std::vector<glm::dvec3>& caustic() const { return value[2]; }
};

/// FNV-1a of a cache key as 16 hex digits: the cache file's name.
[[nodiscard]] std::string cache_hash(const std::string& key);

/// The integrator's settings for a reference of `spec` (seeds, photon-estimated indirect):
/// one definition for the light-map and the frame references.
[[nodiscard]] lighting::reference::ReferenceSettings reference_settings(const ReferenceSpec& spec);

/// The reference for `scene` in the pose `pose` (a description of level and state that the
/// caller guarantees identifies the scene): read from `cache_dir`/<hash>.json when present and
/// matching, else computed and written there. Logs which to stderr.
[[nodiscard]] ReferenceMaps reference_for(const std::filesystem::path& cache_dir,
                                          const std::string& pose,
                                          const lighting::reference::ReferenceScene& scene,
                                          const ReferenceSpec& spec, JobSystem& jobs);

}  // namespace luxel::bench
