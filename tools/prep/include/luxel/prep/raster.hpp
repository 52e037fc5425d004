#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

/// Rasterization in texel units, where texel (x, y) is the square [x, x+1] x [y, y+1] and its
/// centre (x + 0.5, y + 0.5) is where the lighting samples.
namespace luxel::prep {

/// Overlaps thinner than this (in texels) do not claim a texel: a triangle edge that lies on a
/// texel border, give or take float rounding, leaves the texel beyond it alone.
inline constexpr double kCoverageTolerance = 1e-5;

/// Calls visit(x, y) for every texel that a triangle overlaps with positive area: the
/// conservative coverage, whose texels together contain the whole triangle. Zero-area
/// triangles cover nothing. Works for either winding.
template <class Visit>
void for_each_covered_texel(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, Visit&& visit) {
    const double twice_area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    if (twice_area == 0.0 || !std::isfinite(twice_area)) {
        return;
    }
    if (twice_area < 0.0) {
        std::swap(b, c);
    }
    // Outward unit normals of the counter-clockwise edges, and each edge's offset.
    const std::array<glm::dvec2, 3> from{a, b, c};
    const std::array<glm::dvec2, 3> to{b, c, a};
    std::array<glm::dvec2, 3> normal{};
    std::array<double, 3> reach{};
    for (std::size_t i = 0; i < 3; ++i) {
        const glm::dvec2 d = to[i] - from[i];
        normal[i] = glm::dvec2(d.y, -d.x) / glm::length(d);
        // A square's corners extend this far from its centre along the normal.
        reach[i] = 0.5 * (std::abs(normal[i].x) + std::abs(normal[i].y));
    }
    const glm::dvec2 low = glm::min(a, glm::min(b, c));
    const glm::dvec2 high = glm::max(a, glm::max(b, c));
    const auto x0 = static_cast<int>(std::floor(low.x + kCoverageTolerance));
    const auto x1 = static_cast<int>(std::ceil(high.x - kCoverageTolerance)) - 1;
    const auto y0 = static_cast<int>(std::floor(low.y + kCoverageTolerance));
    const auto y1 = static_cast<int>(std::ceil(high.y - kCoverageTolerance)) - 1;
    for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
            const glm::dvec2 centre(x + 0.5, y + 0.5);
            bool separated = false;
            for (std::size_t i = 0; i < 3 && !separated; ++i) {
                // The square lies (almost) entirely outside this edge.
                separated = glm::dot(centre - from[i], normal[i]) - reach[i] >= -kCoverageTolerance;
            }
            if (!separated) {
                visit(x, y);
            }
        }
    }
}

/// True when two triangles of a counter-clockwise triangle list overlap somewhere (by more
/// than a sample spacing of 1/samples_per_texel texels). Samples on a shared edge or vertex
/// belong to exactly one triangle, so a flat, unfolded chart never reports an overlap.
[[nodiscard]] bool triangles_overlap(const std::vector<glm::dvec2>& uv,
                                     const std::vector<std::array<int, 3>>& triangles, int width,
                                     int height, int samples_per_texel = 2);

/// One chart's texels within its rectangle: a width x height mask, row by row.
struct CoverageMask {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> covered;

    [[nodiscard]] bool at(int x, int y) const {
        return covered[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                       static_cast<std::size_t>(x)] != 0;
    }
    [[nodiscard]] std::int64_t count() const;
};

/// The mask grown by `radius` texels in every direction, diagonals included (what bilinear
/// filtering reaches around covered texels): (width + 2 radius) x (height + 2 radius), with
/// the original mask's texel (x, y) at (x + radius, y + radius).
[[nodiscard]] CoverageMask dilate(const CoverageMask& mask, int radius);

/// The conservative coverage of triangles whose UVs are given relative to a rectangle of
/// width x height texels; texels outside the rectangle are counted in `outside`.
[[nodiscard]] CoverageMask cover(const std::vector<glm::dvec2>& uv,
                                 const std::vector<std::array<int, 3>>& triangles, int width,
                                 int height, std::int64_t* outside = nullptr);

}  // namespace luxel::prep
