#version 450 core
// Ray-differential footprints (docs/METHOD.md §7.4): adds the photon's irradiance at the scene
// point this pixel sees, with the Epanechnikov kernel 2 / (pi r^2) (1 - d^2 / r^2) over the
// distance d from the photon (normalised over the disc of radius r on the photon's surface, so
// each photon keeps its power). A scene point farther than r (an occluder in front, the
// background, another wall) takes nothing: the depth test is the distance itself. Blend ONE,
// ONE into RGBA32F; alpha sums the kernel's weight (1 at a photon's centre). The result is the
// irradiance as it is: no filter follows, so no tiles are marked.

#include "caustic_view.glsl"

flat in vec3 g_view_centre;
flat in float g_radius;
flat in vec3 g_power;

layout(location = 0) out vec4 o_splat;

const float PI = 3.14159265358979;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec3 surface = scene_view_position(pixel);
    vec3 offset = surface - g_view_centre;
    float q = dot(offset, offset) / (g_radius * g_radius);
    if (!(q < 1.0)) {
        discard;
    }
    float weight = 2.0 / (PI * g_radius * g_radius) * (1.0 - q);
    o_splat = vec4(g_power * weight, 1.0 - q);
}
