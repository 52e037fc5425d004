#version 450 core
// Hemi-plane gather, reduction: one work group per tile sums weight * radiance over the
// tile's pixels in 32-bit float (a strided per-thread sum, then a tree in shared memory) and
// writes the tile's sum. The weights are dA / (pi (x^2 + y^2 + 1)^2) from
// hemi_plane_weights(); the caller divides by F(a) and multiplies by pi.

#define GROUP_SIZE 256
layout(local_size_x = GROUP_SIZE) in;

#include "gather_interface.h"

layout(binding = GATHER_TILES_UNIT) uniform sampler2D u_tiles;

layout(std430, binding = GATHER_WEIGHTS_BINDING) readonly buffer Weights {
    float weights[];
};
layout(std430, binding = GATHER_SUMS_BINDING) writeonly buffer Sums {
    vec4 sums[];
};

uniform int u_first_view;  // where this batch's sums go
uniform int u_tiles_x;
uniform int u_resolution;

shared vec3 partial[GROUP_SIZE];

void main() {
    uint tile = gl_WorkGroupID.x;
    ivec2 origin = ivec2(int(tile) % u_tiles_x, int(tile) / u_tiles_x) * u_resolution;
    uint pixels = uint(u_resolution * u_resolution);
    uint resolution = uint(u_resolution);
    vec3 sum = vec3(0.0);
    for (uint p = gl_LocalInvocationIndex; p < pixels; p += GROUP_SIZE) {
        ivec2 xy = ivec2(p % resolution, p / resolution);
        sum += weights[p] * texelFetch(u_tiles, origin + xy, 0).rgb;
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
        sums[u_first_view + int(tile)] = vec4(partial[0], 0.0);
    }
}
