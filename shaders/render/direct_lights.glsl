// The lights of one batch with their shadow maps, and the irradiance they deliver: shared by
// the deferred direct pass and the forward shading of specular probe faces.

#include "render/shadow.glsl"

#ifndef LIGHTS_PER_BATCH
#define LIGHTS_PER_BATCH 4
#endif

layout(std140, binding = 0) uniform LightBatch {
    Light u_lights[LIGHTS_PER_BATCH];
    ivec4 u_light_count;  // x: lights in this batch
};

// Light i of the batch reads cube slot i or 2D slot i, as its map's kind says.
layout(binding = 4) uniform samplerCubeShadow u_cube_shadows[LIGHTS_PER_BATCH];
layout(binding = 8) uniform sampler2DShadow u_map_shadows[LIGHTS_PER_BATCH];

uniform int u_filtered;

// The shadow of the light in `slot`, read through constant indices only. GLSL 4.5 allows a
// sampler array indexed by a dynamically uniform expression such as the loop's light index,
// but llvmpipe gave some lanes along the sandbox level's wall corners another slot's map that
// way (docs/RESULTS.md, "The sun leaks into the sandbox level's corners"); a switch with a
// constant index per case reads the right one everywhere.
#define LUXEL_SLOT_SHADOW(k)                                               \
    case k:                                                                \
        return cube ? cube_shadow(u_cube_shadows[k], light, p, n, filtered) \
                    : map_shadow(u_map_shadows[k], light, p, n, filtered);

float slot_shadow(int slot, Light light, vec3 p, vec3 n, bool filtered) {
    bool cube = int(light.params.w) == SHADOW_CUBE;
    switch (slot) {
        LUXEL_SLOT_SHADOW(0)
        LUXEL_SLOT_SHADOW(1)
        LUXEL_SLOT_SHADOW(2)
        LUXEL_SLOT_SHADOW(3)
    }
    return 1.0;
}
#if LIGHTS_PER_BATCH != 4
#error "slot_shadow has one case per slot of a batch"
#endif

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
            lit = slot_shadow(i, light, p, n, filtered);
        }
        irradiance += e * lit;
    }
    return irradiance;
}
