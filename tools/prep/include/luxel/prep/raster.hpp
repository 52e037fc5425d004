#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/scene/texel_coverage.hpp"

/// Rasterization in texel units (see texel_coverage.hpp for the convention).
namespace luxel::prep {

/// Conservative coverage is shared with the runtime (luxel/scene/texel_coverage.hpp),
/// so the texels the light-map table counts are exactly the texels the lighting computes.
using scene::for_each_covered_texel;
using scene::kCoverageTolerance;

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
