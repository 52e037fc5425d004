#version 450 core
// The specular term of mirror and glass surfaces from their probe's cube map, drawn over the
// object's own pixels (depth test EQUAL-or-less against the G-buffer depth):
//   mirror: L = F(theta) * L_probe(reflect)                    F: Schlick with F0 = base colour
//   glass:  L = F * L_probe(reflect) + (1 - F)^k * t * T * L_probe(refract)
// t the transmission factor, k the surfaces a view ray crosses (2 through a closed solid, 1
// through a sheet) and T the rest of what it keeps: the base colour per surface crossed and
// the inside's absorption (renderer/src/scene_draws.cpp). The exit's Fresnel equals the
// entry's (a slab's and a sphere's exit angle is the entry's refracted one). The refracted ray
// is bent once at the entry surface: a thin-object approximation, not a trace through the
// glass.
//
// Parallax: a cube map shows the scene as seen from its centre, and a ray that leaves the
// surface elsewhere sees a different point (looked up by its direction alone, every pixel of a
// pool's water would show the same patch of its floor). The faces store each texel's distance
// from the centre in alpha, which describes the surface the cube map saw; where it saw nothing
// (the sky, the void) the distance is 1e6 m, not 0: filtered across a silhouette, a 0 would
// put a phantom surface close to the centre that rays near it stop on (black pixels);
// probe_along() marches the ray against it (distance impostors, Szirmay-Kalos et al.,
// Eurographics 2005): geometric steps from a few millimetres to the cube map's reach find the
// first step beyond that surface, and bisection between it and the step before finds the hit.

in vec3 v_position;
in vec3 v_normal;
in vec2 v_texcoord0;
in vec2 v_lightmap_uv;

layout(binding = 0) uniform samplerCube u_probe;

uniform vec3 u_camera;
uniform vec3 u_probe_centre;  // the cube map's centre, world
uniform float u_probe_reach;  // metres: the farthest its faces draw
uniform vec4 u_specular;  // rgb F0, a transmission
uniform float u_ior;
uniform vec4 u_transmittance;  // rgb T, a k

layout(location = 0) out vec4 out_radiance;

// Reflections weaker than this are not marched (see main()).
const float kMarchedReflection = 0.2;

// How far a point is beyond the surface the probe saw in its direction (> 0: behind it), for a
// point `p` relative to the centre; negative where the probe saw nothing there.
float beyond_surface(vec3 p) {
    float distance = texture(u_probe, p).a;
    return distance > 0.0 ? length(p) - distance : -1.0;
}

// The probe's radiance along the ray from `origin` (relative to the probe's centre) in unit
// direction `dir`.
vec3 probe_along(vec3 origin, vec3 dir) {
    const int kSteps = 8;
    const int kBisections = 4;
    float reach = max(u_probe_reach, 1e-3);
    float first = 1e-3 * reach;
    float growth = pow(reach / first, 1.0 / float(kSteps - 1));
    float before = 0.0;
    for (int i = 0; i < kSteps; ++i) {
        float t = first * pow(growth, float(i));
        if (beyond_surface(origin + t * dir) >= 0.0) {
            float lo = before;
            float hi = t;
            for (int j = 0; j < kBisections; ++j) {
                float mid = 0.5 * (lo + hi);
                if (beyond_surface(origin + mid * dir) >= 0.0) {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            return texture(u_probe, origin + hi * dir).rgb;
        }
        before = t;
    }
    return texture(u_probe, dir).rgb;  // nothing within reach: what lies that way far off
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
    vec3 origin = v_position - u_probe_centre;
    // A weak reflection (glass and water face on: F about 0.04) is looked up by its direction
    // alone: its parallax error is a few per cent of a few per cent, and the march is most of
    // this pass's cost on a software rasteriser.
    vec3 towards = reflect(v, n);
    vec3 l = fresnel * (max(fresnel.r, max(fresnel.g, fresnel.b)) > kMarchedReflection
                            ? probe_along(origin, towards)
                            : texture(u_probe, towards).rgb);
    float transmission = u_specular.a;
    if (transmission > 0.0) {
        vec3 t = refract(v, n, 1.0 / max(u_ior, 1e-3));
        if (dot(t, t) > 0.0) {
            vec3 passed = pow(1.0 - fresnel, vec3(u_transmittance.a));
            // Through a sheet (one surface: water, a pane) the refracted ray goes on straight
            // and is marched; through a closed solid it bends again where it leaves, which the
            // march cannot follow, and the direction alone was measured closer (cornell's glass
            // sphere, docs/RESULTS.md).
            t = normalize(t);
            vec3 seen = u_transmittance.a < 1.5 ? probe_along(origin, t) : texture(u_probe, t).rgb;
            l += passed * transmission * u_transmittance.rgb * seen;
        }
    }
    out_radiance = vec4(max(l, vec3(0.0)), 1.0);
}
