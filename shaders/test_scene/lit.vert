#version 450 core
// The built-in test scene: world-space positions and normals with a per-vertex albedo.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_albedo;

uniform mat4 u_view_projection;

out vec3 v_position;
out vec3 v_normal;
out vec3 v_albedo;

void main() {
    v_position = a_position;
    v_normal = a_normal;
    v_albedo = a_albedo;
    gl_Position = u_view_projection * vec4(a_position, 1.0);
}
