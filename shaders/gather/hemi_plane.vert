#version 450 core
// Hemi-plane gather, scene pass: one instance per texel. Each instance projects the object
// onto its texel's plane (z = 1, half-width u_half_width, perspective from the texel centre)
// and then into that texel's tile of the tile atlas. Clip distances keep the instance inside
// its tile: the atlas-wide frustum alone would let a triangle spill into a neighbour's tile.

#include "gather_interface.h"

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec2 a_lightmap_uv;
layout(location = 2) in int a_surface;

layout(std430, binding = GATHER_VIEWS_BINDING) readonly buffer Views {
    GatherView views[];
};

uniform mat4 u_model;
uniform int u_first_view;     // the batch's first texel in `views`
uniform ivec2 u_tile_grid;    // tiles across and down the atlas
uniform float u_half_width;   // a
uniform float u_near;         // near plane distance (world units)

out gl_PerVertex {
    vec4 gl_Position;
    float gl_ClipDistance[4];
};
out vec2 v_lightmap_uv;
flat out int v_surface;

void main() {
    GatherView view = views[u_first_view + gl_InstanceID];
    vec3 d = (u_model * vec4(a_position, 1.0)).xyz - view.origin.xyz;
    float x = dot(d, view.right.xyz) / u_half_width;
    float y = dot(d, view.up.xyz) / u_half_width;
    float z = dot(d, view.forward.xyz);
    // Reversed depth with an infinite far plane (clip control [0, 1]): depth = near / z, so
    // precision does not depend on how small the near plane is, and clipping keeps z >= near.
    gl_ClipDistance[0] = z - x;
    gl_ClipDistance[1] = z + x;
    gl_ClipDistance[2] = z - y;
    gl_ClipDistance[3] = z + y;
    ivec2 tile = ivec2(gl_InstanceID % u_tile_grid.x, gl_InstanceID / u_tile_grid.x);
    // NDC x in [-1, 1] of the tile -> [-1 + 2 tx / n, -1 + 2 (tx + 1) / n] of the atlas,
    // written in clip space (multiplied through by w = z).
    vec2 grid = vec2(u_tile_grid);
    vec2 atlas_xy = (vec2(x, y) + z * (1.0 + 2.0 * vec2(tile))) / grid - z;
    gl_Position = vec4(atlas_xy, u_near, z);
    v_lightmap_uv = a_lightmap_uv;
    v_surface = a_surface;
}
