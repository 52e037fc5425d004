#version 450 core
// Caustic tile compaction: one invocation per tile counts the marked tiles and appends every
// tile with a marked tile within the kernel's reach to tile_list, growing the indirect
// dispatch's x count. The list's order varies run to run; each tile's pixels do not.

#include "caustic_tiles.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

void main() {
    ivec2 tile = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(tile, u_tiles))) {
        return;
    }
    if (tile_marked(tile)) {
        atomicAdd(tiles_marked, 1u);
    }
    if (tile_in_reach(tile)) {
        uint slot = atomicAdd(dispatch_x, 1u);
        tile_list[slot] = uint(tile.y * u_tiles.x + tile.x);
    }
}
