#version 450 core
// The specular term of mirror and glass surfaces from their probe's cube map, drawn over the
// object's own pixels (depth test EQUAL-or-less against the G-buffer depth):
//   mirror: L = F(theta) * L_probe(reflect)                    F: Schlick with F0 = base colour
//   glass:  L = F * L_probe(reflect) + (1 - F)^k * t * T * L_probe(refract)
// t the transmission factor, k the surfaces a view ray crosses (2 through a closed solid, 1
// through a sheet) and T the rest of what it keeps: the base colour per surface crossed and
// the inside's absorption (renderer/src/scene_draws.cpp); a ray that ends inside a closed
// solid keeps (1 - F) T / ior^2 and its own path's absorption (through_solid()). The exit's Fresnel equals the
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
// A closed solid's own optics, for a view ray that ends on a surface inside it (a floor under a
// glass block resting on it): the tint of one surface, the volume's attenuation (rgb colour,
// a distance in metres; 0: clear), and the solid's half extent around the probe's centre.
uniform vec3 u_tint;
uniform vec4 u_attenuation;
uniform vec3 u_probe_extent;

layout(location = 0) out vec4 out_radiance;

// Reflections weaker than this are not marched (see main()).
const float kMarchedReflection = 0.2;

// How far a point is beyond the surface the probe saw in its direction (> 0: behind it), for a
// point `p` relative to the centre; negative where the probe saw nothing there.
float beyond_surface(vec3 p) {
    float distance = texture(u_probe, p).a;
    return distance > 0.0 ? length(p) - distance : -1.0;
}

// Where the ray from `origin` (relative to the probe's centre) in unit direction `dir` meets
// the surface the probe saw; false when nothing lies within the probe's reach.
bool march(vec3 origin, vec3 dir, out vec3 hit) {
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
            hit = origin + hi * dir;
            return true;
        }
        before = t;
    }
    hit = dir;
    return false;
}

// The probe's radiance along the ray from `origin` (relative to the probe's centre) in unit
// direction `dir`.
vec3 probe_along(vec3 origin, vec3 dir) {
    vec3 hit;
    // Nothing within reach: what lies that way far off.
    return texture(u_probe, march(origin, dir, hit) ? hit : dir).rgb;
}

// What a view ray refracted into a closed solid at `origin` keeps and sees. Where the surface it
// meets lies inside the solid's box (the floor a block rests on: the probe, drawn without the
// solid, sees it there), the ray ends inside: one surface crossed, its radiance 1 / ior^2 of the
// light inside (L / n^2 is kept across an interface, as the lighting's estimators count it),
// absorbed over its own path. Otherwise it leaves through the far side, which the march cannot
// follow (it bends again there): looked up by its direction, two surfaces crossed and the
// volume's thickness absorbed (u_transmittance), as measured closer on cornell's sphere.
vec3 through_solid(vec3 origin, vec3 t, vec3 fresnel) {
    vec3 hit;
    if (march(origin, t, hit)) {
        // The point the probe saw that way (the march stops up to a step's fraction beyond it).
        vec4 seen = texture(u_probe, hit);
        vec3 surface = hit * (seen.a / max(length(hit), 1e-6));
        vec3 slack = 0.02 * u_probe_extent + vec3(1e-3);  // a floor coplanar with the base
        if (all(lessThanEqual(abs(surface), u_probe_extent + slack))) {
            float n = max(u_ior, 1e-3);
            vec3 kept = (1.0 - fresnel) * u_tint / (n * n);
            if (u_attenuation.a > 0.0) {
                kept *= pow(max(u_attenuation.rgb, vec3(1e-6)),
                            vec3(length(surface - origin) / u_attenuation.a));
            }
            return kept * seen.rgb;
        }
    }
    return (1.0 - fresnel) * (1.0 - fresnel) * u_transmittance.rgb * texture(u_probe, t).rgb;
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
            // Through a sheet (one surface: water, a pane) the refracted ray goes on straight
            // and is marched; through a closed solid see through_solid().
            t = normalize(t);
            l += transmission *
                 (u_transmittance.a < 1.5
                      ? (1.0 - fresnel) * u_transmittance.rgb * probe_along(origin, t)
                      : through_solid(origin, t, fresnel));
        }
    }
    out_radiance = vec4(max(l, vec3(0.0)), 1.0);
}
