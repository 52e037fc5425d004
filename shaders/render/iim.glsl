// Reading the IIM pages (lighting/gpu/include/luxel/lighting/gpu/lightmap_textures.hpp): bilinear, through the
// per-texel front/back blend
//     shown = mix(previous, current, clamp((now - committed) / fade, 0, 1)),
// blended per texel before the bilinear weights, as IimPage::shown and RadiancePage::sample do
// on the CPU, texel for texel. Pages holding irradiance (textured materials) are multiplied by
// albedo / pi; pages holding radiance are already premultiplied.

#include "common/radiometry.glsl"

layout(binding = 12) uniform sampler2DArray u_iim_previous;
layout(binding = 13) uniform sampler2DArray u_iim_current;
layout(binding = 14) uniform sampler2DArray u_iim_fades;  // (committed, fade seconds)

layout(std430, binding = 1) readonly buffer PageSizes {
    int u_page_size[];
};

uniform float u_now;    // seconds, the clock the IIM was committed with

vec3 iim_shown(ivec3 texel) {
    vec3 previous = texelFetch(u_iim_previous, texel, 0).rgb;
    vec3 current = texelFetch(u_iim_current, texel, 0).rgb;
    vec2 fade = texelFetch(u_iim_fades, texel, 0).rg;
    float weight = fade.y > 0.0 ? clamp((u_now - fade.x) / fade.y, 0.0, 1.0) : 1.0;
    return mix(previous, current, weight);
}

// L_indirect at light-map `uv` of page `layer` (< 0: none); `irradiance` says what the page
// holds.
vec3 iim_radiance(vec2 uv, float layer_value, bool irradiance, vec3 albedo) {
    int layer = int(layer_value);
    if (layer_value < 0.0 || layer >= u_page_size.length()) {
        return vec3(0.0);
    }
    int size = u_page_size[layer];
    if (size <= 0) {
        return vec3(0.0);
    }
    float extent = float(size);
    // Texel centres sit at integer + 0.5; clamp so both taps stay on the page.
    vec2 f = clamp(uv * extent - 0.5, vec2(0.0), vec2(extent - 1.0));
    ivec2 t0 = ivec2(f);
    ivec2 t1 = min(t0 + 1, ivec2(size - 1));
    vec2 w = f - vec2(t0);
    vec3 top = mix(iim_shown(ivec3(t0.x, t0.y, layer)), iim_shown(ivec3(t1.x, t0.y, layer)), w.x);
    vec3 bottom =
        mix(iim_shown(ivec3(t0.x, t1.y, layer)), iim_shown(ivec3(t1.x, t1.y, layer)), w.x);
    vec3 value = max(mix(top, bottom, w.y), vec3(0.0));
    return irradiance ? lambert_radiance(albedo, value) : value;
}
