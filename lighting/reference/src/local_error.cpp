#include "luxel/lighting/reference/local_error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "luxel/runtime/error.hpp"

namespace luxel::lighting::reference {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

struct RegionSums {
    double weight = 0.0;
    double error = 0.0;  ///< sum w |x - r|^2
    std::size_t texels = 0;
};

double squared_difference(const glm::dvec3& x, const glm::dvec3& r) {
    const glm::dvec3 d = x - r;
    return glm::dot(d, d);
}

bool finite(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// The area-weighted p-quantile of `values` (value, weight): the smallest value with at least a
/// fraction p of the total weight at or below it.
double weighted_quantile(std::vector<std::pair<double, double>> values, double p) {
    if (values.empty()) {
        return 0.0;
    }
    std::sort(values.begin(), values.end());
    double total = 0.0;
    for (const auto& [value, weight] : values) {
        total += weight;
    }
    if (!(total > 0.0)) {
        return values.back().first;
    }
    double below = 0.0;
    for (const auto& [value, weight] : values) {
        below += weight;
        if (below >= p * total) {
            return value;
        }
    }
    return values.back().first;
}

LocalError broken() {
    LocalError error;
    error.worst_region = kInfinity;
    error.texel_p99 = kInfinity;
    return error;
}

}  // namespace

LocalError local_error(std::span<const glm::dvec3> estimate, std::span<const glm::dvec3> reference,
                       std::span<const double> weights, std::span<const std::uint32_t> region,
                       std::size_t min_region_texels) {
    const std::size_t n = estimate.size();
    if (reference.size() != n || weights.size() != n || region.size() != n) {
        throw Error("local_error: " + std::to_string(n) + " values, " +
                    std::to_string(reference.size()) + " reference values, " +
                    std::to_string(weights.size()) + " weights and " +
                    std::to_string(region.size()) + " region ids");
    }
    double total_weight = 0.0;
    double signal = 0.0;
    double error = 0.0;
    std::uint32_t regions = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (!(weights[i] >= 0.0) || !std::isfinite(weights[i])) {
            throw Error("local_error: weight " + std::to_string(weights[i]) +
                        " is negative or not finite");
        }
        if (!finite(estimate[i]) || !finite(reference[i])) {
            return broken();
        }
        total_weight += weights[i];
        signal += weights[i] * glm::dot(reference[i], reference[i]);
        error += weights[i] * squared_difference(estimate[i], reference[i]);
        regions = std::max(regions, region[i] + 1);
    }
    LocalError result;
    if (!(signal > 0.0) || !(total_weight > 0.0)) {
        return error > 0.0 ? broken() : result;
    }
    // RMS over the three channels, as relative_rmse sums them.
    const double scale = std::sqrt(signal / total_weight);

    // Region ids are dense in practice (luxel-bench numbers them); a sparse numbering costs
    // memory, not correctness.
    std::vector<RegionSums> sums(regions);
    std::vector<std::pair<double, double>> texel_errors;
    texel_errors.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double d2 = squared_difference(estimate[i], reference[i]);
        RegionSums& s = sums[region[i]];
        s.weight += weights[i];
        s.error += weights[i] * d2;
        ++s.texels;
        texel_errors.emplace_back(std::sqrt(d2) / scale, weights[i]);
    }
    for (std::size_t r = 0; r < sums.size(); ++r) {
        const RegionSums& s = sums[r];
        if (s.texels < min_region_texels || !(s.weight > 0.0)) {
            continue;
        }
        ++result.regions;
        const double value = std::sqrt(s.error / s.weight) / scale;
        if (result.worst_region_id == static_cast<std::size_t>(-1) || value > result.worst_region) {
            result.worst_region = value;
            result.worst_region_id = r;
        }
    }
    result.texel_p99 = weighted_quantile(std::move(texel_errors), 0.99);
    return result;
}

}  // namespace luxel::lighting::reference
