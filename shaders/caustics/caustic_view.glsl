// The caller's scene depth texture read back as view-space positions (the camera looks down
// -z; view depth z = -position.z). Perspective projections only. Shared by the caustic splat
// (depth test, surface slope) and the world-space filter (depth of each tap).

#include "caustic_interface.h"

layout(binding = CAUSTIC_DEPTH_UNIT) uniform sampler2D u_depth;
uniform mat4 u_inverse_projection;
uniform ivec2 u_viewport;
// Depth values are NDC z as they are (GL_ZERO_TO_ONE, reversed depth) rather than 2d - 1.
uniform bool u_depth_zero_to_one;

// A depth this large stands for "no surface" (reversed infinite depth cleared to 0).
const float CAUSTIC_NO_SURFACE = 1e30;

bool pixel_inside(ivec2 pixel) {
    return all(greaterThanEqual(pixel, ivec2(0))) && all(lessThan(pixel, u_viewport));
}

// View-space position of the scene at `pixel`'s centre.
vec3 scene_view_position(ivec2 pixel) {
    float d = texelFetch(u_depth, pixel, 0).r;
    vec2 ndc_xy = (vec2(pixel) + 0.5) / vec2(u_viewport) * 2.0 - 1.0;
    float ndc_z = u_depth_zero_to_one ? d : 2.0 * d - 1.0;
    vec4 v = u_inverse_projection * vec4(ndc_xy, ndc_z, 1.0);
    if (!(abs(v.w) > 1e-30)) {
        return vec3(0.0, 0.0, -CAUSTIC_NO_SURFACE);
    }
    return v.xyz / v.w;
}
