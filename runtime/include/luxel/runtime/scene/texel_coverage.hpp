#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/glm.hpp>

/// Rasterization in light-map texel units, where texel (x, y) is the square [x, x+1] x [y, y+1]
/// and its centre (x + 0.5, y + 0.5) is where the lighting samples. luxel-prep counts the
/// texels a chart covers with this, and the lighting system finds the texels to light with it,
/// so both agree texel for texel.
namespace luxel::scene {

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

}  // namespace luxel::scene
