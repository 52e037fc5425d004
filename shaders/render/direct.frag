#version 450 core
// Direct light of up to LIGHTS_PER_BATCH lights per pixel, each times its shadow:
//     L_direct = albedo / pi * sum_i E_i * shadow_i
// Batches are blended additively, so any number of lights is drawn LIGHTS_PER_BATCH at a time
// with a fixed number of texture units.

#include "common/radiometry.glsl"
#include "render/direct_lights.glsl"

layout(binding = 0) uniform sampler2D u_albedo;
layout(binding = 1) uniform sampler2D u_normal;
layout(binding = 2) uniform sampler2D u_position;

layout(location = 0) out vec4 out_radiance;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 position = texelFetch(u_position, pixel, 0);
    if (position.w == 0.0) {
        out_radiance = vec4(0.0);
        return;
    }
    vec3 n = texelFetch(u_normal, pixel, 0).xyz;
    vec3 albedo = texelFetch(u_albedo, pixel, 0).rgb;
    out_radiance = vec4(lambert_radiance(albedo, batch_irradiance(position.xyz, n)), 1.0);
}
