#version 450 core
// The specular term of mirror and glass surfaces from their probe's cube map, drawn over the
// object's own pixels (depth test EQUAL-or-less against the G-buffer depth):
//   mirror: L = F(theta) * L_probe(reflect)                    F: Schlick with F0 = base colour
//   glass:  L = F * L_probe(reflect) + (1 - F)^k * t * T * L_probe(refract)
// t the transmission factor, k the surfaces a view ray crosses (2 through a closed solid, 1
// through a sheet) and T the rest of what it keeps: the base colour per surface crossed and
// the inside's absorption (renderer/src/scene_draws.cpp). The exit's Fresnel is taken as the
// entry's (a slab's and a sphere's exit angle is the entry's refracted one).
//
// Through closed glass, where the frame has its far side (GlassExits, u_trace_exit), the ray
// is refracted twice (docs/METHOD.md §8.3): bent at the entry, followed through the solid to
// where it leaves it (the first point along it that lies beyond the far side the frame drew at
// its pixel), bent again by the far side's normal there (reflected where it cannot leave), and
// absorbed over that path's length. Elsewhere it is bent once and looks the probe up from the
// centre: a thin-object approximation.

in vec3 v_position;
in vec3 v_normal;
in vec2 v_texcoord0;
in vec2 v_lightmap_uv;

layout(binding = 0) uniform samplerCube u_probe;
layout(binding = 1) uniform sampler2D u_exit_position;  // xyz, w: 1 = covered
layout(binding = 2) uniform sampler2D u_exit_normal;    // xyz outward

uniform vec3 u_camera;
uniform mat4 u_view_projection;
uniform vec4 u_specular;  // rgb F0, a transmission
uniform float u_ior;
uniform vec4 u_transmittance;  // rgb T, a k
uniform int u_trace_exit;      // 1: closed glass, and the frame has its far side
uniform vec3 u_glass_tint;     // the two surfaces' tint
uniform vec3 u_absorption;     // ln(transmittance) per metre inside
uniform float u_reach;         // the object's box diagonal, m: no path inside is longer

layout(location = 0) out vec4 out_radiance;

// The far side's texel under world point q, or w = 0 off screen or off the glass.
vec4 far_side_at(vec3 q, out ivec2 texel) {
    vec4 clip = u_view_projection * vec4(q, 1.0);
    texel = ivec2(-1);
    if (!(clip.w > 0.0)) {
        return vec4(0.0);
    }
    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    ivec2 size = textureSize(u_exit_position, 0);
    texel = ivec2(floor(uv * vec2(size)));
    if (any(lessThan(texel, ivec2(0))) || any(greaterThanEqual(texel, size))) {
        return vec4(0.0);
    }
    return texelFetch(u_exit_position, texel, 0);
}

bool beyond_far_side(vec3 q) {
    ivec2 texel;
    vec4 far_side = far_side_at(q, texel);
    return far_side.w == 0.0 || distance(q, u_camera) > distance(far_side.xyz, u_camera);
}

// Follows `dir` from the entry point p through the solid: the distance to where it leaves
// (16 steps over the object's reach, then 6 halvings), and the far side's outward normal
// there; false when it does not leave within the reach or no normal is found.
bool leave_solid(vec3 p, vec3 dir, out float s_exit, out vec3 exit_normal) {
    const int kSteps = 16;
    float step = max(u_reach, 1e-6) / float(kSteps);
    float inside = 0.0;
    float outside = -1.0;
    for (int i = 1; i <= kSteps; ++i) {
        if (beyond_far_side(p + float(i) * step * dir)) {
            outside = float(i) * step;
            break;
        }
        inside = float(i) * step;
    }
    if (outside < 0.0) {
        return false;
    }
    for (int i = 0; i < 6; ++i) {
        float mid = 0.5 * (inside + outside);
        if (beyond_far_side(p + mid * dir)) {
            outside = mid;
        } else {
            inside = mid;
        }
    }
    s_exit = 0.5 * (inside + outside);
    ivec2 texel;
    vec4 far_side = far_side_at(p + inside * dir, texel);
    if (far_side.w == 0.0) {
        return false;
    }
    exit_normal = texelFetch(u_exit_normal, texel, 0).xyz;
    return dot(exit_normal, exit_normal) > 0.25;
}

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
        float eta = max(u_ior, 1e-3);
        vec3 t = refract(v, n, 1.0 / eta);
        if (dot(t, t) > 0.0) {
            vec3 passed = pow(1.0 - fresnel, vec3(u_transmittance.a));
            vec3 kept = u_transmittance.rgb;
            float s_exit;
            vec3 exit_normal;
            if (u_trace_exit == 1 && leave_solid(v_position, t, s_exit, exit_normal)) {
                vec3 m = normalize(exit_normal);
                vec3 out_dir = refract(t, -m, eta);
                // Where it cannot leave (total internal reflection) it turns back inside; its
                // later way out is not followed: the reflected direction stands for it.
                t = dot(out_dir, out_dir) > 0.0 ? out_dir : reflect(t, -m);
                kept = u_glass_tint * exp(u_absorption * s_exit);
            }
            l += passed * transmission * kept * texture(u_probe, t).rgb;
        }
    }
    out_radiance = vec4(max(l, vec3(0.0)), 1.0);
}
