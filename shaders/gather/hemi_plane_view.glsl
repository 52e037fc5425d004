// One hemi-plane view per gathered texel (lighting/gpu HemiPlaneGatherer): the texel centre
// and its tangent frame. right x up = -forward, so triangles whose front faces the texel wind
// counter-clockwise on the plane, as GL's front faces do.
struct GatherView {
    vec4 origin;   // xyz: texel centre (world)
    vec4 right;    // xyz: plane x axis
    vec4 up;       // xyz: plane y axis
    vec4 forward;  // xyz: the texel normal; the plane is at forward distance 1
};
