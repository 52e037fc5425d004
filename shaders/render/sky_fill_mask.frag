#version 450 core
// The pixels the composite's second pass finishes (docs/METHOD.md §8.6): where the sky mask says
// a surface pixel shows some sky, or an empty pixel some surface. The first pass drew every
// pixel as its centre shows it; this one discards the others and marks these in the stencil
// buffer, so the second pass (the mixing, with its eight neighbours' light for an empty pixel)
// runs on the blocks that hold one. A branch in one pass did not do it: a software rasteriser
// runs both sides for its whole block of pixels.

layout(binding = 2) uniform sampler2D u_position;  // world position, w = 1 where covered
uniform int u_sky_on;                              // as the composite's

#include "render/sky_share.glsl"

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    bool surface = texelFetch(u_position, pixel, 0).w != 0.0;
    float share = sky_share(pixel);
    // As the composite mixes: a surface with the sky over its share (only with a sky), an empty
    // pixel with its neighbours over the surfaces' share (without a sky, all of it).
    bool mixed = surface ? (u_sky_on != 0 && share > 0.0) : (u_sky_on == 0 || share < 1.0);
    if (!mixed) {
        discard;
    }
}
