#pragma once

// luxel-bench's command line, parsed and checked.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace luxel::bench {

/// One --sweep KNOB=V1,V2,...: the knob and its values as given (checked by parse_sweep).
struct Sweep {
    std::string knob;
    std::vector<std::string> values;
};

/// The scripted change: a node moved by an offset once the static run has converged.
struct Change {
    std::string node;
    glm::vec3 offset{0.0f};
};

/// The reference's size: what the cache key holds besides the level and the pose.
struct ReferenceSpec {
    std::uint64_t indirect_photons = 100'000'000;
    std::uint64_t caustic_photons = 10'000'000;
    std::uint32_t spp = 16;  ///< path samples per texel (direct component, area-light caustics)
    std::uint32_t seed = 1;
};

struct Options {
    std::string level;
    std::vector<double> budgets{1.0, 2.0, 4.0, 8.0};
    std::uint32_t frames = 150;     ///< static frames per configuration
    std::uint32_t after = 90;       ///< frames after the scripted change
    std::uint32_t checkpoint = 30;  ///< static frames between error measurements
    std::filesystem::path out = "bench-out";
    std::vector<Sweep> sweeps;
    std::string change = "auto";  ///< NODE:dx,dy,dz, "auto" or "none"
    std::optional<Change> parsed_change;
    double time = 0.0;       ///< the animation pose (frozen)
    double dt = 1.0 / 30.0;  ///< seconds per frame (IIM fade-in)
    ReferenceSpec reference;
    int threads = 0;
    bool dump_maps = false;  ///< per-texel JSON of every run in OUT/maps
};

/// Parses KNOB=V1,V2,... (knobs: budget, photons GxM, aim_n, rays, texels_per_unit,
/// caustics NxK). Throws luxel::Error naming the flag and what is wrong.
[[nodiscard]] Sweep parse_sweep(const std::string& text);
/// Parses NODE:dx,dy,dz. Throws luxel::Error.
[[nodiscard]] Change parse_change(const std::string& text);
/// Parses "1,2,4" into numbers > 0. Throws luxel::Error.
[[nodiscard]] std::vector<double> parse_budgets(const std::string& text);
/// Checks ranges CLI11 cannot. Throws luxel::Error.
void validate(const Options& options);

}  // namespace luxel::bench
