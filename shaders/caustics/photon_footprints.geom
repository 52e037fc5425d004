#version 450 core
// Ray-differential footprints (docs/METHOD.md §7.4): each photon becomes a screen-space quad
// bounding the sphere of its footprint radius around it (photon_footprints.vert sizes it); the
// fragment shader spreads its power over the scene points inside that sphere. A quad, not a
// point sprite: GL clips a point by its centre, and a photon just off screen must still light
// the pixels its disc reaches; a close-up disc may also be wider than the largest point size.

layout(points) in;
layout(triangle_strip, max_vertices = 4) out;

flat in int v_keep[];
flat in vec3 v_view_centre[];
flat in float v_radius[];
flat in vec3 v_power[];
flat in vec2 v_half_ndc[];

flat out vec3 g_view_centre;
flat out float g_radius;
flat out vec3 g_power;

void corner(vec2 offset_ndc) {
    vec4 centre = gl_in[0].gl_Position;
    gl_Position = centre + vec4(offset_ndc * centre.w, 0.0, 0.0);
    g_view_centre = v_view_centre[0];
    g_radius = v_radius[0];
    g_power = v_power[0];
    EmitVertex();
}

void main() {
    if (v_keep[0] == 0) {
        return;
    }
    vec2 h = v_half_ndc[0];
    corner(vec2(-h.x, -h.y));
    corner(vec2(h.x, -h.y));
    corner(vec2(-h.x, h.y));
    corner(vec2(h.x, h.y));
    EndPrimitive();
}
