#version 450 core
// Every shadow map stores a linear depth in [0, 1]: the distance to the light divided by the
// map's far distance (point and spot lights), or the distance along the light's direction from
// the map's plane (directional lights). Linear depth makes one bias in metres work for every
// kind of map and at every distance (shaders/render/shadow.glsl compares in the same units).

in vec3 v_position;

uniform vec3 u_light_position;   // the light (point, spot) or a point on the map's plane
uniform vec3 u_light_direction;  // directional: the direction light travels
uniform int u_planar;            // 1: directional (distance along u_light_direction)
uniform float u_far;

void main() {
    vec3 offset = v_position - u_light_position;
    float distance = u_planar != 0 ? dot(offset, u_light_direction) : length(offset);
    gl_FragDepth = clamp(distance / u_far, 0.0, 1.0);
}
