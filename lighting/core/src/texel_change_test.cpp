#include "luxel/lighting/core/texel_change_test.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace luxel::lighting {
namespace {

/// The surface's texels on a dense rectangle of the page (its bounds), where the tent sums run.
struct Rect {
    int x0 = 0;
    int y0 = 0;
    int width = 0;
    int height = 0;

    explicit Rect(const std::vector<SurfaceTexel>& texels) {
        if (texels.empty()) {
            return;
        }
        int x1 = texels[0].x;
        int y1 = texels[0].y;
        x0 = x1;
        y0 = y1;
        for (const SurfaceTexel& texel : texels) {
            x0 = std::min(x0, texel.x);
            y0 = std::min(y0, texel.y);
            x1 = std::max(x1, texel.x);
            y1 = std::max(y1, texel.y);
        }
        width = x1 - x0 + 1;
        height = y1 - y0 + 1;
    }
    [[nodiscard]] std::size_t size() const {
        return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    }
    [[nodiscard]] std::size_t at(const SurfaceTexel& texel) const {
        return static_cast<std::size_t>(texel.y - y0) * static_cast<std::size_t>(width) +
               static_cast<std::size_t>(texel.x - x0);
    }
};

/// Sums `values` over the separable kernel k(dx) k(dy), k(d) = (radius + 1 - |d|)^power, along
/// x then y (power 1: the tent, 2: its square for variances, 0: a box).
template <typename T>
std::vector<T> kernel_sums(const std::vector<T>& values, const Rect& rect, int radius, int power) {
    std::vector<double> kernel(static_cast<std::size_t>(2 * radius + 1));
    for (int d = -radius; d <= radius; ++d) {
        kernel[static_cast<std::size_t>(d + radius)] =
            std::pow(static_cast<double>(radius + 1 - std::abs(d)), power);
    }
    const auto index = [&rect](int x, int y) {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(rect.width) +
               static_cast<std::size_t>(x);
    };
    std::vector<T> along_x(values.size(), T(0.0));
    for (int y = 0; y < rect.height; ++y) {
        for (int x = 0; x < rect.width; ++x) {
            T sum(0.0);
            for (int d = std::max(-radius, -x); d <= std::min(radius, rect.width - 1 - x); ++d) {
                sum += kernel[static_cast<std::size_t>(d + radius)] * values[index(x + d, y)];
            }
            along_x[index(x, y)] = sum;
        }
    }
    std::vector<T> out(values.size(), T(0.0));
    for (int y = 0; y < rect.height; ++y) {
        for (int x = 0; x < rect.width; ++x) {
            T sum(0.0);
            for (int d = std::max(-radius, -y); d <= std::min(radius, rect.height - 1 - y); ++d) {
                sum += kernel[static_cast<std::size_t>(d + radius)] * along_x[index(x, y + d)];
            }
            out[index(x, y)] = sum;
        }
    }
    return out;
}

}  // namespace

std::vector<std::uint8_t> texels_changed(const std::vector<SurfaceTexel>& texels,
                                         const std::vector<glm::vec3>& pass,
                                         const RefinementStats& refinement, int radius,
                                         double sigmas) {
    const std::size_t count = texels.size();
    std::vector<std::uint8_t> changed(count, 1);
    const bool stats_whole = pass.size() == count && refinement.mean.size() == count &&
                             refinement.texel_passes.size() == count &&
                             refinement.relative_pass_variance.size() == count;
    if (!stats_whole || count == 0 || !(sigmas > 0.0)) {
        return changed;  // nothing to compare with: every texel restarts
    }
    const Rect rect(texels);
    // Per texel: the difference of the pass from the mean, its variance (one pass's noise plus
    // the mean's: pass_variance (1 + 1/n)), presence, and whether its noise is unknown.
    std::vector<glm::dvec3> difference(rect.size(), glm::dvec3(0.0));
    std::vector<double> variance(rect.size(), 0.0);
    std::vector<double> present(rect.size(), 0.0);
    std::vector<double> unknown(rect.size(), 0.0);
    for (std::size_t i = 0; i < count; ++i) {
        const std::size_t at = rect.at(texels[i]);
        const glm::dvec3 mean(refinement.mean[i]);
        const glm::dvec3 value(pass[i]);
        const std::uint32_t n = refinement.texel_passes[i];
        const double relative = refinement.relative_pass_variance[i];
        difference[at] = value - mean;
        present[at] = 1.0;
        const bool finite =
            std::isfinite(value.x + value.y + value.z) && std::isfinite(mean.x + mean.y + mean.z);
        if (n == 0 || !(relative >= 0.0) || !finite) {
            unknown[at] = 1.0;
            difference[at] = glm::dvec3(0.0);
            continue;
        }
        variance[at] = relative * glm::dot(mean, mean) * (1.0 + 1.0 / static_cast<double>(n));
    }
    const std::vector<glm::dvec3> d_sum = kernel_sums(difference, rect, radius, 1);
    const std::vector<double> w_sum = kernel_sums(present, rect, radius, 1);
    const std::vector<double> v_sum = kernel_sums(variance, rect, radius, 2);
    const std::vector<double> u_sum = kernel_sums(unknown, rect, radius, 0);
    const double k2 = sigmas * sigmas;
    // The kept texels' own differences, summed, for the test of a change no neighbourhood
    // resolves.
    glm::dvec3 kept_difference(0.0);
    double kept_variance = 0.0;
    double kept = 0.0;
    for (std::size_t i = 0; i < count; ++i) {
        const std::size_t at = rect.at(texels[i]);
        const double w = w_sum[at];
        if (u_sum[at] > 0.0 || !(w > 0.0)) {
            continue;  // changed: a neighbour's noise is unknown
        }
        // D = sum(t d) / sum(t); Var(D) = sum(t^2 var) / sum(t)^2.
        const glm::dvec3 mean_difference = d_sum[at] / w;
        const double mean_variance = v_sum[at] / (w * w);
        const double squared = glm::dot(mean_difference, mean_difference);
        if (squared > k2 * mean_variance) {
            continue;
        }
        changed[i] = 0;
        kept_difference += difference[at];
        kept_variance += variance[at];
        kept += 1.0;
    }
    if (kept > 0.0) {
        const glm::dvec3 mean_difference = kept_difference / kept;
        if (glm::dot(mean_difference, mean_difference) > k2 * kept_variance / (kept * kept)) {
            std::fill(changed.begin(), changed.end(), std::uint8_t{1});
        }
    }
    return changed;
}

}  // namespace luxel::lighting
