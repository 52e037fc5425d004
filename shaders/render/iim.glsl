// Reading the IIM pages (lighting/gpu/include/luxel/lighting/gpu/lightmap_textures.hpp): bilinear
// (or cubic B-spline on request), through the per-texel front/back blend
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
// Cubic B-spline filtering of the pages instead of bilinear (FrameSettings::bicubic_light_maps):
// a variant of the program (luxel/runtime/program_variants.hpp), bilinear where not defined.
#ifndef IIM_BICUBIC
#define IIM_BICUBIC 0
#endif

vec3 iim_shown(ivec3 texel) {
    vec3 previous = texelFetch(u_iim_previous, texel, 0).rgb;
    vec3 current = texelFetch(u_iim_current, texel, 0).rgb;
    vec2 fade = texelFetch(u_iim_fades, texel, 0).rg;
    float weight = fade.y > 0.0 ? clamp((u_now - fade.x) / fade.y, 0.0, 1.0) : 1.0;
    return mix(previous, current, weight);
}

// Bilinear between the four texels around `f` (page texel coordinates, centres at integers).
vec3 iim_bilinear(vec2 f, int layer, int size) {
    ivec2 t0 = ivec2(f);
    ivec2 t1 = min(t0 + 1, ivec2(size - 1));
    vec2 w = f - vec2(t0);
    vec3 top = mix(iim_shown(ivec3(t0.x, t0.y, layer)), iim_shown(ivec3(t1.x, t0.y, layer)), w.x);
    vec3 bottom =
        mix(iim_shown(ivec3(t0.x, t1.y, layer)), iim_shown(ivec3(t1.x, t1.y, layer)), w.x);
    return mix(top, bottom, w.y);
}

// The uniform cubic B-spline's weights for the taps at -1, 0, 1, 2 about a fraction t. Of the
// cubic filters this one has no negative lobe: no ringing around a bright texel and no negative
// light, and it is smooth (C2) where bilinear has a crease at every texel centre, the light
// map's grid that shows on gradients. It approximates rather than interpolates (a texel's own
// value is blurred by its neighbours, 1/6 each way) but reproduces a linear gradient exactly.
vec4 bspline_weights(float t) {
    float s = 1.0 - t;
    float t2 = t * t;
    float t3 = t2 * t;
    return vec4(s * s * s, 3.0 * t3 - 6.0 * t2 + 4.0, -3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0, t3) /
           6.0;
}

// Bicubic B-spline over the 4 x 4 texels around `f`, each blended before weighting. It reads
// two texels beyond a chart's last covered one: luxel-prep's `--padding 2` keeps those in the
// chart's own filled gutter (with the default 1 the outermost tap, weight at most 1/48 per axis,
// falls in a neighbour's).
vec3 iim_bicubic(vec2 f, int layer, int size) {
    ivec2 base = ivec2(floor(f));
    vec2 t = f - vec2(base);
    vec4 wx = bspline_weights(t.x);
    vec4 wy = bspline_weights(t.y);
    vec3 sum = vec3(0.0);
    for (int j = 0; j < 4; ++j) {
        int y = clamp(base.y + j - 1, 0, size - 1);
        vec3 row = vec3(0.0);
        for (int i = 0; i < 4; ++i) {
            int x = clamp(base.x + i - 1, 0, size - 1);
            row += wx[i] * iim_shown(ivec3(x, y, layer));
        }
        sum += wy[j] * row;
    }
    return sum;
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
    // Texel centres sit at integer + 0.5; clamp so every tap stays on the page.
    vec2 f = clamp(uv * extent - 0.5, vec2(0.0), vec2(extent - 1.0));
#if IIM_BICUBIC
    vec3 value = iim_bicubic(f, layer, size);
#else
    vec3 value = iim_bilinear(f, layer, size);
#endif
    value = max(value, vec3(0.0));
    return irradiance ? lambert_radiance(albedo, value) : value;
}
