// The contract between lighting/gpu/src/caustic_pass.cpp and shaders/caustics/*, written once:
// binding points, the tile size and the std430 layouts of the buffers both sides read. C++ and
// GLSL both include this file. The #define lines are common to both preprocessors; each
// language's declarations sit in a block of their own, side by side, and the C++ side checks
// its structs against the offsets given here with static_assert (std430: a vec3 is aligned to
// 16 bytes and a following scalar fills its fourth slot).
#ifndef LUXEL_CAUSTIC_INTERFACE_H
#define LUXEL_CAUSTIC_INTERFACE_H

#define CAUSTIC_TILE 16  // pixels across a tile (the filter's work group is one tile)

// Shader storage buffers.
#define CAUSTIC_PHOTONS_BINDING 0     // Photons: the caustic photons, vertex-pulled by the splat
#define CAUSTIC_TILE_FLAGS_BINDING 1  // one uint per tile, set where a photon landed
#define CAUSTIC_CONTROL_BINDING 2     // CausticControl: dispatch size and counters
#define CAUSTIC_TILE_LIST_BINDING 3   // the compacted list of tiles to filter
#define CAUSTIC_WEIGHTS_BINDING 4     // the screen-space kernel's (2 RADIUS + 1)^2 weights
// The caustic layer of the light maps (CausticLightMaps): per surface vec4(page layer or -1,
// page size, 1 / texel area in m^-2, 0).
#define CAUSTIC_LIGHT_MAP_SURFACES_BINDING 5
// Textures and images.
#define CAUSTIC_DEPTH_UNIT 0    // the scene's depth
#define CAUSTIC_SPLAT_UNIT 1    // the splat buffer, read by the filter
#define CAUSTIC_OUTPUT_IMAGE 0  // the filtered caustic irradiance

// struct Photon (lighting::CausticPhoton on the C++ side), std430.
#define CAUSTIC_PHOTON_SIZE 32
#define CAUSTIC_PHOTON_POSITION 0      // vec3, world metres
// int: bits 0-23 the light-mapped surface or -1 (signed), bits 24-31 the footprint radius code
// (lighting::encode_footprint_radius: CAUSTIC_FOOTPRINT_BASE * 2^((code - 1) / 16) m, 0 unknown)
#define CAUSTIC_PHOTON_SURFACE 12
#define CAUSTIC_FOOTPRINT_BASE 1e-4
#define CAUSTIC_PHOTON_POWER 16        // vec3, watts per channel
#define CAUSTIC_PHOTON_LIGHTMAP_UV 28  // uint, the hit's light-map UV (unpackUnorm2x16)

// CausticControl: six uints. The first three are the indirect dispatch's (x, y, z), so the tile
// compaction appends straight into the dispatch.
#define CAUSTIC_CONTROL_SIZE 24

#ifndef __cplusplus
struct Photon {
    vec3 position;
    int surface_footprint;
    vec3 power;
    uint lightmap_uv_bits;
};

int photon_surface(Photon photon) {
    return bitfieldExtract(photon.surface_footprint, 0, 24);  // sign-extended: -1 stays -1
}

// The footprint's radius in metres, 0 when unknown.
float photon_footprint_radius(Photon photon) {
    uint code = uint(photon.surface_footprint) >> 24;
    return code == 0u ? 0.0 : CAUSTIC_FOOTPRINT_BASE * exp2((float(code) - 1.0) / 16.0);
}
#endif

#endif
