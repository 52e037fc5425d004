#pragma once

#include <cstdint>

#include <glm/glm.hpp>

/// Quasi-Monte Carlo points (docs/METHOD.md §2). Photon i of a light always gets the same sample,
/// so a retraced photon follows the same initial direction and results do not depend on threads.
namespace luxel::lighting {

/// The radical inverse Phi_b(i) = sum_j a_j(i) b^(-j-1), where a_j(i) are the base-b digits of
/// i. In [0, 1); computed in double so that indices up to 2^32 keep full float resolution.
[[nodiscard]] inline double radical_inverse(std::uint32_t base, std::uint64_t index) {
    const double inverse_base = 1.0 / static_cast<double>(base);
    double weight = inverse_base;
    double result = 0.0;
    while (index > 0) {
        result += static_cast<double>(index % base) * weight;
        index /= base;
        weight *= inverse_base;
    }
    return result;
}

/// The 2D Halton point of index i with the prime bases 2 and 3.
[[nodiscard]] inline glm::dvec2 halton2(std::uint64_t index) {
    return {radical_inverse(2, index), radical_inverse(3, index)};
}

}  // namespace luxel::lighting
