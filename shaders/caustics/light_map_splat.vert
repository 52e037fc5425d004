#version 450 core
// The caustic layer of the light maps (lighting/gpu CausticLightMaps), one vertex per photon
// (vertex pulling): the photon goes to the centre of the page texel its light-map UV falls in,
// carrying power / (the texel's world area). Photons on surfaces without a light map are
// dropped (layer -1); the geometry shader routes the rest to their page's layer.

#include "caustic_interface.h"

layout(std430, binding = CAUSTIC_PHOTONS_BINDING) readonly buffer Photons {
    Photon photons[];
};
layout(std430, binding = CAUSTIC_LIGHT_MAP_SURFACES_BINDING) readonly buffer Surfaces {
    vec4 surfaces[];  // page layer or -1, page size, 1 / texel area, unused
};

uniform float u_layer_size;  // texels across a layer (the largest page)

flat out vec3 v_irradiance;
flat out int v_layer;

void main() {
    Photon photon = photons[gl_VertexID];
    v_irradiance = vec3(0.0);
    v_layer = -1;
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    int surface_index = photon_surface(photon);
    if (surface_index < 0 || surface_index >= surfaces.length()) {
        return;
    }
    vec4 surface = surfaces[surface_index];
    if (surface.x < 0.0) {
        return;
    }
    float page_size = surface.y;
    vec2 uv = unpackUnorm2x16(photon.lightmap_uv_bits);
    // Texel x covers [x, x + 1) of uv * size; u = 1 belongs to the last texel.
    vec2 texel = min(floor(uv * page_size), vec2(page_size - 1.0)) + 0.5;
    v_irradiance = photon.power * surface.z;
    v_layer = int(surface.x);
    gl_Position = vec4(texel / u_layer_size * 2.0 - 1.0, 0.0, 1.0);
}
