#version 450 core
// Anti-aliasing of the composed frame at geometric edges (docs/METHOD.md §8.4).
//
// In this deferred renderer only geometry aliases: shadows are filtered (PCF), textures and
// light maps are sampled bilinearly, caustics are splatted with a kernel. So the pass works
// where the G-buffer says two surfaces meet (coverage, a normal that turns, a neighbour off the
// pixel's plane) and copies every other pixel exactly. At those pixels it does what a
// morphological filter does (the approach of FXAA and MLAA): it finds the edge's direction and
// its two ends along the image, estimates where the true edge crosses the pixel, and reads the
// frame that far across it with a bilinear fetch, so the pixel takes the mix of both sides that
// its coverage would give. Mixing happens in linear radiance, as the box filter of a reference
// averages it. Contrasts are judged on luminance divided by the brightest of the pixel's 3 x 3
// neighbourhood: the frame is physical HDR with no exposure known here, and a measure linear in
// radiance keeps the bilinear reads between pixels and the edge's level consistent (in log2 a
// mix with black sits many stops below one side and one stop below the other).

layout(binding = 0) uniform sampler2D u_frame;     // composed linear radiance, bilinear
layout(binding = 1) uniform sampler2D u_position;  // world position, w = 1 where covered
layout(binding = 2) uniform sampler2D u_normal;    // world normal

layout(location = 0) out vec4 out_radiance;

#include "post/geometric_edges.glsl"

// Contrast below which an edge is left alone: 8% of the neighbourhood's brightest pixel.
const float kMinContrast = 0.08;
// A neighbourhood darker than this is black to any exposure (and 1 / it would overflow).
const float kBlack = 1e-30;
// The search along the edge: a first step of one pixel each way, then these strides, one at a
// time near and longer far (up to 25 pixels from the centre).
const int kStrides = 9;
const float kStride[kStrides] = float[](1.0, 1.0, 1.0, 1.5, 2.0, 2.0, 4.0, 4.0, 8.0);

float to_contrast;  // 1 / the neighbourhood's brightest luminance

vec3 radiance_at(ivec2 p) {
    return texelFetch(u_frame, clamp(p, ivec2(0), frame_size - 1), 0).rgb;
}

float luminance(vec3 radiance) {
    return max(dot(radiance, vec3(0.2126, 0.7152, 0.0722)), 0.0);
}

float luma(vec3 radiance) {
    return luminance(radiance) * to_contrast;
}

float luma_at(ivec2 p) {
    return luma(radiance_at(p));
}

float luma_at_uv(vec2 uv) {
    return luma(textureLod(u_frame, uv, 0.0).rgb);
}

