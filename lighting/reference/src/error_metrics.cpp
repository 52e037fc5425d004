#include "luxel/lighting/reference/error_metrics.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "luxel/runtime/error.hpp"

namespace luxel::lighting::reference {
namespace {

/// The two sums of relRMSE, accumulated in double; `broken` records a non-finite input.
struct Sums {
    double error = 0.0;
    double signal = 0.0;
    bool broken = false;

    void add(double weight, double estimate, double reference) {
        if (!std::isfinite(estimate) || !std::isfinite(reference)) {
            broken = true;
            return;
        }
        const double difference = estimate - reference;
        error += weight * difference * difference;
        signal += weight * reference * reference;
    }

    [[nodiscard]] double result() const {
        if (broken || !std::isfinite(error) || !std::isfinite(signal)) {
            return std::numeric_limits<double>::infinity();
        }
        if (signal > 0.0) {
            return std::sqrt(error / signal);
        }
        return error > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
    }
};

void check(std::size_t estimate, std::size_t reference, std::size_t weights) {
    if (estimate != reference || estimate != weights) {
        throw Error("relative_rmse: " + std::to_string(estimate) + " values, " +
                    std::to_string(reference) + " reference values and " + std::to_string(weights) +
                    " weights");
    }
}

double checked_weight(double weight) {
    if (!(weight >= 0.0) || !std::isfinite(weight)) {
        throw Error("relative_rmse: weight " + std::to_string(weight) +
                    " is negative or not finite");
    }
    return weight;
}

}  // namespace

double relative_rmse(std::span<const double> estimate, std::span<const double> reference,
                     std::span<const double> weights) {
    check(estimate.size(), reference.size(), weights.size());
    Sums sums;
    for (std::size_t i = 0; i < estimate.size(); ++i) {
        sums.add(checked_weight(weights[i]), estimate[i], reference[i]);
    }
    return sums.result();
}

double relative_rmse(std::span<const glm::dvec3> estimate, std::span<const glm::dvec3> reference,
                     std::span<const double> weights) {
    check(estimate.size(), reference.size(), weights.size());
    Sums sums;
    for (std::size_t i = 0; i < estimate.size(); ++i) {
        const double weight = checked_weight(weights[i]);
        for (int c = 0; c < 3; ++c) {
            sums.add(weight, estimate[i][c], reference[i][c]);
        }
    }
    return sums.result();
}

double image_relative_rmse(const Image& estimate, const Image& reference) {
    if (estimate.width != reference.width || estimate.height != reference.height ||
        estimate.rgba.size() != reference.rgba.size()) {
        throw Error("image_relative_rmse: " + std::to_string(estimate.width) + "x" +
                    std::to_string(estimate.height) + " image against a " +
                    std::to_string(reference.width) + "x" + std::to_string(reference.height) +
                    " reference");
    }
    Sums sums;
    for (std::size_t i = 0; i < estimate.rgba.size(); i += 4) {
        for (std::size_t c = 0; c < 3; ++c) {
            sums.add(1.0, static_cast<double>(estimate.rgba[i + c]),
                     static_cast<double>(reference.rgba[i + c]));
        }
    }
    return sums.result();
}

}  // namespace luxel::lighting::reference
