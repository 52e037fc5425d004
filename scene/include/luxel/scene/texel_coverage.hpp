#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <glm/glm.hpp>

/// Rasterization in light-map texel units, where texel (x, y) is the square [x, x+1] x [y, y+1]
/// and its centre (x + 0.5, y + 0.5) is where the lighting samples. luxel-prep counts the
/// texels a chart covers with this, and the lighting system finds the texels to light with it,
/// so both agree texel for texel.
namespace luxel::scene {

/// Overlaps thinner than this (in texels) do not claim a texel: a triangle edge that lies on a
/// texel border, give or take float rounding, leaves the texel beyond it alone.
inline constexpr double kCoverageTolerance = 1e-5;

/// The texels a caller can use, [x0, x1) x [y0, y1): coverage outside it is not visited, so a
/// triangle whose UVs reach far beyond its page (a hostile file) costs no more than the window.
struct TexelWindow {
    int x0 = 0;
    int y0 = 0;
    int x1 = 0;
    int y1 = 0;
};

/// Calls visit(x, y) for every texel of `window` that a triangle overlaps with positive area:
/// the conservative coverage, whose texels together contain the whole triangle. Zero-area
/// triangles cover nothing. Works for either winding.
template <class Visit>
void for_each_covered_texel(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, const TexelWindow& window,
                            Visit&& visit) {
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
    // Clamped in double before the conversion: a coordinate beyond int's range is no UB.
    const auto clamp_to = [](double value, int lo, int hi) {
        return static_cast<int>(
            std::clamp(value, static_cast<double>(lo), static_cast<double>(hi)));
    };
    const int x0 = clamp_to(std::floor(low.x + kCoverageTolerance), window.x0, window.x1);
    const int x1 = clamp_to(std::ceil(high.x - kCoverageTolerance), window.x0, window.x1) - 1;
    const int y0 = clamp_to(std::floor(low.y + kCoverageTolerance), window.y0, window.y1);
    const int y1 = clamp_to(std::ceil(high.y - kCoverageTolerance), window.y0, window.y1) - 1;
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

/// The area of the part of triangle (a, b, c) inside texel (x, y), the unit square
/// [x, x+1] x [y, y+1]: Sutherland-Hodgman against the square's four edges, then the shoelace
/// formula. Either winding; 0 for a triangle that misses the texel.
[[nodiscard]] inline double triangle_area_in_texel(const glm::dvec2& a, const glm::dvec2& b,
                                                   const glm::dvec2& c, int x, int y) {
    std::vector<glm::dvec2> polygon{a, b, c};
    std::vector<glm::dvec2> next;
    const std::array<glm::dvec3, 4> planes{
        glm::dvec3(1.0, 0.0, -static_cast<double>(x)),      // u >= x
        glm::dvec3(-1.0, 0.0, static_cast<double>(x + 1)),  // u <= x + 1
        glm::dvec3(0.0, 1.0, -static_cast<double>(y)),      // v >= y
        glm::dvec3(0.0, -1.0, static_cast<double>(y + 1))};
    for (const glm::dvec3& plane : planes) {
        next.clear();
        const std::size_t n = polygon.size();
        for (std::size_t i = 0; i < n; ++i) {
            const glm::dvec2& p = polygon[i];
            const glm::dvec2& q = polygon[(i + 1) % n];
            const double dp = plane.x * p.x + plane.y * p.y + plane.z;
            const double dq = plane.x * q.x + plane.y * q.y + plane.z;
            if (dp >= 0.0) {
                next.push_back(p);
            }
            if ((dp >= 0.0) != (dq >= 0.0)) {
                const double denominator = dp - dq;
                const double t = denominator != 0.0 ? dp / denominator : 0.0;
                next.push_back(p + t * (q - p));
            }
        }
        polygon.swap(next);
        if (polygon.size() < 3) {
            return 0.0;
        }
    }
    double twice = 0.0;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const glm::dvec2& p = polygon[i];
        const glm::dvec2& q = polygon[(i + 1) % polygon.size()];
        twice += p.x * q.y - q.x * p.y;
    }
    return 0.5 * std::abs(twice);
}

}  // namespace luxel::scene
