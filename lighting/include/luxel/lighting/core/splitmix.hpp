#pragma once

#include <cstdint>

namespace luxel::lighting {

/// One step of splitmix64 (Steele, Lea & Flood, "Fast splittable pseudorandom number
/// generators", OOPSLA 2014): advances `state` and returns a well-mixed 64-bit number. Nearly
/// equal states (consecutive passes, neighbouring probes or texels) give unrelated numbers, the
/// same on every run and platform: what the irradiance probes' and the hemi-plane's per-pass
/// rotations are drawn from.
[[nodiscard]] inline std::uint64_t splitmix64(std::uint64_t& state) {
    state += 0x9e3779b97f4a7c15ull;
    std::uint64_t z = state;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/// A number in [0, 1) from the top 24 bits of `bits` (exact in a float).
[[nodiscard]] inline float unit_interval(std::uint64_t bits) {
    return static_cast<float>(bits >> 40) / static_cast<float>(1ull << 24);
}

}  // namespace luxel::lighting
