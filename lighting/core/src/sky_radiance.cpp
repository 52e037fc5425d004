#include "luxel/lighting/core/sky_radiance.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/constants.hpp>

#include "luxel/runtime/error.hpp"

namespace luxel::lighting {
namespace {

constexpr double kPi = glm::pi<double>();

glm::vec3 sanitized(const glm::vec3& v) {
    glm::vec3 out;
    for (int c = 0; c < 3; ++c) {
        out[c] =
            std::isfinite(v[c]) && v[c] > 0.0f ? std::min(v[c], SkyRadiance::kMaxRadiance) : 0.0f;
    }
    return out;
}

/// What a cell's radiance weighs in sampling: its channels summed, as EmissionPieces weigh
/// an emitter's pieces, so every sample of one colour carries the same radiance / pdf.
double weight_of(const glm::vec3& radiance) {
    return static_cast<double>(radiance.r) + static_cast<double>(radiance.g) +
           static_cast<double>(radiance.b);
}

}  // namespace

SkyRadiance::SkyRadiance() : cells_(1, glm::vec3(0.0f)), cdf_(1, 0.0) {}

SkyRadiance::SkyRadiance(int width, int height, std::vector<glm::vec3> cells)
    : width_(width), height_(height), cells_(std::move(cells)) {
    if (width <= 0 || height <= 0 ||
        static_cast<std::size_t>(width) > kMaxCells / static_cast<std::size_t>(height)) {
        throw Error("sky: a grid of " + std::to_string(width) + " x " + std::to_string(height) +
                    " cells is empty or larger than the " + std::to_string(kMaxCells) +
                    " cells a sky may have");
    }
    const std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    if (cells_.size() != count) {
        throw Error("sky: " + std::to_string(cells_.size()) + " radiances for a grid of " +
                    std::to_string(count) + " cells");
    }
    cdf_.resize(count);
    double running = 0.0;
    for (int row = 0; row < height_; ++row) {
        const double omega = solid_angle(row);
        for (int col = 0; col < width_; ++col) {
            const std::size_t i = static_cast<std::size_t>(row) * static_cast<std::size_t>(width_) +
                                  static_cast<std::size_t>(col);
            cells_[i] = sanitized(cells_[i]);
            running += weight_of(cells_[i]) * omega;
            integral_ += glm::dvec3(cells_[i]) * omega;
            cdf_[i] = running;
        }
    }
    total_weight_ = running;
    if (total_weight_ > 0.0) {
        for (double& c : cdf_) {
            c /= total_weight_;
        }
    }
}

SkyRadiance SkyRadiance::uniform(const glm::vec3& radiance) {
    return SkyRadiance(1, 2, {radiance, glm::vec3(0.0f)});
}

double SkyRadiance::solid_angle(int row) const {
    const double top = std::cos(kPi * row / height_);
    const double bottom = std::cos(kPi * (row + 1) / height_);
    return (top - bottom) * 2.0 * kPi / width_;
}

std::size_t SkyRadiance::cell_of(const glm::vec3& unit) const {
    const double theta = std::acos(std::clamp(static_cast<double>(unit.y), -1.0, 1.0));
    const int row = std::min(height_ - 1, static_cast<int>(theta / kPi * height_));
    double phi = std::atan2(static_cast<double>(unit.z), static_cast<double>(unit.x));
    if (phi < 0.0) {
        phi += 2.0 * kPi;
    }
    const int col = std::clamp(static_cast<int>(phi / (2.0 * kPi) * width_), 0, width_ - 1);
    return static_cast<std::size_t>(row) * static_cast<std::size_t>(width_) +
           static_cast<std::size_t>(col);
}

glm::vec3 SkyRadiance::radiance(const glm::vec3& towards_sky) const {
    const float length = glm::length(towards_sky);
    if (!(length > 0.0f) || !std::isfinite(length)) {
        return glm::vec3(0.0f);
    }
    return cells_[cell_of(towards_sky / length)];
}

double SkyRadiance::pdf(const glm::vec3& towards_sky) const {
    const float length = glm::length(towards_sky);
    if (black() || !(length > 0.0f) || !std::isfinite(length)) {
        return 0.0;
    }
    // Uniform within a cell: the cell's share of the weight over its solid angle, in which
    // the solid angle cancels.
    return weight_of(cells_[cell_of(towards_sky / length)]) / total_weight_;
}

SkyRadiance::Sample SkyRadiance::sample(const glm::dvec2& u) const {
    Sample out;
    if (black()) {
        return out;
    }
    const double x = std::clamp(u.x, 0.0, std::nextafter(1.0, 0.0));
    const auto found = std::upper_bound(cdf_.begin(), cdf_.end(), x);
    const auto index = static_cast<std::size_t>(std::min<std::ptrdiff_t>(
        found - cdf_.begin(), static_cast<std::ptrdiff_t>(cdf_.size()) - 1));
    const double below = index > 0 ? cdf_[index - 1] : 0.0;
    const double span = cdf_[index] - below;
    const double v = span > 0.0 ? std::clamp((x - below) / span, 0.0, 1.0) : 0.5;
    const int row = static_cast<int>(index / static_cast<std::size_t>(width_));
    const int col = static_cast<int>(index % static_cast<std::size_t>(width_));
    // Uniform in solid angle within the cell: cos(theta) uniform between the row's bounds.
    const double top = std::cos(kPi * row / height_);
    const double bottom = std::cos(kPi * (row + 1) / height_);
    const double cos_theta = std::clamp(top + v * (bottom - top), -1.0, 1.0);
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    const double phi = 2.0 * kPi * (col + std::clamp(u.y, 0.0, 1.0)) / width_;
    out.direction = glm::normalize(glm::vec3(static_cast<float>(sin_theta * std::cos(phi)),
                                             static_cast<float>(cos_theta),
                                             static_cast<float>(sin_theta * std::sin(phi))));
    out.radiance = cells_[index];
    out.pdf = weight_of(cells_[index]) / total_weight_;
    return out;
}

glm::dvec3 horizontal_irradiance(const SkyRadiance& sky) {
    glm::dvec3 sum(0.0);
    const int width = sky.width();
    const int height = sky.height();
    for (int row = 0; 2 * (row + 1) <= height; ++row) {  // rows whose lower edge is at or above 0
        const double top = std::cos(kPi * row / height);
        const double bottom = std::cos(kPi * (row + 1) / height);
        // The integral of cos(theta) over one cell: (cos^2 top - cos^2 bottom) / 2 per radian.
        const double weight = 0.5 * (top * top - bottom * bottom) * (2.0 * kPi / width);
        for (int col = 0; col < width; ++col) {
            sum += glm::dvec3(
                       sky.cells()[static_cast<std::size_t>(row) * static_cast<std::size_t>(width) +
                                   static_cast<std::size_t>(col)]) *
                   weight;
        }
    }
    return sum;
}

SkyRadiance with_ground(const SkyRadiance& sky, const glm::vec3& albedo,
                        const glm::vec3& sun_on_ground) {
    const glm::dvec3 rho = glm::clamp(glm::dvec3(sanitized(albedo)), 0.0, 1.0);
    const glm::dvec3 ground =
        rho * (horizontal_irradiance(sky) + glm::dvec3(sanitized(sun_on_ground))) / kPi;
    std::vector<glm::vec3> cells = sky.cells();
    const int width = sky.width();
    const int height = sky.height();
    // The rows whose upper edge is at or below the horizon.
    for (int row = (height + 1) / 2; row < height; ++row) {
        for (int col = 0; col < width; ++col) {
            cells[static_cast<std::size_t>(row) * static_cast<std::size_t>(width) +
                  static_cast<std::size_t>(col)] = glm::vec3(ground);
        }
    }
    return SkyRadiance(width, height, std::move(cells));
}

}  // namespace luxel::lighting
