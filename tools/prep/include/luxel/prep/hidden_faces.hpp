#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/scene/scene.hpp"

/// Which surfaces no one can see: the outside of a closed level, faces pressed against other
/// geometry (a crate's bottom on the floor, a wall's end inside another wall). luxel-prep gives
/// them coarse texels (tools/prep/README.md, "Texel size"): one 6 x 5 x 3 m room modelled as
/// slabs spent half its texels on faces no camera reaches.
///
/// The level's space is cut into cubic cells; every cell a triangle of the static light-mapped
/// geometry passes through is solid (triangles sampled at a third of a cell, so a wall leaves
/// no gap a six-connected flood can pass); the flood starts at the viewpoints (cameras, point
/// and spot lights, or luxel's default view when the level has none) and fills every free
/// cell it can reach. A surface is seen when a point two cells in front of one of its faces lies
/// in a reached cell; surfaces smaller than 4 x 4 cells are not judged (seen). Glass and other
/// pass-through primitives are not barriers (one sees through a window); dynamic nodes are neither
/// barriers nor ever hidden (a door that opens shows what was behind it, a crate that slides shows
/// its bottom).
namespace luxel::prep {

/// One light-mapped triangle in world space and the surface (any numbering) it belongs to.
struct VisibilityTriangle {
    glm::dvec3 a{0.0};
    glm::dvec3 b{0.0};
    glm::dvec3 c{0.0};
    std::uint32_t surface = 0;
    bool dynamic = false;
};

struct Visibility {
    /// Per surface: whether a viewpoint's flood reaches the front of any of its faces (every
    /// surface is seen when the test could not run).
    std::vector<bool> seen;
    /// Why the test did not run ("" when it did): no viewpoint in free space, a level too large
    /// for cells fine enough to judge, too much geometry to sample.
    std::string skipped;
    double cell_size = 0.0;  ///< metres
};

/// The points a level is seen from: its cameras and its point and spot lights, or luxel's
/// default view (scene/level_check.hpp) when it has none of them.
[[nodiscard]] std::vector<glm::dvec3> viewpoints(const scene::Scene& scene);

/// The flood described above. Cells are the box's longest side over 256, at least `min_cell`
/// metres (a texel: finer cells find gaps no texel resolves) and at most `max_cell`: a level
/// whose box needs coarser cells is not judged, since its corridors could close up.
[[nodiscard]] Visibility find_seen_surfaces(std::span<const VisibilityTriangle> triangles,
                                            std::size_t surface_count,
                                            std::span<const glm::dvec3> viewpoints, double min_cell,
                                            double max_cell);

}  // namespace luxel::prep
