// Reading the caustic layer of the light maps (lighting/gpu CausticLightMaps): caustic
// irradiance per page texel, at the IIM page's layer and coordinates (render/iim.glsl's
// u_page_size gives the page sizes). Read at the nearest texel, not bilinearly: the layer bins
// photons only inside the charts, and a bilinear tap on a chart's border would blend in the
// empty texel beside it (the IIM pages fill theirs by dilation; this layer is rebuilt too
// often for that to pay).

// Unit 20: CausticLightMaps::kTextureUnit, clear of 17 (sky), 18-19 (probes).
layout(binding = 20) uniform sampler2DArray u_caustic_light_map;
uniform bool u_caustic_layer = false;  // false: no layer bound, no caustic term

// L_caustic = albedo / pi * E at light-map `uv` of page `layer_value` (< 0: none).
vec3 caustic_light_map_radiance(vec2 uv, float layer_value, vec3 albedo) {
    int layer = int(layer_value);
    if (!u_caustic_layer || layer_value < 0.0 || layer >= u_page_size.length()) {
        return vec3(0.0);
    }
    int size = u_page_size[layer];
    if (size <= 0) {
        return vec3(0.0);
    }
    ivec2 texel = clamp(ivec2(floor(uv * float(size))), ivec2(0), ivec2(size - 1));
    vec3 irradiance = max(texelFetch(u_caustic_light_map, ivec3(texel, layer), 0).rgb, vec3(0.0));
    return lambert_radiance(albedo, irradiance);
}
