#version 450 core
// The frame in linear HDR radiance (docs/METHOD.md §8.1):
//     L = L_indirect + L_caustics + L_specular + sum_i L_direct(i) * shadow(i)   (+ L_emitted)
// each term weighted 0 or 1 by its toggle. The caustic input is either irradiance (multiplied
// by albedo / pi here) or radiance. Tone mapping happens later, for display only.

#include "common/radiometry.glsl"
#include "common/sky.glsl"

layout(binding = 0) uniform sampler2D u_albedo;
layout(binding = 2) uniform sampler2D u_position;
layout(binding = 4) uniform sampler2D u_emission;
layout(binding = 5) uniform sampler2D u_direct;
layout(binding = 6) uniform sampler2D u_indirect;
layout(binding = 7) uniform sampler2D u_caustics;
layout(binding = 8) uniform sampler2D u_specular;
layout(binding = 9) uniform sampler2D u_sky;

uniform vec4 u_terms;           // direct, indirect, caustics, specular (0 or 1; 0 if absent)
uniform float u_emission_on;
uniform int u_caustics_irradiance;  // 1: the caustic input is irradiance W/m^2
uniform int u_sky_on;               // 1: where nothing was drawn, the sky
uniform mat4 u_inverse_view_projection;
uniform vec3 u_camera;
uniform vec2 u_viewport;

layout(location = 0) out vec4 out_radiance;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    if (texelFetch(u_position, pixel, 0).w == 0.0) {
        // Nothing drawn: the sky along the pixel's ray, or no light at all from the void.
        vec3 l = vec3(0.0);
        if (u_sky_on != 0) {
            vec2 ndc = 2.0 * gl_FragCoord.xy / u_viewport - 1.0;
            vec4 far = u_inverse_view_projection * vec4(ndc, 0.5, 1.0);
            l = sky_radiance(u_sky, far.xyz / far.w - u_camera);
        }
        out_radiance = vec4(l, 1.0);
        return;
    }
    vec3 l = vec3(0.0);
    if (u_terms.x > 0.0) {
        l += texelFetch(u_direct, pixel, 0).rgb;
    }
    if (u_terms.y > 0.0) {
        l += texelFetch(u_indirect, pixel, 0).rgb;
    }
    if (u_terms.z > 0.0) {
        vec3 caustic = texelFetch(u_caustics, pixel, 0).rgb;
        if (u_caustics_irradiance != 0) {
            caustic = lambert_radiance(texelFetch(u_albedo, pixel, 0).rgb, caustic);
        }
        l += caustic;
    }
    if (u_terms.w > 0.0) {
        l += texelFetch(u_specular, pixel, 0).rgb;
    }
    if (u_emission_on > 0.0) {
        l += texelFetch(u_emission, pixel, 0).rgb;
    }
    out_radiance = vec4(l, 1.0);
}
