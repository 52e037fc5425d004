#version 450 core
// Caustic splat: adds the photon's irradiance (blend ONE, ONE into RGBA32F; alpha counts
// photons), marks its tile and counts it.

#include "caustic_tiles.glsl"

flat in vec3 v_irradiance;
layout(location = 0) out vec4 o_splat;

void main() {
    ivec2 tile = ivec2(gl_FragCoord.xy) / CAUSTIC_TILE;
    atomicOr(tile_flags[tile.y * u_tiles.x + tile.x], 1u);
    atomicAdd(photons_splatted, 1u);
    o_splat = vec4(v_irradiance, 1.0);
}
