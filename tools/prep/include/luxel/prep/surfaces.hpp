#pragma once

#include <vector>

#include "luxel/prep/geometry.hpp"

namespace luxel::prep {

/// Faces of one material joined across edges flatter than the crease angle (docs/METHOD.md
/// §3.1): mark every edge connected when its two faces share a material and their normals
/// differ by less than the crease angle, then take the connected components.
struct CreaseSurface {
    std::vector<int> faces;  ///< ascending face indices
    int material = -1;
    double area = 0.0;  ///< m^2
};

/// The crease surfaces of a node, ordered by their first face (so the result depends only on
/// the mesh, not on the order work happens in).
[[nodiscard]] std::vector<CreaseSurface> find_crease_surfaces(const NodeGeometry& geometry,
                                                              double crease_degrees);

/// The largest angle, in degrees, between the normals of two faces that share an edge and a
/// material (what decides which crease angles keep a mesh in one piece).
[[nodiscard]] double max_connected_dihedral_degrees(const NodeGeometry& geometry);

/// Splits one crease surface's charts into surfaces of at most `area_budget` m^2 each (a
/// single chart larger than that is a surface of its own; the charting step keeps charts under
/// the budget). Charts are gathered breadth first across shared edges, so a surface stays one
/// connected piece. `chart_faces[c]` are the node faces of chart c; returns chart indices per
/// surface, in a deterministic order.
[[nodiscard]] std::vector<std::vector<int>> group_charts(
    const NodeGeometry& geometry, const std::vector<std::vector<int>>& chart_faces,
    const std::vector<double>& chart_area, double area_budget);

}  // namespace luxel::prep
