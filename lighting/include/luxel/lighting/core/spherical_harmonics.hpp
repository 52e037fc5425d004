#pragma once

#include <array>
#include <cstddef>

#include <glm/glm.hpp>

namespace luxel::lighting {

/// Real spherical harmonics of bands 0-2 (nine functions), the irradiance probes' basis.
/// Radiance projected onto them and convolved with the clamped cosine gives irradiance to
/// within a few per cent for any lighting (Ramamoorthi & Hanrahan, "An Efficient
/// Representation for Irradiance Environment Maps", SIGGRAPH 2001): the cosine lobe has almost
/// no energy above band 2, so nine numbers per channel are what engines store per probe.
inline constexpr std::size_t kShCoefficients = 9;

/// The nine basis functions at unit direction `d`, in the order (l, m) = (0,0), (1,-1), (1,0),
/// (1,1), (2,-2), (2,-1), (2,0), (2,1), (2,2).
using ShBasis = std::array<float, kShCoefficients>;
[[nodiscard]] ShBasis sh_basis(const glm::vec3& d);

/// Nine RGB coefficients.
struct ShRgb {
    std::array<glm::vec3, kShCoefficients> c{};
};

/// The cosine convolution folded into radiance coefficients: irradiance E(n) is then
/// sum_i result.c[i] * Y_i(n) (band l scaled by A_l = pi, 2 pi / 3, pi / 4).
[[nodiscard]] ShRgb convolve_cosine(const ShRgb& radiance);

/// sum_i c[i] * Y_i(n), clamped at 0: band-2 ringing can make a tiny negative value behind a
/// very bright, very small source, and light is never negative.
[[nodiscard]] glm::vec3 evaluate(const ShRgb& coefficients, const glm::vec3& n);

}  // namespace luxel::lighting
