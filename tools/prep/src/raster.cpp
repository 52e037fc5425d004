#include "luxel/prep/raster.hpp"

#include <numeric>

namespace luxel::prep {
namespace {

bool lexicographically_less(const glm::dvec2& a, const glm::dvec2& b) {
    return a.x < b.x || (a.x == b.x && a.y < b.y);
}

/// Twice the signed area of (a, b, p), computed from the lexicographically smaller endpoint so
/// that orient(a, b, p) == -orient(b, a, p) holds exactly, not just up to rounding: the two
/// triangles sharing an edge then always disagree about which side a sample is on.
double orient(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& p) {
    if (lexicographically_less(b, a)) {
        return -orient(b, a, p);
    }
    return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
}

/// The tie-break for samples exactly on an edge: of the two opposite directions of an edge,
/// exactly one owns it.
bool owns_edge(const glm::dvec2& a, const glm::dvec2& b) {
    return a.y > b.y || (a.y == b.y && a.x < b.x);
}

bool inside(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c, const glm::dvec2& p) {
    const std::array<glm::dvec2, 3> from{a, b, c};
    const std::array<glm::dvec2, 3> to{b, c, a};
    for (std::size_t i = 0; i < 3; ++i) {
        const double side = orient(from[i], to[i], p);
        if (side < 0.0 || (side == 0.0 && !owns_edge(from[i], to[i]))) {
            return false;
        }
    }
    return true;
}

}  // namespace

bool triangles_overlap(const std::vector<glm::dvec2>& uv,
                       const std::vector<std::array<int, 3>>& triangles, int width, int height,
                       int samples_per_texel) {
    const auto columns =
        static_cast<std::size_t>(width) * static_cast<std::size_t>(samples_per_texel);
    const auto rows =
        static_cast<std::size_t>(height) * static_cast<std::size_t>(samples_per_texel);
    std::vector<std::uint8_t> hits(columns * rows, 0);
    const double step = 1.0 / samples_per_texel;
    for (const auto& triangle : triangles) {
        const glm::dvec2 a = uv[static_cast<std::size_t>(triangle[0])];
        const glm::dvec2 b = uv[static_cast<std::size_t>(triangle[1])];
        const glm::dvec2 c = uv[static_cast<std::size_t>(triangle[2])];
        const glm::dvec2 low = glm::min(a, glm::min(b, c));
        const glm::dvec2 high = glm::max(a, glm::max(b, c));
        // Sample i sits at (i + 0.5) * step.
        const auto first = [&](double v) {
            return static_cast<std::ptrdiff_t>(std::max(0.0, std::ceil(v / step - 0.5)));
        };
        const auto last = [&](double v, std::size_t count) {
            return std::min(static_cast<std::ptrdiff_t>(std::floor(v / step - 0.5)),
                            static_cast<std::ptrdiff_t>(count) - 1);
        };
        for (std::ptrdiff_t j = first(low.y); j <= last(high.y, rows); ++j) {
            for (std::ptrdiff_t i = first(low.x); i <= last(high.x, columns); ++i) {
                const glm::dvec2 sample((static_cast<double>(i) + 0.5) * step,
                                        (static_cast<double>(j) + 0.5) * step);
                if (inside(a, b, c, sample)) {
                    std::uint8_t& count =
                        hits[static_cast<std::size_t>(j) * columns + static_cast<std::size_t>(i)];
                    if (++count > 1) {
                        return true;
                    }
                }
            }
        }
    }
    return false;
}

std::int64_t CoverageMask::count() const {
    return std::accumulate(covered.begin(), covered.end(), std::int64_t{0});
}

CoverageMask dilate(const CoverageMask& mask, int radius) {
    // A square neighbourhood is separable: grow along rows, then along columns.
    CoverageMask rows;
    rows.width = mask.width + 2 * radius;
    rows.height = mask.height;
    rows.covered.assign(
        static_cast<std::size_t>(rows.width) * static_cast<std::size_t>(rows.height), 0);
    for (int y = 0; y < mask.height; ++y) {
        for (int x = 0; x < mask.width; ++x) {
            if (mask.at(x, y)) {
                const auto row = static_cast<std::size_t>(y) * static_cast<std::size_t>(rows.width);
                std::fill_n(rows.covered.begin() +
                                static_cast<std::ptrdiff_t>(row + static_cast<std::size_t>(x)),
                            2 * radius + 1, std::uint8_t{1});
            }
        }
    }
    CoverageMask grown;
    grown.width = rows.width;
    grown.height = mask.height + 2 * radius;
    grown.covered.assign(
        static_cast<std::size_t>(grown.width) * static_cast<std::size_t>(grown.height), 0);
    for (int y = 0; y < rows.height; ++y) {
        for (int x = 0; x < rows.width; ++x) {
            if (rows.at(x, y)) {
                for (int dy = 0; dy <= 2 * radius; ++dy) {
                    grown.covered[static_cast<std::size_t>(y + dy) *
                                      static_cast<std::size_t>(grown.width) +
                                  static_cast<std::size_t>(x)] = 1;
                }
            }
        }
    }
    return grown;
}

CoverageMask cover(const std::vector<glm::dvec2>& uv,
                   const std::vector<std::array<int, 3>>& triangles, int width, int height,
                   std::int64_t* outside) {
    CoverageMask mask;
    mask.width = width;
    mask.height = height;
    mask.covered.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0);
    std::int64_t spilled = 0;
    for (const auto& triangle : triangles) {
        // A window a chart's size beyond the mask on each side: spills are counted, and UVs
        // far off (which prep never makes) cost no more than that.
        for_each_covered_texel(
            uv[static_cast<std::size_t>(triangle[0])], uv[static_cast<std::size_t>(triangle[1])],
            uv[static_cast<std::size_t>(triangle[2])], {-width, -height, 2 * width, 2 * height},
            [&](int x, int y) {
                if (x < 0 || y < 0 || x >= width || y >= height) {
                    ++spilled;
                    return;
                }
                mask.covered[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                             static_cast<std::size_t>(x)] = 1;
            });
    }
    if (outside != nullptr) {
        *outside = spilled;
    }
    return mask;
}

}  // namespace luxel::prep
