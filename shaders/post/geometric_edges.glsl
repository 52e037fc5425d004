// Where the G-buffer shows two surfaces meeting (docs/METHOD.md §8.4): shared by the edge mask
// (post/edge_mask.frag), which marks those pixels in the stencil buffer, and the edge pass
// (post/edge_aa.frag), which filters only the pixels marked. The including shader declares
// u_position and u_normal (the G-buffer's world positions and normals).

uniform int u_sky_resolved;  // 1: silhouettes against the sky were resolved by coverage

ivec2 frame_size;  // set by main() before any lookup

// A turn of the normal past 30 degrees between neighbours is a crease.
const float kCreaseCos = 0.866;
// A neighbour more than 0.25 of its distance off the pixel's tangent plane lies on another
// surface (a step in depth); neighbours on one plane, even at grazing angles, give 0.
const float kOffPlane = 0.25;

// Whether the pixel at position xp with normal np and pixel q show different surfaces.
bool surfaces_differ(vec4 xp, vec3 np, ivec2 q) {
    q = clamp(q, ivec2(0), frame_size - 1);
    vec4 xq = texelFetch(u_position, q, 0);
    if (xp.w != xq.w) {
        // A surface against the sky: the composite mixed the two by their coverage already.
        return u_sky_resolved == 0;
    }
    if (xp.w == 0.0) {
        return false;  // sky on both sides
    }
    vec3 nq = texelFetch(u_normal, q, 0).xyz;
    if (dot(np, nq) < kCreaseCos) {
        return true;
    }
    vec3 between = xq.xyz - xp.xyz;
    float apart = length(between);
    return abs(dot(np, between)) > kOffPlane * apart || abs(dot(nq, between)) > kOffPlane * apart;
}

bool on_geometric_edge(ivec2 p) {
    // The pixel's own position and normal are read once for its four neighbours.
    vec4 xp = texelFetch(u_position, p, 0);
    vec3 np = texelFetch(u_normal, p, 0).xyz;
    return surfaces_differ(xp, np, p + ivec2(1, 0)) || surfaces_differ(xp, np, p - ivec2(1, 0)) ||
           surfaces_differ(xp, np, p + ivec2(0, 1)) || surfaces_differ(xp, np, p - ivec2(0, 1));
}

