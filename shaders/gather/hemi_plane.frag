#version 450 core
// Hemi-plane gather, scene pass: the AIM radiance leaving each visible front face, read
// bilinearly from its surface's light-map page, plus what the face emits (RadianceAtlas::sample
// on the GPU). Back faces are the insides of walls and objects and send nothing; surfaces
// without a page send only what they emit.

in vec2 v_lightmap_uv;
flat in int v_surface;

// Per surface, two entries: [2s] x = layer (-1: no page), y = page size / layer size,
// zw = UV clamp range; [2s + 1] rgb = the radiance the surface's front emits (area lights: the
// radiance leaving a surface is what it emits plus what it reflects, RadianceAtlas::sample).
#include "gather_interface.h"

layout(std430, binding = GATHER_SURFACE_PAGES_BINDING) readonly buffer SurfacePages {
    vec4 surface_pages[];
};

layout(binding = GATHER_RADIANCE_UNIT) uniform sampler2DArray u_radiance;
uniform bool u_mirrored;  // the model matrix flips winding: front faces wind clockwise

layout(location = 0) out vec4 o_radiance;
// Of two faces back to back in one plane (a zero-thickness wall between two rooms) the one
// facing the texel must win the depth test, as RayScene::facing_the_ray makes it win for the
// CPU's rays; left to rasterisation, the two triangulations' depths differ by rounding and
// whichever is nearer by a hair wins pixel by pixel (two-rooms' texels beside the shared wall
// lost up to 23% to the other room's black back face). A back face is pushed a relative 1e-4
// farther, the CPU's tolerance. Depth is reversed (near / z), so farther is smaller: declaring
// that the shader only lowers depth keeps early depth testing valid.
layout(depth_less) out float gl_FragDepth;
const float kBackFacePush = 1.0 - 1e-4;

void main() {
    bool front = gl_FrontFacing != u_mirrored;
    gl_FragDepth = front ? gl_FragCoord.z : gl_FragCoord.z * kBackFacePush;
    if (v_surface == GATHER_SPECULAR_SURFACE) {
        // A mirror or glass: hides what lies behind it, and is marked for the CPU's rays.
        o_radiance = vec4(0.0, 0.0, 0.0, GATHER_SPECULAR_ALPHA);
        return;
    }
    vec3 radiance = vec3(0.0);
    if (front && v_surface >= 0 && 2 * v_surface + 1 < surface_pages.length()) {
        vec4 page = surface_pages[2 * v_surface];
        if (page.x >= 0.0) {
            vec2 uv = clamp(v_lightmap_uv, page.zz, page.ww) * page.y;
            radiance = max(textureLod(u_radiance, vec3(uv, page.x), 0.0).rgb, vec3(0.0));
        }
        radiance += max(surface_pages[2 * v_surface + 1].rgb, vec3(0.0));
    }
    o_radiance = vec4(radiance, 1.0);
}
