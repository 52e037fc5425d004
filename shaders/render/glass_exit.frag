#version 450 core
// The far side of closed glass, for the specular pass's two-surface refraction
// (docs/METHOD.md §8.3): drawn with front faces culled, the nearest back face per pixel, so
// each pixel holds where its view ray would leave the solid and the surface's outward normal.

in vec3 v_position;
in vec3 v_normal;
in vec2 v_texcoord0;
in vec2 v_lightmap_uv;

uniform vec3 u_camera;

layout(location = 0) out vec4 out_position;  // xyz world position, w: 1 = covered
layout(location = 1) out vec4 out_normal;    // xyz outward unit normal

void main() {
    vec3 n = v_normal;
    if (!(dot(n, n) > 1e-12)) {
        n = cross(dFdx(v_position), dFdy(v_position));
    }
    n = normalize(n);
    // A back face faces away from the eye; a mesh whose normals disagree with its winding is
    // taken by its winding.
    if (dot(n, v_position - u_camera) < 0.0) {
        n = -n;
    }
    out_position = vec4(v_position, 1.0);
    out_normal = vec4(n, 0.0);
}
