// The light records of the direct pass (std140; mirrored by GpuLight in
// renderer/src/frame_lights.hpp). Units: metres, watts, linear RGB.

const int LIGHT_POINT = 0;
const int LIGHT_SPOT = 1;
const int LIGHT_DIRECTIONAL = 2;

const int SHADOW_CUBE = 0;         // point lights and wide spots: six faces around the light
const int SHADOW_PERSPECTIVE = 1;  // spot lights
const int SHADOW_ORTHO = 2;        // directional lights

struct Light {
    vec4 position_kind;     // xyz position (directional: the shadow plane's origin), w kind
    vec4 direction_far;     // xyz unit direction (spot axis, or the direction light travels),
                            // w the shadow map's far distance in metres
    vec4 intensity_shadow;  // rgb radiant intensity W/sr (directional: irradiance W/m^2),
                            // w the shadow map's layer in its array (-1: none)
    vec4 params;            // x cos inner, y cos outer, z shadow texel size (per metre of
                            // distance; ortho: metres), w shadow map kind
    mat4 shadow_matrix;     // world to the 2D map's clip space
    mat4 shadow_inverse;    // the 2D map's clip space to world
};

// Irradiance (W/m^2) that `light` delivers to a surface at p with normal n, unshadowed. Point:
// I cos / d^2. Spot: the same inside the cone, times the smooth falloff from the inner to the
// outer cone the photon emitter uses. Directional: E_perp cos.
vec3 unshadowed_irradiance(Light light, vec3 p, vec3 n) {
    int kind = int(light.position_kind.w);
    vec3 intensity = light.intensity_shadow.rgb;
    if (kind == LIGHT_DIRECTIONAL) {
        return intensity * max(dot(n, -light.direction_far.xyz), 0.0);
    }
    vec3 to_light = light.position_kind.xyz - p;
    float distance_squared = max(dot(to_light, to_light), 1e-8);
    vec3 l = to_light * inversesqrt(distance_squared);
    float cos_theta = max(dot(n, l), 0.0);
    float falloff = 1.0;
    if (kind == LIGHT_SPOT) {
        float cos_axis = dot(-l, light.direction_far.xyz);
        float cos_inner = light.params.x;
        float cos_outer = light.params.y;
        if (cos_inner > cos_outer) {
            float t = clamp((cos_axis - cos_outer) / (cos_inner - cos_outer), 0.0, 1.0);
            falloff = t * t * (3.0 - 2.0 * t);
        } else {
            falloff = cos_axis >= cos_inner ? 1.0 : 0.0;
        }
    }
    return intensity * (falloff * cos_theta / distance_squared);
}
