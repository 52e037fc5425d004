// The lights of one batch with their shadow maps, and the irradiance they deliver: shared by
// the deferred direct pass and the forward shading of specular probe faces.

#include "render/shadow.glsl"

#ifndef LIGHTS_PER_BATCH
#define LIGHTS_PER_BATCH 4
#endif
// The shadow-map shapes the batch's lights use (variants of the direct pass,
// luxel/runtime/program_variants.hpp): a shape no light of the batch has is compiled out. Both
// where not defined.
#ifndef CUBE_SHADOWS
#define CUBE_SHADOWS 1
#endif
#ifndef MAP_SHADOWS
#define MAP_SHADOWS 1
#endif

layout(std140, binding = 0) uniform LightBatch {
    Light u_lights[LIGHTS_PER_BATCH];
    ivec4 u_light_count;  // x: lights in this batch
};

uniform int u_filtered;

// sum_i E_i(p, n) * shadow_i(p) over the batch, W/m^2.
vec3 batch_irradiance(vec3 p, vec3 n) {
    bool filtered = u_filtered != 0;
    vec3 irradiance = vec3(0.0);
    for (int i = 0; i < LIGHTS_PER_BATCH; ++i) {
        if (i >= u_light_count.x) {
            break;
        }
        Light light = u_lights[i];
        vec3 e = unshadowed_irradiance(light, p, n);
        if (!any(greaterThan(e, vec3(0.0)))) {
            continue;
        }
        float lit = 1.0;
        if (light.intensity_shadow.w >= 0.0) {
#if CUBE_SHADOWS && MAP_SHADOWS
            lit = int(light.params.w) == SHADOW_CUBE ? cube_shadow(light, p, n, filtered)
                                                     : map_shadow(light, p, n, filtered);
#elif CUBE_SHADOWS
            lit = cube_shadow(light, p, n, filtered);
#elif MAP_SHADOWS
            lit = map_shadow(light, p, n, filtered);
#endif
        }
        irradiance += e * lit;
    }
    return irradiance;
}
