#version 450 core
// Adds one photon's irradiance to its texel (additive blending); alpha counts the photons.

flat in vec3 g_irradiance;

layout(location = 0) out vec4 out_value;

void main() {
    out_value = vec4(g_irradiance, 1.0);
}
