#version 450 core
// Hemi-plane gather, reduction: one work group per tile sums weight * radiance over the
// tile's pixels in 32-bit float (a strided per-thread sum, then a tree in shared memory) and
// writes the tile's sum. The weights are dA / (pi (x^2 + y^2 + 1)^2) from
// hemi_plane_weights(); the caller multiplies by pi and adds the band the plane misses. A
// mirror or glass pixel adds its weight to the tile's alpha instead (the CPU traces rays
// through it). A pixel the scene pass left clear (alpha 0: nothing drawn) looks out of the
// level: it reads the sky along its direction, x right + y up + forward in the texel's view,
// as the CPU gather's rays that leave the level do.

#define GROUP_SIZE 256
layout(local_size_x = GROUP_SIZE) in;

#include "../common/sky.glsl"
#include "gather_interface.h"

layout(binding = GATHER_TILES_UNIT) uniform sampler2D u_tiles;
layout(binding = GATHER_SKY_UNIT) uniform sampler2D u_sky;

layout(std430, binding = GATHER_VIEWS_BINDING) readonly buffer Views {
    GatherView views[];
};
layout(std430, binding = GATHER_WEIGHTS_BINDING) readonly buffer Weights {
    float weights[];
};
layout(std430, binding = GATHER_SUMS_BINDING) writeonly buffer Sums {
    vec4 sums[];
};

uniform int u_first_view;  // where this batch's views and sums are
uniform int u_tiles_x;
uniform int u_resolution;
uniform float u_half_width;  // a
uniform int u_sky_on;        // 1: pixels that leave the level read u_sky

shared vec4 partial[GROUP_SIZE];  // rgb: weighted radiance; a: the weight of specular pixels

void main() {
    uint tile = gl_WorkGroupID.x;
    ivec2 origin = ivec2(int(tile) % u_tiles_x, int(tile) / u_tiles_x) * u_resolution;
    uint pixels = uint(u_resolution * u_resolution);
    uint resolution = uint(u_resolution);
    GatherView view = views[u_first_view + int(tile)];
    // The plane coordinate of pixel i's centre: a (-1 + (2 i + 1) / n), as hemi_plane_weights.
    float pixel_size = 2.0 * u_half_width / float(u_resolution);
    vec4 sum = vec4(0.0);
    for (uint p = gl_LocalInvocationIndex; p < pixels; p += GROUP_SIZE) {
        ivec2 xy = ivec2(p % resolution, p / resolution);
        vec4 drawn = texelFetch(u_tiles, origin + xy, 0);
        vec3 radiance = drawn.rgb;
        if (drawn.a > 0.0 && drawn.a < 1.0) {
            // A mirror or glass (GATHER_SPECULAR_ALPHA): its light comes from the CPU's rays.
            sum.a += weights[p];
            continue;
        }
        if (drawn.a == 0.0 && u_sky_on != 0) {
            vec2 plane = (vec2(xy) + 0.5) * pixel_size - u_half_width;
            radiance = sky_radiance(u_sky, plane.x * view.right.xyz + plane.y * view.up.xyz +
                                               view.forward.xyz);
        }
        sum.rgb += weights[p] * radiance;
    }
    partial[gl_LocalInvocationIndex] = sum;
    barrier();
    for (uint stride = GROUP_SIZE / 2; stride > 0; stride >>= 1) {
        if (gl_LocalInvocationIndex < stride) {
            partial[gl_LocalInvocationIndex] += partial[gl_LocalInvocationIndex + stride];
        }
        barrier();
    }
    if (gl_LocalInvocationIndex == 0) {
        sums[u_first_view + int(tile)] = partial[0];
    }
}
