// The contract between lighting/gpu/src/hemi_plane_gatherer.cpp and shaders/gather/*, written
// once: binding points and the std430 layout of a texel's view. C++ and GLSL both include this
// file (see shaders/caustics/caustic_interface.h for how); the C++ side checks its struct
// against the offsets here with static_assert.
#ifndef LUXEL_GATHER_INTERFACE_H
#define LUXEL_GATHER_INTERFACE_H

// Shader storage buffers.
#define GATHER_VIEWS_BINDING 0          // GatherView per texel of the batch
#define GATHER_SURFACE_PAGES_BINDING 1  // per surface: its AIM page and what it emits
#define GATHER_WEIGHTS_BINDING 2        // the hemi-plane's per-pixel weights
#define GATHER_SUMS_BINDING 3           // one weighted sum per texel
// Textures.
#define GATHER_RADIANCE_UNIT 0  // the AIM pages (radiance leaving each surface)
#define GATHER_TILES_UNIT 1     // the tile atlas the scene pass drew
#define GATHER_SKY_UNIT 2       // the sky (lighting::SkyTexture) for pixels that leave the level

// The surface id a vertex of a mirror or glass triangle carries: the scene pass marks its pixels
// (alpha 0.5, no radiance), the reduction sums their weight apart, and the CPU traces rays
// through them (HemiPlaneGatherer), since the plane cannot follow a specular bounce.
#define GATHER_SPECULAR_SURFACE (-2)
#define GATHER_SPECULAR_ALPHA 0.5

// struct GatherView, std430: four vec4s. right x up = -forward, so triangles whose front faces
// the texel wind counter-clockwise on the plane, as GL's front faces do.
#define GATHER_VIEW_SIZE 64
#define GATHER_VIEW_ORIGIN 0    // xyz: texel centre (world)
#define GATHER_VIEW_RIGHT 16    // xyz: plane x axis
#define GATHER_VIEW_UP 32       // xyz: plane y axis
#define GATHER_VIEW_FORWARD 48  // xyz: the texel normal; the plane is at forward distance 1

#ifndef __cplusplus
struct GatherView {
    vec4 origin;
    vec4 right;
    vec4 up;
    vec4 forward;
};
#endif

#endif
