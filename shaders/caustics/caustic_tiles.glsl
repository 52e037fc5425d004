// The tile bookkeeping shared by the splat, the tile compaction and the filter: one flag per
// CAUSTIC_TILE x CAUSTIC_TILE pixel tile (set by the splat), the counters read back into
// CausticPassStats, and the compacted list of tiles to filter. The first three counters are
// the indirect dispatch's (x, y, z), so the compaction appends straight into the dispatch.
// Binding points and layouts: caustic_interface.h, shared with lighting/gpu's CausticPass.

#include "caustic_interface.h"

layout(std430, binding = CAUSTIC_TILE_FLAGS_BINDING) buffer CausticTileFlags {
    uint tile_flags[];
};
layout(std430, binding = CAUSTIC_CONTROL_BINDING) buffer CausticControl {
    uint dispatch_x;  // tiles in tile_list
    uint dispatch_y;
    uint dispatch_z;
    uint photons_splatted;
    uint tiles_marked;
    uint tiles_filtered;
};
layout(std430, binding = CAUSTIC_TILE_LIST_BINDING) buffer CausticTileList {
    uint tile_list[];
};

uniform ivec2 u_tiles;  // tiles across and down
uniform int u_reach;    // tiles a kernel reaches beyond its own: ceil(radius / CAUSTIC_TILE)

bool tile_marked(ivec2 tile) {
    return tile_flags[tile.y * u_tiles.x + tile.x] != 0u;
}

// Whether a pixel of `tile` can receive a photon's filtered power: a marked tile within the
// kernel's reach. A pixel near a tile border needs its neighbour's photons.
bool tile_in_reach(ivec2 tile) {
    ivec2 lo = max(tile - u_reach, ivec2(0));
    ivec2 hi = min(tile + u_reach, u_tiles - 1);
    for (int y = lo.y; y <= hi.y; ++y) {
        for (int x = lo.x; x <= hi.x; ++x) {
            if (tile_marked(ivec2(x, y))) {
                return true;
            }
        }
    }
    return false;
}
