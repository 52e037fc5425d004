// For the composition: the caustic term L_caustics = albedo / pi * E of a diffuse surface,
// E read from CausticPass::irradiance_texture() (RGBA32F, rgb = irradiance in W/m^2).

#include "../common/radiometry.glsl"

vec3 caustic_radiance(sampler2D caustic_irradiance, ivec2 pixel, vec3 albedo) {
    return lambert_radiance(albedo, texelFetch(caustic_irradiance, pixel, 0).rgb);
}
