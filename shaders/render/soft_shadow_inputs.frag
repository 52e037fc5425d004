#version 450 core
// Soft shadows, first pass (docs/METHOD.md §8.8): one light with a radius, its hard shadow per
// pixel as the direct pass would read it, and the distance from the receiver to the nearest
// occluder in front of it (metres along the light's ray; -1 where no tap was shadowed). The
// gather pass (soft_shadow_gather.frag) spreads the first by the second.

#include "render/direct_lights.glsl"

layout(binding = 1) uniform sampler2D u_normal;
layout(binding = 2) uniform sampler2D u_position;

layout(location = 0) out vec2 out_shadow;  // x lit (0..1), y the occluder's gap or -1

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 position = texelFetch(u_position, pixel, 0);
    out_shadow = vec2(1.0, -1.0);
    if (position.w == 0.0) {
        return;
    }
    vec3 n = texelFetch(u_normal, pixel, 0).xyz;
    Light light = u_lights[0];
    // A receiver the light does not reach says nothing about the shadow: lit, no occluder, so
    // it neither darkens nor sizes its neighbours' penumbrae.
    if (!any(greaterThan(unshadowed_irradiance(light, position.xyz, n), vec3(0.0)))) {
        return;
    }
    float gap;
    float lit = light_shadow_gap(light, position.xyz, n, u_filtered != 0, gap);
    out_shadow = vec2(lit, gap < 1e29 ? gap : -1.0);
}
