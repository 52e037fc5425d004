#version 450 core
// Caustic splat, one vertex per photon (vertex pulling from the photon buffer). The depth
// test against the scene is done here rather than by the depth buffer: the caller's depth may
// use any convention, the tolerance can follow the surface's slope, and the photon's pixel,
// its depth test and its pixel area all use the same pixel. A photon that fails is moved
// outside the clip volume, which drops the point.

#include "caustic_interface.h"
#include "caustic_view.glsl"

layout(std430, binding = CAUSTIC_PHOTONS_BINDING) readonly buffer Photons {
    Photon photons[];
};

uniform mat4 u_view;
uniform mat4 u_projection;
uniform float u_area_scale;  // 4 / (P00 P11 W H): facing pixel area = u_area_scale * z^2
uniform bool u_orientation;
uniform float u_min_cos;
uniform float u_bias_relative;
uniform float u_bias_absolute;

flat out vec3 v_irradiance;

bool finite3(vec3 v) {
    return !any(isnan(v)) && !any(isinf(v));
}

void cull() {
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    v_irradiance = vec3(0.0);
}

// The scene's change in view position one pixel along `step`, from the side whose depth
// changes less (the other side may lie across a silhouette); zero where neither side has a
// surface.
vec3 surface_step(ivec2 pixel, ivec2 step, vec3 centre) {
    vec3 best = vec3(0.0);
    float best_dz = CAUSTIC_NO_SURFACE;
    ivec2 forward = pixel + step;
    ivec2 backward = pixel - step;
    if (pixel_inside(forward)) {
        vec3 d = scene_view_position(forward) - centre;
        if (abs(d.z) < best_dz) {
            best = d;
            best_dz = abs(d.z);
        }
    }
    if (pixel_inside(backward)) {
        vec3 d = centre - scene_view_position(backward);
        if (abs(d.z) < best_dz) {
            best = d;
            best_dz = abs(d.z);
        }
    }
    return best_dz < 0.5 * CAUSTIC_NO_SURFACE ? best : vec3(0.0);
}

void main() {
    Photon photon = photons[gl_VertexID];
    if (!finite3(photon.position) || !finite3(photon.power)) {
        cull();
        return;
    }
    vec4 view = u_view * vec4(photon.position, 1.0);
    vec4 clip = u_projection * view;
    float z = -view.z;
    if (!(clip.w > 0.0) || !(z > 0.0)) {
        cull();
        return;
    }
    vec2 window = (clip.xy / clip.w * 0.5 + 0.5) * vec2(u_viewport);
    if (any(lessThan(window, vec2(0.0))) || any(greaterThanEqual(window, vec2(u_viewport)))) {
        cull();
        return;
    }
    ivec2 pixel = min(ivec2(window), u_viewport - 1);

    vec3 surface = scene_view_position(pixel);
    float scene_z = -surface.z;
    vec3 dx = surface_step(pixel, ivec2(1, 0), surface);
    vec3 dy = surface_step(pixel, ivec2(0, 1), surface);
    // The photon may sit anywhere in its pixel, the depth was sampled at the centre: half a
    // pixel of slope each way, doubled for margin.
    float tolerance =
        u_bias_relative * scene_z + u_bias_absolute + abs(dx.z) + abs(dy.z);
    if (z > scene_z + tolerance) {
        cull();
        return;
    }

    // The pixel's area on the surface: A_facing(z) / |n . p| with p = view / z (derivation in
    // caustic_pass.cpp); |n . p| = 1 on a plane parallel to the image plane.
    float cos_theta = 1.0;
    vec3 n = cross(dx, dy);
    if (u_orientation && dot(n, n) > 0.0) {
        cos_theta = max(abs(dot(normalize(n), view.xyz / z)), u_min_cos);
    }
    float area = u_area_scale * z * z / cos_theta;
    v_irradiance = max(photon.power, vec3(0.0)) / area;
    gl_Position = vec4((vec2(pixel) + 0.5) / vec2(u_viewport) * 2.0 - 1.0, 0.0, 1.0);
}
