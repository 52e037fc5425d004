#pragma once

#include <cstdint>

#include <glm/glm.hpp>

/// Counter-based random numbers for the reference integrator. A stream is keyed by (seed,
/// item, sample), so every texel's or pixel's samples are the same whatever thread draws them
/// and in whatever order: a reference is deterministic for a seed.
namespace luxel::lighting::reference {

/// SplitMix64's finaliser: a bijective 64-bit mix with full avalanche.
[[nodiscard]] constexpr std::uint64_t mix64(std::uint64_t x) {
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

/// Independent uniform numbers in [0, 1) (pseudo-random, not QMC: the per-sample variance the
/// integrator reports as its standard error is only valid for independent samples).
class SampleStream {
  public:
    SampleStream(std::uint64_t seed, std::uint64_t item, std::uint64_t sample)
        : state_(mix64(mix64(mix64(seed) ^ item) + sample)) {}

    [[nodiscard]] double next() {
        state_ += 0x9E3779B97F4A7C15ull;  // SplitMix64's Weyl step
        return static_cast<double>(mix64(state_) >> 11) * 0x1.0p-53;
    }
    [[nodiscard]] glm::dvec2 next2() {
        const double u = next();
        return {u, next()};
    }

  private:
    std::uint64_t state_;
};

}  // namespace luxel::lighting::reference
