#version 450 core
// Indirect light per pixel from the IIM pages at the pixel's light-map UV (render/iim.glsl).

#include "render/iim.glsl"

layout(binding = 0) uniform sampler2D u_albedo;
layout(binding = 3) uniform sampler2D u_lightmap;  // uv, page layer, content

layout(location = 0) out vec4 out_radiance;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 lookup = texelFetch(u_lightmap, pixel, 0);
    vec3 albedo = texelFetch(u_albedo, pixel, 0).rgb;
    out_radiance = vec4(iim_radiance(lookup.xy, lookup.z, lookup.w > 0.5, albedo), 1.0);
}
