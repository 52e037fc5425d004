#version 450 core
// Indirect light per pixel: from the IIM pages at the pixel's light-map UV (render/iim.glsl),
// or, for a receiver without a light map, from the irradiance probes
// (render/irradiance_probes.glsl). PROBES 0 (a variant, luxel/runtime/program_variants.hpp) leaves
// the probes out for a frame that has none: such pixels get no indirect light, as from empty
// probes.

#ifndef PROBES
#define PROBES 1
#endif

#include "render/iim.glsl"
#if PROBES
#include "render/irradiance_probes.glsl"
#endif

layout(binding = 0) uniform sampler2D u_albedo;
layout(binding = 1) uniform sampler2D u_normal;
layout(binding = 2) uniform sampler2D u_position;
layout(binding = 3) uniform sampler2D u_lightmap;  // uv, page layer, content

uniform vec3 u_camera;  // world position: the probes' visibility test looks from its side

layout(location = 0) out vec4 out_radiance;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 lookup = texelFetch(u_lightmap, pixel, 0);
    vec3 albedo = texelFetch(u_albedo, pixel, 0).rgb;
    if (lookup.z >= 0.0) {
        out_radiance = vec4(iim_radiance(lookup.xy, lookup.z, lookup.w > 0.5, albedo), 1.0);
        return;
    }
#if PROBES
    vec4 position = texelFetch(u_position, pixel, 0);
    if (position.w < 0.5) {
        out_radiance = vec4(0.0, 0.0, 0.0, 1.0);  // nothing drawn here: the sky's pixel
        return;
    }
    vec3 normal = texelFetch(u_normal, pixel, 0).xyz;
    out_radiance = vec4(lambert_radiance(albedo, probe_irradiance(position.xyz, normal, u_camera)), 1.0);
#else
    out_radiance = vec4(0.0, 0.0, 0.0, 1.0);
#endif
}
