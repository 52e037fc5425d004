#version 450 core
// Caustic filter, one work group per 16 x 16 tile: the tile and its RADIUS-pixel apron of the
// splat buffer are staged in shared memory, then each pixel sums its (2 RADIUS + 1)^2 taps.
// Defines (from CausticPass): RADIUS, MODE (0: every tile; 1: every tile, returning at once
// where no marked tile is in reach; 2: the tiles of tile_list, indirect dispatch), WORLD (1:
// the world-space cone, weights computed here; 0: the weights buffer).
// Every mode runs the same arithmetic per pixel, so their images are identical.

#include "caustic_tiles.glsl"
#include "caustic_view.glsl"

layout(local_size_x = CAUSTIC_TILE, local_size_y = CAUSTIC_TILE) in;

layout(binding = CAUSTIC_SPLAT_UNIT) uniform sampler2D u_splat;
layout(rgba32f, binding = CAUSTIC_OUTPUT_IMAGE) writeonly uniform image2D u_output;
layout(std430, binding = CAUSTIC_WEIGHTS_BINDING) readonly buffer CausticWeights {
    float weights[];  // (2 RADIUS + 1)^2, row-major, summing to 1
};

uniform float u_world_radius;      // metres (WORLD)
uniform float u_pixel_size_scale;  // a pixel's width in metres at view depth z: z * this

const int SPAN = CAUSTIC_TILE + 2 * RADIUS;
shared vec4 s_splat[SPAN * SPAN];
#if WORLD
shared float s_depth[SPAN * SPAN];
#endif

void main() {
#if MODE == 2
    uint index = tile_list[gl_WorkGroupID.x];
    ivec2 tile = ivec2(int(index % uint(u_tiles.x)), int(index / uint(u_tiles.x)));
#else
    ivec2 tile = ivec2(gl_WorkGroupID.xy);
    if (gl_LocalInvocationIndex == 0u && tile_marked(tile)) {
        atomicAdd(tiles_marked, 1u);
    }
#endif
#if MODE == 1
    // The same answer for the whole group, so no invocation is left waiting at the barrier.
    if (!tile_in_reach(tile)) {
        return;
    }
    if (gl_LocalInvocationIndex == 0u) {
        atomicAdd(tiles_filtered, 1u);
    }
#endif

    ivec2 origin = tile * CAUSTIC_TILE - RADIUS;
    for (int i = int(gl_LocalInvocationIndex); i < SPAN * SPAN; i += CAUSTIC_TILE * CAUSTIC_TILE) {
        ivec2 p = origin + ivec2(i % SPAN, i / SPAN);
        bool inside = pixel_inside(p);
        s_splat[i] = inside ? texelFetch(u_splat, p, 0) : vec4(0.0);
#if WORLD
        s_depth[i] = inside ? -scene_view_position(p).z : CAUSTIC_NO_SURFACE;
#endif
    }
    barrier();

    ivec2 local = ivec2(gl_LocalInvocationID.xy);
    ivec2 pixel = tile * CAUSTIC_TILE + local;
    if (!pixel_inside(pixel)) {
        return;
    }
    vec4 sum = vec4(0.0);
#if WORLD
    // The cone 1 - r/d with d = radius + 1 (as RoundCone's d = k + 1), the radius in pixels
    // of world_radius at the centre's depth. Normalised over every tap of the cone, so a
    // photon keeps its power on a surface of constant depth, while taps across a depth edge
    // (depth differing by more than the radius) are left out and do not bleed.
    float zc = s_depth[(local.y + RADIUS) * SPAN + local.x + RADIUS];
    float radius = u_world_radius / (zc * u_pixel_size_scale);
    radius = radius >= 0.0 ? min(radius, float(RADIUS)) : 0.0;
    float d = radius + 1.0;
    float norm = 0.0;
    for (int j = -RADIUS; j <= RADIUS; ++j) {
        for (int i = -RADIUS; i <= RADIUS; ++i) {
            float w = max(1.0 - length(vec2(i, j)) / d, 0.0);
            int s = (local.y + RADIUS + j) * SPAN + local.x + RADIUS + i;
            norm += w;
            if (abs(s_depth[s] - zc) <= u_world_radius) {
                sum += w * s_splat[s];
            }
        }
    }
    sum /= norm;
#else
    for (int j = -RADIUS; j <= RADIUS; ++j) {
        for (int i = -RADIUS; i <= RADIUS; ++i) {
            float w = weights[(j + RADIUS) * (2 * RADIUS + 1) + i + RADIUS];
            sum += w * s_splat[(local.y + RADIUS + j) * SPAN + local.x + RADIUS + i];
        }
    }
#endif
    imageStore(u_output, pixel, sum);
}
