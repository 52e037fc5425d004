#include "luxel/lighting/core/surface_footprint.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "luxel/scene/texel_coverage.hpp"

namespace luxel::lighting {
namespace {

constexpr int kRings = 8;
constexpr int kPerRing = 8;
constexpr int kSamples = kRings * kPerRing;

/// Unit-disc points of equal area: ring i at radius sqrt((i + 0.5) / rings), rotated by half a
/// step every other ring.
const std::array<glm::dvec2, kSamples>& disc_pattern() {
    static const std::array<glm::dvec2, kSamples> pattern = [] {
        std::array<glm::dvec2, kSamples> points{};
        for (int ring = 0; ring < kRings; ++ring) {
            const double r = std::sqrt((ring + 0.5) / kRings);
            for (int k = 0; k < kPerRing; ++k) {
                const double angle = 2.0 * std::numbers::pi * (k + 0.5 * (ring % 2)) / kPerRing;
                points[static_cast<std::size_t>(ring * kPerRing + k)] =
                    glm::dvec2(r * std::cos(angle), r * std::sin(angle));
            }
        }
        return points;
    }();
    return pattern;
}

bool inside(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c, const glm::dvec2& p) {
    const double d0 = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
    const double d1 = (c.x - b.x) * (p.y - b.y) - (c.y - b.y) * (p.x - b.x);
    const double d2 = (a.x - c.x) * (p.y - c.y) - (a.y - c.y) * (p.x - c.x);
    return (d0 >= 0.0 && d1 >= 0.0 && d2 >= 0.0) || (d0 <= 0.0 && d1 <= 0.0 && d2 <= 0.0);
}

}  // namespace

SurfaceFootprint::SurfaceFootprint(const scene::Primitive& primitive, const SurfaceTexels& texels) {
    const auto& uvs = primitive.texcoords1;
    const double size = texels.page_size;
    if (uvs.size() != primitive.positions.size() || texels.page_size <= 0) {
        return;
    }
    glm::dvec2 low(std::numeric_limits<double>::max());
    glm::dvec2 high(std::numeric_limits<double>::lowest());
    for (std::size_t t = 0; t + 2 < primitive.indices.size(); t += 3) {
        bool valid = true;
        for (std::size_t k = 0; k < 3; ++k) {
            valid = valid && primitive.indices[t + k] < uvs.size();
        }
        if (!valid) {
            continue;
        }
        for (std::size_t k = 0; k < 3; ++k) {
            const glm::dvec2 corner = glm::dvec2(uvs[primitive.indices[t + k]]) * size;
            corners_.push_back(corner);
            low = glm::min(low, corner);
            high = glm::max(high, corner);
        }
    }
    if (corners_.empty()) {
        return;
    }
    // One cell of margin all round, so cells outside the triangles exist to measure from. The
    // grid never reaches beyond the page: texels are only there, and UVs far off the page (a
    // hostile file) must not size the grid.
    low = glm::clamp(low, glm::dvec2(0.0), glm::dvec2(size));
    high = glm::clamp(high, glm::dvec2(0.0), glm::dvec2(size));
    x0_ = static_cast<int>(std::floor(low.x)) - 1;
    y0_ = static_cast<int>(std::floor(low.y)) - 1;
    width_ = static_cast<int>(std::ceil(high.x)) + 1 - x0_;
    height_ = static_cast<int>(std::ceil(high.y)) + 1 - y0_;
    cells_.resize(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_));
    for (std::size_t t = 0; t < corners_.size() / 3; ++t) {
        const glm::dvec2 offset(x0_, y0_);
        scene::for_each_covered_texel(
            corners_[3 * t] - offset, corners_[3 * t + 1] - offset, corners_[3 * t + 2] - offset,
            {0, 0, width_, height_}, [&](int x, int y) {
                cells_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                       static_cast<std::size_t>(x)]
                    .push_back(static_cast<std::uint32_t>(t));
            });
    }
    // Distance from each texel's point to the nearest empty cell: a brute-force search over
    // empty cells would be quadratic; surfaces are small rectangles, so scan rings outward and
    // stop at the first empty cell found (its distance bounds the rest of the ring).
    const auto empty = [&](int x, int y) {
        return x < 0 || y < 0 || x >= width_ || y >= height_ ||
               cells_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                      static_cast<std::size_t>(x)]
                   .empty();
    };
    border_distance_.reserve(texels.texels.size());
    points_.reserve(texels.texels.size());
    for (const SurfaceTexel& texel : texels.texels) {
        const glm::dvec2 point = glm::dvec2(texel.page_point) - glm::dvec2(x0_, y0_);
        points_.push_back(texel.page_point);
        const int cx = static_cast<int>(std::floor(point.x));
        const int cy = static_cast<int>(std::floor(point.y));
        double nearest = std::numeric_limits<double>::max();
        const int limit = std::max(width_, height_) + 1;
        for (int ring = 0; ring <= limit; ++ring) {
            // Every cell on ring `ring` is at least ring - 1 texels away from the point.
            if (ring - 1 >= nearest) {
                break;
            }
            for (int y = cy - ring; y <= cy + ring; ++y) {
                for (int x = cx - ring; x <= cx + ring; ++x) {
                    if (std::max(std::abs(x - cx), std::abs(y - cy)) != ring || !empty(x, y)) {
                        continue;
                    }
                    // Distance from the point to the cell's square.
                    const double dx = std::max({x - point.x, 0.0, point.x - (x + 1)});
                    const double dy = std::max({y - point.y, 0.0, point.y - (y + 1)});
                    nearest = std::min(nearest, std::sqrt(dx * dx + dy * dy));
                }
            }
        }
        border_distance_.push_back(static_cast<float>(nearest));
    }
}

bool SurfaceFootprint::covers(const glm::dvec2& point) const {
    const int x = static_cast<int>(std::floor(point.x)) - x0_;
    const int y = static_cast<int>(std::floor(point.y)) - y0_;
    if (x < 0 || y < 0 || x >= width_ || y >= height_) {
        return false;
    }
    for (std::uint32_t t : cells_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                                  static_cast<std::size_t>(x)]) {
        if (inside(corners_[3 * t], corners_[3 * t + 1], corners_[3 * t + 2], point)) {
            return true;
        }
    }
    return false;
}

double SurfaceFootprint::fraction(std::size_t texel, double radius_texels,
                                  DensityKernel kernel) const {
    if (texel >= border_distance_.size() || !(radius_texels > 0.0) ||
        radius_texels <= static_cast<double>(border_distance_[texel])) {
        return 1.0;
    }
    const glm::dvec2 centre(points_[texel]);
    double covered = 0.0;
    double total = 0.0;
    for (const glm::dvec2& unit : disc_pattern()) {
        const double weight =
            kernel == DensityKernel::Epanechnikov ? 1.0 - glm::dot(unit, unit) : 1.0;
        covered += covers(centre + radius_texels * unit) ? weight : 0.0;
        total += weight;
    }
    // The texel's own point lies on the surface, so some of its disc does: never divide by 0.
    return std::max(covered / total, 1.0 / kSamples);
}

}  // namespace luxel::lighting
