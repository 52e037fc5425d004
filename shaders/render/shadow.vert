#version 450 core
// Shadow casters: world position only (the fragment stage writes the light's own depth). A
// skinned caster is posed as in render/mesh.vert.

layout(location = 0) in vec3 a_position;

#include "skinning.glsl"

uniform mat4 u_model;
uniform mat4 u_view_projection;

out vec3 v_position;

void main() {
    vec4 local = vec4(a_position, 1.0);
    vec4 world = u_model * (skinned() ? skin_matrix() * local : local);
    v_position = world.xyz;
    gl_Position = u_view_projection * world;
}
