#pragma once

// Internal to luxel_prep: the pieces charting works on, and the ways to flatten one.

#include <array>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/prep/charts.hpp"
#include "luxel/prep/geometry.hpp"

namespace luxel::prep::detail {

/// A crease surface re-indexed from 0: charting cuts it into pieces many times over, and local
/// indices let every step use flat arrays instead of maps.
struct Patch {
    std::vector<int> node_face;                  ///< local face -> node face
    std::vector<int> node_vertex;                ///< local vertex -> half-edge mesh vertex
    std::vector<std::array<int, 3>> corners;     ///< local vertex of each face corner
    std::vector<std::array<int, 3>> neighbours;  ///< local face across each edge; -1 outside
    std::vector<glm::dvec3> positions;           ///< per local vertex, world space
    std::vector<glm::dvec3> normals;             ///< per local face
    std::vector<double> areas;                   ///< per local face, m^2

    [[nodiscard]] std::size_t face_count() const { return node_face.size(); }
    [[nodiscard]] glm::dvec3 centroid(int face) const;
};

[[nodiscard]] Patch make_patch(const NodeGeometry& geometry, const std::vector<int>& faces);

/// A set of patch faces with its own vertex numbering (what a chart's uv is indexed by).
struct Piece {
    std::vector<int> faces;                   ///< patch faces, ascending
    std::vector<int> vertices;                ///< patch vertex of each piece vertex
    std::vector<std::array<int, 3>> corners;  ///< piece vertex of each face corner
};

/// Builds the vertex numbering of `faces`. `scratch` has one entry per patch vertex, all -1,
/// and is left that way.
[[nodiscard]] Piece make_piece(const Patch& patch, std::vector<int> faces,
                               std::vector<int>& scratch);

/// Orthographic projection onto the plane through the origin with normal `axis`, in metres,
/// oriented so that faces facing along `axis` keep a counter-clockwise winding.
[[nodiscard]] std::vector<glm::dvec2> planar_projection(const Patch& patch, const Piece& piece,
                                                        const glm::dvec3& axis);

/// Least-squares conformal map: the flattening whose triangles are closest to similar copies
/// of the originals, with two far-apart vertices pinned. Needs a connected piece with a
/// boundary. Returns nothing when the sparse solver fails.
[[nodiscard]] std::optional<std::vector<glm::dvec2>> conformal_map(const Patch& patch,
                                                                   const Piece& piece);

/// A flattening scaled to texels, rotated to its smallest bounding rectangle and placed in an
/// integer rectangle, with its stretch measured.
struct FittedChart {
    bool ok = false;
    /// Within bounds but wider than a page: `uv` holds the scaled flattening, to cut along.
    bool too_large = false;
    const char* failure = "";  ///< why not, for debugging
    std::vector<glm::dvec2> uv;
    int width = 1;
    int height = 1;
    double stretch_min = 1.0;
    double stretch_max = 1.0;
    double stretch_area_sum = 0.0;

    /// How far from uniform the texel density is (1 = uniform).
    [[nodiscard]] double distortion() const { return stretch_max / stretch_min; }
};

/// Scales `uv` (any unit) so that its stretch sits inside the bounds as close to exact area as
/// they allow, and checks the bounds, the winding of every triangle and that no two triangles
/// overlap.
[[nodiscard]] FittedChart fit_chart(const Patch& patch, const Piece& piece,
                                    std::vector<glm::dvec2> uv, const ChartLimits& limits);

/// A flattening and how it was made.
struct Flattening {
    FittedChart fitted;
    ChartMethod method = ChartMethod::Planar;
};

/// The better of a planar projection along `normal_sum` (tried when every face normal is within
/// about 87 degrees of it: `min_cos`) and, where that is not near uniform, a least-squares
/// conformal map (tried on pieces with a boundary). Counts the conformal maps that failed in
/// `conformal_failures` when given.
[[nodiscard]] Flattening flatten_piece(const Patch& patch, const Piece& piece,
                                       const glm::dvec3& normal_sum, double min_cos,
                                       bool has_boundary, const ChartLimits& limits,
                                       std::size_t* conformal_failures);

/// A flattened piece that passed the bounds: one chart before it is written out.
struct AcceptedPiece {
    Piece piece;
    FittedChart fitted;
    ChartMethod method = ChartMethod::Planar;
    double area = 0.0;  ///< m^2
};

/// Merges adjacent charts of a patch while the union flattens within the bounds, stays within
/// the area budget and needs fewer page texels (padding included) than the two apart. Charts
/// keep their order (a merged chart takes the place of the earlier of the two).
void merge_adjacent_charts(const Patch& patch, std::vector<AcceptedPiece>& charts,
                           const ChartLimits& limits, std::vector<int>& vertex_scratch);

}  // namespace luxel::prep::detail
