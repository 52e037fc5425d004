#version 450 core
// The edge pass's stencil mask (docs/METHOD.md §8.4): keeps the pixels where the G-buffer shows
// two surfaces meeting and discards the rest, so that the edge pass, drawn with the stencil
// test, shades only those. A software rasterizer such as llvmpipe runs both sides of a branch
// for a whole block of pixels, so an early return in the edge pass saved nothing there; a block
// the stencil rejects whole is not shaded at all (docs/PERFORMANCE.md, "Shader variants").

layout(binding = 1) uniform sampler2D u_position;  // world position, w = 1 where covered
layout(binding = 2) uniform sampler2D u_normal;    // world normal

#include "post/geometric_edges.glsl"

void main() {
    frame_size = textureSize(u_position, 0);
    if (!on_geometric_edge(ivec2(gl_FragCoord.xy))) {
        discard;
    }
}
