#version 450 core
// Ray-differential footprints (docs/METHOD.md §7.4): one vertex per photon (vertex pulling
// from the photon buffer); the geometry shader turns it into the quad its footprint covers.
//
// r = clamp(scale * footprint, min_pixels pixels at the photon's depth, max_radius): at least
// a pixel, so the disc's sum over pixel centres holds its power; at most the widest radius a
// photon map would search, and at most max_pixels pixels (the cost of a camera right on a
// caustic). An unknown footprint (0) takes the widest.

#include "caustic_tiles.glsl"

layout(std430, binding = CAUSTIC_PHOTONS_BINDING) readonly buffer Photons {
    Photon photons[];
};

uniform mat4 u_view;
uniform mat4 u_projection;
uniform ivec2 u_viewport;
uniform float u_pixel_size_scale;  // a facing pixel's side at view depth z: scale * z
uniform float u_footprint_scale;
uniform float u_min_pixels;
uniform float u_max_pixels;
uniform float u_max_radius;

flat out int v_keep;
flat out vec3 v_view_centre;
flat out float v_radius;
flat out vec3 v_power;
flat out vec2 v_half_ndc;

bool finite3(vec3 v) {
    return !any(isnan(v)) && !any(isinf(v));
}

void main() {
    Photon photon = photons[gl_VertexID];
    v_keep = 0;
    v_view_centre = vec3(0.0);
    v_radius = 0.0;
    v_power = vec3(0.0);
    v_half_ndc = vec2(0.0);
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
    if (!finite3(photon.position) || !finite3(photon.power)) {
        return;
    }
    vec4 view = u_view * vec4(photon.position, 1.0);
    vec4 clip = u_projection * view;
    float z = -view.z;
    if (!(z > 0.0) || !(clip.w > 0.0)) {
        return;
    }
    float pixel = u_pixel_size_scale * z;
    float footprint = photon_footprint_radius(photon);
    float radius = footprint > 0.0 ? u_footprint_scale * footprint : u_max_radius;
    radius = clamp(radius, u_min_pixels * pixel, max(u_max_radius, u_min_pixels * pixel));
    radius = min(radius, u_max_pixels * pixel);
    // The sphere's screen half-size, from its nearest depth (never nearer than a tenth of the
    // centre's: a sphere around the eye would cover everything), plus a pixel of margin.
    float near_z = max(z - radius, 0.1 * z);
    v_half_ndc = vec2(radius / (u_pixel_size_scale * near_z) + 1.0) * 2.0 / vec2(u_viewport);
    v_keep = 1;
    v_view_centre = view.xyz;
    v_radius = radius;
    v_power = max(photon.power, vec3(0.0));
    gl_Position = clip;
    atomicAdd(photons_splatted, 1u);
}
