#version 450 core
// Shadow casters: world position only (the fragment stage writes the light's own depth).

layout(location = 0) in vec3 a_position;

uniform mat4 u_model;
uniform mat4 u_view_projection;

out vec3 v_position;

void main() {
    vec4 world = u_model * vec4(a_position, 1.0);
    v_position = world.xyz;
    gl_Position = u_view_projection * world;
}
