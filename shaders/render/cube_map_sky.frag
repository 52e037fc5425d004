#version 450 core
// The sky behind a specular cube map face (render/cube_map_face.frag draws the level over
// it): what a mirror or a pane shows where it sees out of the level, as the frame's composite
// shows it where nothing was drawn.

#include "common/sky.glsl"

in vec2 v_uv;

// Unit 17: clear of the shadow maps, IIM pages and material textures the face program binds,
// which stay bound across the faces.
layout(binding = 17) uniform sampler2D u_sky;
uniform mat4 u_inverse_view_projection;
uniform vec3 u_centre;  // the cube map's centre

layout(location = 0) out vec4 out_radiance;

void main() {
    vec4 far = u_inverse_view_projection * vec4(2.0 * v_uv - 1.0, 0.5, 1.0);
    // Alpha: "far", 1e6 m, as a face's clear colour where there is no sky (the specular term's
    // parallax correction, render/specular.frag, says why not 0).
    out_radiance = vec4(sky_radiance(u_sky, far.xyz / far.w - u_centre), 1e6);
}
