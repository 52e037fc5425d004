#version 450 core
// The frame in linear HDR radiance (docs/METHOD.md §8.1):
//     L = L_indirect + L_caustics + L_specular + sum_i L_direct(i) * shadow(i)   (+ L_emitted)
// each term weighted 0 or 1 by its toggle. The caustic input is either irradiance (multiplied
// by albedo / pi here) or radiance; with u_caustic_layer, light-mapped pixels read the caustic
// layer of the light maps instead (FrameSettings::caustic_layer_in_view). Tone mapping happens
// later, for display only.
//
// Variants (luxel/runtime/program_variants.hpp) compile out what a frame does not have: the
// caustic layer (CAUSTIC_LAYER), the sky (SKY) and the mixing by its edge mask (SKY_MASK). With
// a mask the frame draws twice: every pixel without the mixing, then, under a stencil of the
// pixels the mask mixes (sky_fill_mask.frag), those with it. All on where not defined.
#ifndef CAUSTIC_LAYER
#define CAUSTIC_LAYER 1
#endif
#ifndef SKY
#define SKY 1
#endif
#ifndef SKY_MASK
#define SKY_MASK 1
#endif

#include "common/radiometry.glsl"
#include "common/sky.glsl"
// iim.glsl for the page sizes the caustic layer is read with.
#include "render/iim.glsl"
#include "render/caustic_light_map.glsl"
#include "render/sky_share.glsl"

layout(binding = 0) uniform sampler2D u_albedo;
layout(binding = 2) uniform sampler2D u_position;
layout(binding = 3) uniform sampler2D u_lightmap;  // light-map uv, page layer, content
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

// How many caustic-layer texels one pixel steps over at `pixel` (whose G-buffer light-map entry
// is `lookup`, on a page): per screen axis the smaller step to a neighbour on the same page (the
// other side may lie across a chart seam), the larger of the two axes; 1 where no neighbour
// tells.
float layer_texels_per_pixel(ivec2 pixel, vec4 lookup) {
    int layer = int(lookup.z);
    if (layer >= u_page_size.length()) {
        return 1.0;
    }
    float size = float(u_page_size[layer]);
    ivec2 viewport = ivec2(u_viewport);
    float texels = 0.0;
    bool found = false;
    for (int axis = 0; axis < 2; ++axis) {
        float along = 1e30;
        for (int side = -1; side <= 1; side += 2) {
            ivec2 q = pixel + (axis == 0 ? ivec2(side, 0) : ivec2(0, side));
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, viewport))) {
                continue;
            }
            vec4 other = texelFetch(u_lightmap, q, 0);
            if (other.z == lookup.z) {
                along = min(along, length(other.xy - lookup.xy) * size);
            }
        }
        if (along < 1e30) {
            texels = max(texels, along);
            found = true;
        }
    }
    return found ? texels : 1.0;
}

// The surfaces' radiance at a covered pixel.
vec3 surface_radiance(ivec2 pixel) {
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
#if CAUSTIC_LAYER
        vec4 lookup = u_caustic_layer ? texelFetch(u_lightmap, pixel, 0) : vec4(-1.0);
        if (lookup.z >= 0.0) {
            // Where a layer texel covers a pixel or less the layer is shown; where the camera is
            // so close that a texel spans two pixels or more, the splat, which keeps a pixel's
            // detail (the layer would show its texels as blocks); a blend between.
            float weight = smoothstep(0.5, 1.0, layer_texels_per_pixel(pixel, lookup));
            vec3 layer = caustic_light_map_radiance(lookup.xy, lookup.z,
                                                    texelFetch(u_albedo, pixel, 0).rgb);
            caustic = mix(caustic, layer, weight);
        }
#endif
        l += caustic;
    }
    if (u_terms.w > 0.0) {
        l += texelFetch(u_specular, pixel, 0).rgb;
    }
    if (u_emission_on > 0.0) {
        l += texelFetch(u_emission, pixel, 0).rgb;
    }
    return l;
}

// The sky along the ray through the pixel centre.
vec3 sky_through_pixel() {
    vec2 ndc = 2.0 * gl_FragCoord.xy / u_viewport - 1.0;
    vec4 far = u_inverse_view_projection * vec4(ndc, 0.5, 1.0);
    return sky_radiance(u_sky, far.xyz / far.w - u_camera);
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    bool surface = texelFetch(u_position, pixel, 0).w != 0.0;
#if SKY && SKY_MASK
    float sky_part = u_sky_on != 0 ? sky_share(pixel) : 0.0;
#else
    float sky_part = 0.0;
#endif
    if (surface) {
        vec3 l = surface_radiance(pixel);
#if SKY && SKY_MASK
        // A silhouette against the sky: the pixel shows the sky over the share the surfaces
        // leave (SkyCoverage: one sample at the centre cannot tell how much that is).
        if (sky_part > 0.0) {
            l = mix(l, sky_through_pixel(), sky_part);
        }
#endif
        out_radiance = vec4(l, 1.0);
        return;
    }
    // Nothing drawn at the centre: the sky along the pixel's ray, or no light at all from the
    // void.
#if SKY
    vec3 l = u_sky_on != 0 ? sky_through_pixel() : vec3(0.0);
#else
    vec3 l = vec3(0.0);
#endif
#if SKY_MASK
    float surface_part = u_coverage_scale > 0 ? 1.0 - sky_part : 0.0;
    if (surface_part > 0.0) {
        // Surfaces cover part of it: their light as the neighbours whose centres they cover
        // show it.
        vec3 sum = vec3(0.0);
        float count = 0.0;
        ivec2 size = ivec2(u_viewport);
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
                ivec2 q = pixel + ivec2(dx, dy);
                if ((dx != 0 || dy != 0) && all(greaterThanEqual(q, ivec2(0))) &&
                    all(lessThan(q, size)) && texelFetch(u_position, q, 0).w != 0.0) {
                    sum += surface_radiance(q);
                    count += 1.0;
                }
            }
        }
        if (count > 0.0) {
            l = mix(l, sum / count, surface_part);
        }
    }
#endif
    out_radiance = vec4(l, 1.0);
}
