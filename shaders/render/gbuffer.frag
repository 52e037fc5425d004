#version 450 core
// Writes what the lighting passes need per pixel: diffuse albedo, world normal, world position,
// the light-map lookup (UV, page layer, content) and emitted radiance. The lighting itself is
// computed once per pixel by the full-screen passes, so its cost does not grow with overdraw.

in vec3 v_position;
in vec3 v_normal;
in vec2 v_texcoord0;
in vec2 v_lightmap_uv;

uniform vec3 u_albedo;         // diffuse albedo factor (linear, [0,1])
// The base-colour texture (GL_SRGB8_ALPHA8: sampling returns linear values), or a 1x1 white
// one for untextured primitives; unit 15 is lighting/gpu's kBaseColorTextureUnit.
layout(binding = 15) uniform sampler2D u_base_color;
// The emissive texture (sRGB, sampled linear) or the white one; unit 16 is kEmissiveTextureUnit.
layout(binding = 16) uniform sampler2D u_emissive;
uniform vec3 u_emission;       // emitted radiance W/(m^2 sr)
uniform vec4 u_specular;       // rgb: specular colour F0 (0: none), a: transmission
uniform vec2 u_lightmap;       // x: IIM page layer (-1: none), y: 1 = irradiance, 0 = radiance
uniform vec3 u_camera;
uniform int u_double_sided;

layout(location = 0) out vec4 out_albedo;    // rgb albedo, a: 1 where the pixel is specular
layout(location = 1) out vec4 out_normal;    // xyz unit world normal
layout(location = 2) out vec4 out_position;  // xyz world position, w: 1 = covered
layout(location = 3) out vec4 out_lightmap;  // uv, page layer, content
layout(location = 4) out vec4 out_emission;  // rgb emitted radiance
layout(location = 5) out vec4 out_specular;  // rgb F0, a transmission

void main() {
    vec3 n = v_normal;
    if (!(dot(n, n) > 1e-12)) {
        // A mesh without normals: the flat triangle normal, from screen-space derivatives.
        n = cross(dFdx(v_position), dFdy(v_position));
        if (dot(n, u_camera - v_position) < 0.0) {
            n = -n;
        }
    }
    n = normalize(n);
    if (u_double_sided != 0 && dot(n, u_camera - v_position) < 0.0) {
        n = -n;  // a two-sided surface seen from its back is lit on that side
    }
    // glTF: base colour = factor x texture (alpha ignored: every material is drawn opaque).
    vec3 albedo = u_albedo * texture(u_base_color, v_texcoord0).rgb;
    out_albedo = vec4(albedo, any(greaterThan(u_specular.rgb, vec3(0.0))) ? 1.0 : 0.0);
    out_normal = vec4(n, 0.0);
    out_position = vec4(v_position, 1.0);
    out_lightmap = vec4(v_lightmap_uv, u_lightmap);
    // glTF: emission = factor x strength x texture, per pixel.
    out_emission = vec4(u_emission * texture(u_emissive, v_texcoord0).rgb, 0.0);
    out_specular = u_specular;
}
