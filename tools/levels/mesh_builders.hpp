#pragma once

#include <functional>

#include <glm/glm.hpp>

#include "luxel/scene/scene.hpp"

/// Procedural meshes for the built-in levels. Every builder produces one indexed primitive with
/// positions, unit normals and TEXCOORD_0, in metres, with triangles wound counter-clockwise
/// seen from the side the normals point to.
namespace luxel::levels {

/// A flat rectangle spanned from `corner` by `edge_u` and `edge_v`, normal = normalize(u x v),
/// split into segments_u x segments_v cells (two triangles each).
[[nodiscard]] scene::Primitive make_quad(glm::vec3 corner, glm::vec3 edge_u, glm::vec3 edge_v,
                                         int segments_u = 1, int segments_v = 1);

/// A horizontal grid over [x0,x1] x [z0,z1] at height y + height(x, z), normals facing +y,
/// computed from the height field's analytic gradient `slope(x, z)` = (dh/dx, dh/dz).
[[nodiscard]] scene::Primitive make_height_field(
    float x0, float x1, float z0, float z1, float y, int cells_x, int cells_z,
    const std::function<float(float, float)>& height,
    const std::function<glm::vec2(float, float)>& slope);

/// An axis-aligned box centred at the origin with the given full size; normals face outward
/// (or inward when `inside` is true, for rooms seen from within).
[[nodiscard]] scene::Primitive make_box(glm::vec3 size, bool inside = false);

/// A UV sphere centred at the origin: `rings` latitude bands and `segments` longitude slices.
/// Normals face outward, or inward when `inside` is true.
[[nodiscard]] scene::Primitive make_sphere(float radius, int segments, int rings,
                                           bool inside = false);

/// An open cylinder (no caps) around the y axis from y = 0 to `height`, outward normals. Use a
/// double-sided material to make its inside visible.
[[nodiscard]] scene::Primitive make_open_cylinder(float radius, float height, int segments);

/// Appends `more` to `into` (same attribute layout).
void append(scene::Primitive& into, const scene::Primitive& more);

}  // namespace luxel::levels
