#version 450 core
// The specular term of mirror and glass surfaces from their probe's cube map, drawn over the
// object's own pixels (depth test EQUAL-or-less against the G-buffer depth):
//   mirror: L = F(theta) * L_probe(reflect)                    F: Schlick with F0 = base colour
//   glass:  L = F * L_probe(reflect) + (1 - F)^k * t * T * L_probe(refract)
// t the transmission factor, k the surfaces a view ray crosses (2 through a closed solid, 1
// through a sheet) and T the rest of what it keeps: the base colour per surface crossed and
// the inside's absorption (renderer/src/scene_draws.cpp). The exit's Fresnel equals the
// entry's (a slab's and a sphere's exit angle is the entry's refracted one). The refracted ray
// is bent once at the entry surface and looks the probe up from the centre: a thin-object
// approximation, not a trace through the glass.

in vec3 v_position;
in vec3 v_normal;
in vec2 v_texcoord0;
in vec2 v_lightmap_uv;

layout(binding = 0) uniform samplerCube u_probe;

uniform vec3 u_camera;
uniform vec4 u_specular;  // rgb F0, a transmission
uniform float u_ior;
uniform vec4 u_transmittance;  // rgb T, a k

layout(location = 0) out vec4 out_radiance;

void main() {
    vec3 n = v_normal;
    if (!(dot(n, n) > 1e-12)) {
        n = cross(dFdx(v_position), dFdy(v_position));
    }
    n = normalize(n);
    vec3 v = normalize(v_position - u_camera);  // from the eye to the surface
    if (dot(n, v) > 0.0) {
        n = -n;
    }
    float cos_theta = clamp(-dot(n, v), 0.0, 1.0);
    vec3 f0 = u_specular.rgb;
    vec3 fresnel = f0 + (1.0 - f0) * pow(1.0 - cos_theta, 5.0);
    vec3 l = fresnel * texture(u_probe, reflect(v, n)).rgb;
    float transmission = u_specular.a;
    if (transmission > 0.0) {
        vec3 t = refract(v, n, 1.0 / max(u_ior, 1e-3));
        if (dot(t, t) > 0.0) {
            vec3 passed = pow(1.0 - fresnel, vec3(u_transmittance.a));
            l += passed * transmission * u_transmittance.rgb * texture(u_probe, t).rgb;
        }
    }
    out_radiance = vec4(max(l, vec3(0.0)), 1.0);
}