void main() {
    frame_size = textureSize(u_frame, 0);
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec3 centre = radiance_at(p);
    if (!on_geometric_edge(p)) {
        out_radiance = vec4(centre, 1.0);
        return;
    }
    float brightest = 0.0;
    for (int j = -1; j <= 1; ++j) {
        for (int i = -1; i <= 1; ++i) {
            brightest = max(brightest, luminance(radiance_at(p + ivec2(i, j))));
        }
    }
    if (brightest < kBlack) {
        out_radiance = vec4(centre, 1.0);
        return;
    }
    to_contrast = 1.0 / brightest;
    float c = luma(centre);
    float n = luma_at(p + ivec2(0, 1));
    float s = luma_at(p - ivec2(0, 1));
    float e = luma_at(p + ivec2(1, 0));
    float w = luma_at(p - ivec2(1, 0));
    float low = min(c, min(min(n, s), min(e, w)));
    float high = max(c, max(max(n, s), max(e, w)));
    float range = high - low;
    if (range < kMinContrast) {
        out_radiance = vec4(centre, 1.0);
        return;
    }
    float ne = luma_at(p + ivec2(1, 1));
    float nw = luma_at(p + ivec2(-1, 1));
    float se = luma_at(p + ivec2(1, -1));
    float sw = luma_at(p + ivec2(-1, -1));

    // An edge that runs along x changes the image along y: compare second differences.
    float across_y = 2.0 * abs(n + s - 2.0 * c) + abs(ne + se - 2.0 * e) + abs(nw + sw - 2.0 * w);
    float across_x = 2.0 * abs(e + w - 2.0 * c) + abs(ne + nw - 2.0 * n) + abs(se + sw - 2.0 * s);
    bool runs_along_x = across_y >= across_x;

    vec2 texel = 1.0 / vec2(frame_size);
    // The neighbour across the edge: the side where the image changes most.
    float before = runs_along_x ? s : w;
    float after = runs_along_x ? n : e;
    bool towards_after = abs(after - c) >= abs(before - c);
    vec2 across = runs_along_x ? vec2(0.0, texel.y) : vec2(texel.x, 0.0);
    if (!towards_after) {
        across = -across;
    }
    ivec2 other_side = p + (runs_along_x ? ivec2(0, towards_after ? 1 : -1)
                                         : ivec2(towards_after ? 1 : -1, 0));
    // The edge line, half a pixel towards the other side; its level, and how far the
    // search may drift from it before it has left the edge.
    float edge_level = luma(0.5 * (centre + radiance_at(other_side)));
    float tolerance = 0.25 * max(abs(after - c), abs(before - c));
    vec2 uv = (vec2(p) + 0.5) * texel + 0.5 * across;
    vec2 along = runs_along_x ? vec2(texel.x, 0.0) : vec2(0.0, texel.y);

    // Walk both ways until the pair of pixels either side of the line no longer looks like
    // the edge: that is where the edge ends.
    vec2 uv_back = uv - along;
    vec2 uv_ahead = uv + along;
    float end_back = luma_at_uv(uv_back) - edge_level;
    float end_ahead = luma_at_uv(uv_ahead) - edge_level;
    bool done_back = abs(end_back) >= tolerance;
    bool done_ahead = abs(end_ahead) >= tolerance;
    for (int i = 0; i < kStrides && !(done_back && done_ahead); ++i) {
        if (!done_back) {
            uv_back -= kStride[i] * along;
            end_back = luma_at_uv(uv_back) - edge_level;
            done_back = abs(end_back) >= tolerance;
        }
        if (!done_ahead) {
            uv_ahead += kStride[i] * along;
            end_ahead = luma_at_uv(uv_ahead) - edge_level;
            done_ahead = abs(end_ahead) >= tolerance;
        }
    }
    vec2 centre_uv = (vec2(p) + 0.5) * texel;
    float distance_back = runs_along_x ? centre_uv.x - uv_back.x : centre_uv.y - uv_back.y;
    float distance_ahead = runs_along_x ? uv_ahead.x - centre_uv.x : uv_ahead.y - centre_uv.y;
    float length_total = distance_back + distance_ahead;
    bool nearer_back = distance_back < distance_ahead;
    // A stair step of the edge: the pixel nearest the step's end is covered least. Only when the
    // nearer end turns away from the centre's side (else the pixel is inside a corner).
    float offset = length_total > 0.0 ? 0.5 - min(distance_back, distance_ahead) / length_total
                                       : 0.0;
    bool centre_below = c < edge_level;
    bool end_below = (nearer_back ? end_back : end_ahead) < 0.0;
    if (end_below == centre_below) {
        offset = 0.0;
    }
    // Features thinner than a pixel have no ends to find: mix by how far the pixel stands out
    // from its neighbourhood.
    float neighbourhood = (2.0 * (n + s + e + w) + ne + nw + se + sw) / 12.0;
    float stands_out = clamp(abs(neighbourhood - c) / range, 0.0, 1.0);
    float smooth_out = (3.0 - 2.0 * stands_out) * stands_out * stands_out;
    offset = max(offset, 0.75 * smooth_out * smooth_out);

    out_radiance = vec4(textureLod(u_frame, centre_uv + offset * across, 0.0).rgb, 1.0);
}
