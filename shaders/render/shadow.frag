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
uniform float u_texel;        // the map's texel: metres (directional), per metre of distance (others)
uniform int u_single_sided;   // 1: the primitive's material is single-sided (glTF doubleSided false)

// A single-sided surface the light meets from behind is stored this many texels nearer the
// light than it is. Such a surface is the back of a shell (a room's ceiling or wall seen from
// outside): nothing just behind it can be lit by this light, since no surface is drawn on that
// side. Where a receiver touches it (the wall under the ceiling, the sun above the roof) the
// receiver-plane comparison reads it within the half-texel bias (shadow.glsl) and counted the
// receiver lit: a row of sunlit notches along the sandbox level's ceiling edge
// (docs/RESULTS.md, "Frame 0 at the main job's resolution"). Depth alone cannot tell an
// occluder touching the receiver from the receiver's own surface; the side the light sees can.
// Front faces (every lit surface) and double-sided sheets keep their depth.
const float kBackFaceLeadTexels = 1.0;

void main() {
    vec3 offset = v_position - u_light_position;
    float distance = u_planar != 0 ? dot(offset, u_light_direction) : length(offset);
    if (u_single_sided != 0 && !gl_FrontFacing) {
        float texel = u_planar != 0 ? u_texel : u_texel * distance;
        distance -= kBackFaceLeadTexels * texel;
    }
    gl_FragDepth = clamp(distance / u_far, 0.0, 1.0);
}
