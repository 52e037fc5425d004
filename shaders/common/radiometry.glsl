// Radiometric helpers shared by the lighting shaders. Units: metres, watts, linear RGB.

const float PI = 3.14159265358979323846;

// Irradiance (W/m^2) at a point with normal n from a light described by `light`:
//   light.w == 1: a point light at light.xyz with radiant intensity `intensity` (W/sr,
//                 = power / 4pi): E = I cos(theta) / d^2;
//   light.w == 0: a directional light arriving from direction light.xyz with irradiance
//                 `intensity` (W/m^2) on a surface facing it: E = E_perp cos(theta).
vec3 light_irradiance(vec3 position, vec3 n, vec4 light, vec3 intensity) {
    if (light.w == 0.0) {
        return intensity * max(dot(n, normalize(light.xyz)), 0.0);
    }
    vec3 to_light = light.xyz - position;
    float distance_squared = max(dot(to_light, to_light), 1e-8);
    float cos_theta = max(dot(n, to_light * inversesqrt(distance_squared)), 0.0);
    return intensity * cos_theta / distance_squared;
}

// Radiance leaving a Lambertian surface of albedo rho under irradiance E: L = rho E / pi.
vec3 lambert_radiance(vec3 albedo, vec3 irradiance) {
    return albedo * irradiance / PI;
}
