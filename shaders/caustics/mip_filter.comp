#version 450 core
// The level-adjusted mip-map filter (S. Larsen 2006, §3 and §6.2.6): where photons are sparse
// (a camera close to a caustic), a fixed screen-space kernel holds one or two of them and the
// caustic breaks into dots. The splat buffer's mip chain holds, at level L, the mean of
// 2^L x 2^L pixels: rgb the mean irradiance over that block, alpha the photons in it over its
// pixel count. Each pixel takes the finest level whose block, read bilinearly at the pixel's
// centre, holds at least u_min_photons photons (the photon map's "widen the radius until it
// holds N photons", in screen space), blended with the level below by where N falls between
// their counts (in log2), so the level does not jump from pixel to pixel. As the photon map's
// search, the widening stops at a radius in metres (u_max_radius, at the pixel's depth):
// without it every empty pixel of the frame would reach some caustic at a coarse enough level
// and glow with it (a disc's filtered power measured 1.86 times its photons').
// Every tile is filtered: a coarse level may reach past the tiles the splat marked.

#include "caustic_tiles.glsl"
#include "caustic_view.glsl"

layout(local_size_x = CAUSTIC_TILE, local_size_y = CAUSTIC_TILE) in;

layout(binding = CAUSTIC_SPLAT_UNIT) uniform sampler2D u_splat;  // with its mip chain
layout(rgba32f, binding = CAUSTIC_OUTPUT_IMAGE) writeonly uniform image2D u_output;

uniform float u_min_photons;  // photons an estimate needs (CausticPassSettings::mip_min_photons)
uniform int u_levels;         // levels of the chain, level 0 included
uniform float u_max_radius;       // metres: the widest an estimate may reach
uniform float u_pixel_size_scale;  // a pixel's width in metres at view depth z: z * this

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (!pixel_inside(pixel)) {
        return;
    }
    vec2 uv = (vec2(pixel) + 0.5) / vec2(u_viewport);
    // The coarsest level whose block (2^L pixels across) fits in the radius's diameter.
    float depth = -scene_view_position(pixel).z;
    int top = 0;
    if (depth > 0.0 && depth < 0.5 * CAUSTIC_NO_SURFACE) {
        float across = 2.0 * u_max_radius / max(depth * u_pixel_size_scale, 1e-9);
        top = across >= 2.0 ? min(int(floor(log2(across))), u_levels - 1) : 0;
    }
    // No photon within the widest block: nothing to estimate (most of a frame), two reads.
    if (textureLod(u_splat, uv, float(top)).a <= 0.0) {
        imageStore(u_output, pixel, vec4(0.0));
        return;
    }
    vec4 finer = texelFetch(u_splat, pixel, 0);
    float finer_count = finer.a;
    vec4 result = finer;
    if (finer_count < u_min_photons) {
        for (int level = 1; level <= top; ++level) {
            vec4 coarser = textureLod(u_splat, uv, float(level));
            float count = coarser.a * exp2(2.0 * float(level));
            result = coarser;
            if (count >= u_min_photons) {
                // log2 position of N between the two counts; a finer level with no photon at
                // all gives the coarser one alone.
                float lo = log2(max(finer_count, 1e-3));
                float hi = log2(max(count, 1e-3));
                float t = hi > lo ? clamp((log2(u_min_photons) - lo) / (hi - lo), 0.0, 1.0) : 1.0;
                result = mix(finer, coarser, t);
                break;
            }
            finer = coarser;
            finer_count = count;
        }
    }
    imageStore(u_output, pixel, result);
}
