#pragma once

#include <span>

#include <glm/glm.hpp>

#include "luxel/runtime/image.hpp"

/// The error measures of docs/METHOD.md §10.2.
namespace luxel::lighting::reference {

/// relRMSE = sqrt(sum_t w_t (x_t - r_t)^2 / sum_t w_t r_t^2): the area-weighted relative RMS
/// error of light-map texels (w_t = texel area) or of pixels (w_t = 1). Throws luxel::Error
/// when the spans differ in length or a weight is negative or not finite. Guarded: 0 when both
/// sums are 0 (nothing to light, nothing lit); +infinity when the reference is black where the
/// estimate is not, or when any value is NaN or infinite (a broken estimate must not pass a
/// threshold).
[[nodiscard]] double relative_rmse(std::span<const double> estimate,
                                   std::span<const double> reference,
                                   std::span<const double> weights);
/// The same over RGB values: each texel's three channels are summed in both sums.
[[nodiscard]] double relative_rmse(std::span<const glm::dvec3> estimate,
                                   std::span<const glm::dvec3> reference,
                                   std::span<const double> weights);
/// Image relRMSE of a linear HDR frame against a reference frame of the same camera: RGB of
/// every pixel, equal weights (alpha ignored). Throws luxel::Error when the sizes differ.
[[nodiscard]] double image_relative_rmse(const Image& estimate, const Image& reference);

}  // namespace luxel::lighting::reference
