#version 450 core
// Scene meshes for the G-buffer and the specular cube faces: object space to world space by the
// entity's WorldTransform. Normals go through the inverse transpose so non-uniform scale keeps
// them perpendicular to the surface. A skinned mesh is posed from its bind pose first
// (skinning.glsl); its entity's WorldTransform is the identity.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_texcoord0;
layout(location = 3) in vec2 a_lightmap_uv;

#include "skinning.glsl"

uniform mat4 u_model;
uniform mat3 u_normal_matrix;
uniform mat4 u_view_projection;

// The specular pass redraws objects over their G-buffer depth: the same vertex code must give
// the same depth in both programs.
invariant gl_Position;

out vec3 v_position;
out vec3 v_normal;
out vec2 v_texcoord0;
out vec2 v_lightmap_uv;

void main() {
    vec4 world;
    if (skinned()) {
        mat4 skin = skin_matrix();
        world = u_model * (skin * vec4(a_position, 1.0));
        v_normal = u_normal_matrix * skin_normal(skin, a_normal);
    } else {
        world = u_model * vec4(a_position, 1.0);
        v_normal = u_normal_matrix * a_normal;
    }
    v_position = world.xyz;
    v_texcoord0 = a_texcoord0;
    v_lightmap_uv = a_lightmap_uv;
    gl_Position = u_view_projection * world;
}
