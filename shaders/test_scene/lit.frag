#version 450 core
// Lambertian surfaces under one light plus a constant ambient irradiance; writes linear
// radiance (W / (m^2 sr)) into an RGBA32F target.

#include "common/radiometry.glsl"

in vec3 v_position;
in vec3 v_normal;
in vec3 v_albedo;

uniform vec4 u_light;             // see light_irradiance()
uniform vec3 u_light_intensity;   // W/sr (point) or W/m^2 (directional)
uniform vec3 u_ambient_irradiance;

layout(location = 0) out vec4 out_radiance;

void main() {
    vec3 n = normalize(v_normal);
    vec3 irradiance = light_irradiance(v_position, n, u_light, u_light_intensity) +
                      u_ambient_irradiance;
    out_radiance = vec4(lambert_radiance(v_albedo, irradiance), 1.0);
}
