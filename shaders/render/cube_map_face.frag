#version 450 core
// Forward shading of one face of a specular cube map (around a mirror or glass
// object): the diffuse scene as the main view shows it, emitted + direct (first light batch,
// with shadows) + indirect from the IIM + caustics from the caustic layer of the light maps
// (the camera's screen-space caustics do not reach this view), at the cube map's reduced
// resolution. Alpha holds the distance from the centre to the surface shown.

#include "render/direct_lights.glsl"
#include "render/iim.glsl"
#include "render/caustic_light_map.glsl"

in vec3 v_position;
in vec3 v_normal;
in vec2 v_texcoord0;
in vec2 v_lightmap_uv;

uniform vec3 u_albedo;  // diffuse albedo factor
// The base-colour texture or a 1x1 white one, as in render/gbuffer.frag (unit 15 is clear of
// the shadow maps and IIM pages bound here).
layout(binding = 15) uniform sampler2D u_base_color;
// The emissive texture (sRGB, sampled linear) or the white one; unit 16 is kEmissiveTextureUnit.
layout(binding = 16) uniform sampler2D u_emissive;
uniform vec3 u_emission;
uniform vec2 u_lightmap;  // page layer, content
uniform vec3 u_camera;    // the cube map's centre

layout(location = 0) out vec4 out_radiance;

void main() {
    vec3 n = v_normal;
    if (!(dot(n, n) > 1e-12)) {
        n = cross(dFdx(v_position), dFdy(v_position));
    }
    n = normalize(n);
    if (dot(n, u_camera - v_position) < 0.0) {
        n = -n;  // the cube map sees sheets from either side
    }
    vec3 albedo = u_albedo * texture(u_base_color, v_texcoord0).rgb;
    vec3 l = u_emission * texture(u_emissive, v_texcoord0).rgb +
             lambert_radiance(albedo, batch_irradiance(v_position, n)) +
             iim_radiance(v_lightmap_uv, u_lightmap.x, u_lightmap.y > 0.5, albedo) +
             caustic_light_map_radiance(v_lightmap_uv, u_lightmap.x, albedo);
    // Alpha: how far the surface is from the cube map's centre, which the specular term's
    // parallax correction looks along (render/specular.frag); 1e6 where nothing was drawn.
    out_radiance = vec4(l, max(length(v_position - u_camera), 1e-6));
}
