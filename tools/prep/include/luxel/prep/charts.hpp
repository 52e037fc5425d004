#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/prep/geometry.hpp"
#include "luxel/prep/surfaces.hpp"

namespace luxel::prep {

enum class ChartMethod {
    Planar,     ///< projection onto the chart's mean plane
    Conformal,  ///< least-squares conformal map (Lévy et al. 2002)
};

/// One piece of a surface with its own light-map parameterization, in texel units inside a
/// width x height rectangle (padding excluded): vertex uv lies in [0, width] x [0, height].
struct Chart {
    std::vector<int> faces;                   ///< node faces
    std::vector<int> vertices;                ///< half-edge mesh vertex of each chart vertex
    std::vector<std::array<int, 3>> corners;  ///< chart vertex of each face corner
    std::vector<glm::dvec2> uv;               ///< per chart vertex, in texels
    int width = 1;
    int height = 1;
    ChartMethod method = ChartMethod::Planar;
    double area = 0.0;  ///< m^2
    /// Area stretch of the triangles: world area per texel divided by texel_size^2. 1 is
    /// exact; the bounds keep every triangle within [1 / max_stretch, max_stretch].
    double stretch_min = 1.0;
    double stretch_max = 1.0;
    double stretch_area_sum = 0.0;  ///< sum of area * stretch, for area-weighted means
};

struct ChartLimits {
    double texel_size = 0.05;
    double max_stretch = 1.5;
    /// Charts larger than this (m^2) are cut: a chart must fit in one surface.
    double area_budget = 1.0;
    /// Largest chart rectangle side, padding included, in texels (the page size).
    int max_extent = 2048;
    int padding = 1;
    /// Larger pieces are not given to the conformal solver (its cost grows faster than
    /// linearly); they are cut first.
    std::size_t max_conformal_faces = 150000;
};

struct ChartingCounts {
    std::size_t planar = 0;
    std::size_t conformal = 0;
    std::size_t conformal_failures = 0;  ///< solver or bound failures that led to a cut
};

/// Cuts a crease surface into charts and flattens each: planar projection where it keeps the
/// stretch within bounds without flipped or overlapping triangles, a least-squares conformal
/// map where that does better, and otherwise cuts along the dominant axis directions (for
/// strongly curved pieces) or in two halves, until every piece passes. Charts come out in a
/// deterministic order that depends only on the geometry.
[[nodiscard]] std::vector<Chart> build_charts(const NodeGeometry& geometry,
                                              const CreaseSurface& surface,
                                              const ChartLimits& limits,
                                              ChartingCounts* counts = nullptr);

}  // namespace luxel::prep
