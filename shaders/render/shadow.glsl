// Shadow-map lookups. Maps hold linear depth (see shadow.frag), so depths here are in metres.
//
// Every comparison is made at a texel centre against the depth the receiver's own plane has
// there (receiver-plane depth), not against the receiver's depth pushed towards the light by a
// slope-scaled bias. A slope bias must cover the plane's depth change across the filter, which
// is texels x tan(theta) and grows without bound as the light grazes the surface: on the
// sandbox level it reached 4 texels (6.5 cm) on a wall the sun meets at 75 degrees, more than
// the distance to the wall beside it, and lit a bright line along every corner
// (docs/RESULTS.md, "The sun leaks into the sandbox level's corners"). With the plane's own
// depth at each centre, only a constant half texel is left for the rasterised occluder's
// depth and the plane's curvature, so a corner leaks over at most that.
//
// Filtered lookups weigh the 3 x 3 texel centres around the receiver as 2 x 2 bilinear taps
// half a texel either side of it would (a filter two texels wide, whose weights move smoothly
// with the receiver); unfiltered lookups compare the texel the receiver falls in. Nine
// comparisons either way: the nine bilinear taps one texel apart used before (a 4 x 4
// footprint) would take sixteen at texel centres, which doubled the direct pass on llvmpipe
// (docs/PERFORMANCE.md). The maps hold raw depths and the comparisons are made here, so the
// nearest occluder's distance is known too: near a contact the filter narrows (shadow_result).

#include "render/lights.glsl"

// Every light's map is a layer of one of two arrays (renderer/src/shadow_layers.hpp), named by
// the light record's intensity_shadow.w. One sampler per shape, never an array of samplers:
// llvmpipe gave some lanes along the sandbox level's wall corners another light's map when a
// sampler array was indexed by the batch's light index (docs/RESULTS.md).
// The arrays hold raw depths (no hardware comparison): the comparisons are made here, so each
// tap's depth is also known to the contact test below.
layout(binding = 4) uniform samplerCubeArray u_cube_shadows;
layout(binding = 8) uniform sampler2DArray u_map_shadows;

// Unfiltered lookups compare the receiver's texel alone; where add_tap leaves it out (the
// receiver's plane has ended there), a second pass lets the filter's nine texels decide.
const int kShadowPasses = 2;

// The constant bias, in texels of the map at the receiver.
const float kShadowBiasTexels = 0.5;
// The steepest plane the depth walk follows: cos(theta) >= 1/8 (83 degrees). Past it the plane
// is taken at that slope; E cos(theta) is small there, and the walk stays bounded.
const float kShadowMinCos = 0.125;

// Distance from `origin` along unit `dir` to the receiver plane (p, n). The plane is treated
// as facing the ray (n . dir <= -kShadowMinCos): surfaces facing away get no light anyway.
float plane_distance(vec3 origin, vec3 dir, vec3 p, vec3 n) {
    return dot(n, origin - p) / max(-dot(n, dir), kShadowMinCos);
}

// The same from the light along `ray`, which need not be unit length, with
// `towards_light` = n . (light - p) computed once per receiver.
float ray_plane_distance(vec3 ray, vec3 n, float towards_light) {
    float len = length(ray);
    return towards_light * len / max(-dot(n, ray), kShadowMinCos * len);
}

// An occluder standing on the receiver (a wall on the floor) is reached by the filter's taps on
// the far side of it when it is nearer than this, in texels along the light's ray: the taps lie
// up to 1.5 texels across the ray, which the receiver's slope stretches by 1 / cos(theta) along
// its plane, and an occluder square to the receiver meets the ray after a further
// 1 / sin(theta). Twice that, kept between 4 and 24 texels.
float contact_texels(float cos_theta) {
    float c = clamp(cos_theta, 0.05, 1.0);
    float s = sqrt(max(1.0 - c * c, 0.0025));
    return clamp(3.0 / (c * s), 4.0, 24.0);
}

// The comparisons of one lookup: the filter's weighted sum of lit taps and of the taps that
// count, the same for the 2 x 2 texels nearest the receiver (bilinear weights), and the nearest
// occluder in front of the receiver plane (metres along the ray; 1e30: none).
struct ShadowTaps {
    float filtered;
    float filtered_weight;
    float near;
    float near_weight;
    float gap;
};

const ShadowTaps kNoTaps = ShadowTaps(0.0, 0.0, 0.0, 0.0, 1e30);

// One comparison: `stored` the map's depth in [0, 1] at a texel centre, `plane` the receiver
// plane's depth in metres along that texel's ray; `w` its filter weight, `w_near` its bilinear
// weight among the nearest four.
//
// A texel whose first surface lies beyond the plane by more than the bias says nothing about
// the receiver: were the receiver's surface there, the map would hold it. The plane has ended
// (past a corner, an edge or a hole), and the tap is left out rather than counted lit. Counted
// lit, such taps lit a band along every corner where the receiver meets its occluder at a
// grazing light: the plane's depth changes by 1 / tan(theta) texels per texel, so taps a texel
// across reach that far past the occluder (a south wall the sun meets at 84 degrees, 9.5 texels
// a texel, showed a lit band 4-8 cm wide along its corner with the window wall: docs/RESULTS.md,
// "A sky room built in").
void add_tap(inout ShadowTaps taps, float w, float w_near, float stored, float plane, float bias,
             float far) {
    float occluder = stored * far;
    if (occluder > plane + bias) {
        return;
    }
    bool lit = plane - bias <= occluder;
    taps.filtered_weight += w;
    taps.near_weight += w_near;
    taps.filtered += lit ? w : 0.0;
    taps.near += lit ? w_near : 0.0;
    if (!lit) {
        taps.gap = min(taps.gap, plane - occluder);
    }
}

// The filter smooths the map's texel steps, but where an occluder touches the receiver (a wall
// standing on the floor) its taps reach past the occluder onto the surface's continuation on
// the far side, which the light does reach: a bright line along every contact. Light from a
// real source is all but hard there (the sun's half degree gives a penumbra of 1% of the
// occluder's distance), so as the nearest occluder among the taps comes within
// contact_texels() of the receiver, the result moves from the filter to the four texels
// nearest the receiver (one texel wide: what is left at a contact is at most half a texel).
// The taps left out (add_tap) take their weight with them; where none counts, the receiver is
// lit, as where its map holds nothing.
float shadow_result(ShadowTaps taps, float texel, float cos_theta) {
    if (!(taps.filtered_weight > 0.0)) {
        return 1.0;
    }
    float filtered = taps.filtered / taps.filtered_weight;
    float near = taps.near_weight > 0.0 ? taps.near / taps.near_weight : filtered;
    float contact = contact_texels(cos_theta) * texel;
    float t = clamp(taps.gap / max(contact, 1e-9), 0.0, 1.0);
    return mix(near, filtered, t);
}

// The bilinear weights of texels k - 1, k, k + 1 for a receiver `g` texels from the centre of
// texel k: the two nearest. Unfiltered: texel k.
vec3 near_weights(float g, bool filtered) {
    if (!filtered) {
        return vec3(0.0, 1.0, 0.0);
    }
    return g < 0.0 ? vec3(-g, 1.0 + g, 0.0) : vec3(0.0, 1.0 - g, g);
}

// The 1D weights of texels k - 1, k, k + 1 around a receiver `g` texels from the centre of
// texel k (|g| <= 1/2): two bilinear taps half a texel either side of it. Unfiltered: texel k.
vec3 filter_weights(float g, bool filtered) {
    return filtered ? vec3(0.5 - g, 1.0, 0.5 + g) * 0.5 : vec3(0.0, 1.0, 0.0);
}

// The weights of one pass over the 3 x 3 texels around a receiver `g` texels from the centre of
// its own: filtered, the filter's nine; unfiltered, the receiver's texel alone, and then the
// nine only where add_tap left that texel out (kShadowPasses). False: no further pass.
struct TapWeights {
    bool wide;
    vec3 x;
    vec3 y;
    vec3 near_x;
    vec3 near_y;
};

bool tap_pass(int pass, bool filtered, ShadowTaps taps, vec2 g, out TapWeights weights) {
    weights.wide = filtered || pass == 1;
    weights.x = filter_weights(g.x, weights.wide);
    weights.y = filter_weights(g.y, weights.wide);
    weights.near_x = near_weights(g.x, weights.wide);
    weights.near_y = near_weights(g.y, weights.wide);
    return pass == 0 || (pass < kShadowPasses && !filtered && !(taps.filtered_weight > 0.0));
}

// A 2D map's ray through `centre` (map uv), as a point of the world on it: w = 0 gives a point
// in clip space between the near and far planes.
vec4 map_ray_point(Light light, vec2 centre) {
    return light.shadow_inverse * vec4(centre * 2.0 - 1.0, 0.0, 1.0);
}

// A 2D map's lookup; `gap` the nearest occluder's distance in front of the receiver plane
// along the light's ray (metres; 1e30: no tap was shadowed), which soft shadows size their
// penumbra by (render/soft_shadow_gather.frag).
float map_shadow_gap(Light light, vec3 p, vec3 n, bool filtered, out float gap) {
    gap = 1e30;
    bool ortho = int(light.params.w) == SHADOW_ORTHO;
    vec3 origin = light.position_kind.xyz;
    vec3 direction = light.direction_far.xyz;
    float far = light.direction_far.w;
    vec4 clip = light.shadow_matrix * vec4(p, 1.0);
    if (!(clip.w > 0.0) || !(far > 0.0)) {
        return 1.0;
    }
    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) {
        return 1.0;  // outside the map: outside the spot's cone or the scene's bounds
    }
    float texel = ortho ? light.params.z : light.params.z * length(p - origin);
    float bias = kShadowBiasTexels * texel;
    vec2 size = vec2(textureSize(u_map_shadows, 0).xy);
    float layer = light.intensity_shadow.w;
    vec2 position = uv * size - 0.5;  // texel centres at integers
    vec2 base = floor(position + 0.5);  // the texel the receiver is in
    vec2 g = position - base;
    // The rays through texel `base` and the next texels in x and y. Clip space is a projective
    // image of the world, so X.xyz - origin X.w (a spot's ray direction, unnormalised) and X.xyz
    // (a point on the sun's ray) are affine in the texel: three matrix products give every
    // tap's ray exactly, and along the sun's parallel rays the plane's depth is affine too.
    vec2 c0 = (base + 0.5) / size;
    vec4 x0 = map_ray_point(light, c0);
    vec4 x1 = map_ray_point(light, c0 + vec2(1.0 / size.x, 0.0));
    vec4 x2 = map_ray_point(light, c0 + vec2(0.0, 1.0 / size.y));
    vec3 r0 = ortho ? x0.xyz / x0.w : x0.xyz - origin * x0.w;
    vec3 rx = (ortho ? x1.xyz / x1.w : x1.xyz - origin * x1.w) - r0;
    vec3 ry = (ortho ? x2.xyz / x2.w : x2.xyz - origin * x2.w) - r0;
    float towards_light = dot(n, origin - p);
    float d0 = 0.0;
    float dx = 0.0;
    float dy = 0.0;
    if (ortho) {
        d0 = dot(r0 - origin, direction) + plane_distance(r0, direction, p, n);
        dx = dot(rx, direction) + dot(n, rx) / max(-dot(n, direction), kShadowMinCos);
        dy = dot(ry, direction) + dot(n, ry) / max(-dot(n, direction), kShadowMinCos);
    }
    ShadowTaps taps = kNoTaps;
    TapWeights weights;
    for (int pass = 0; tap_pass(pass, filtered, taps, g, weights); ++pass) {
        for (int j = 0; j < 3; ++j) {
            for (int i = 0; i < 3; ++i) {
                float w = weights.x[i] * weights.y[j];
                if (!weights.wide && w == 0.0) {
                    continue;
                }
                vec2 offset = vec2(i - 1, j - 1);
                float depth = ortho ? d0 + offset.x * dx + offset.y * dy
                                    : ray_plane_distance(r0 + offset.x * rx + offset.y * ry, n,
                                                         towards_light);
                float stored = textureLod(u_map_shadows, vec3(c0 + offset / size, layer), 0.0).r;
                add_tap(taps, w, weights.near_x[i] * weights.near_y[j], stored, depth, bias, far);
            }
        }
    }
    vec3 to_light = ortho ? -direction : normalize(origin - p);
    gap = taps.gap;
    return shadow_result(taps, texel, dot(n, to_light));
}

float map_shadow(Light light, vec3 p, vec3 n, bool filtered) {
    float gap;
    return map_shadow_gap(light, p, n, filtered, gap);
}

// The face a direction from the light lands on: its major axis and its two minor axes as unit
// vectors. The face's texel grid is laid over the minor axes; texel centres are symmetric about
// the face's middle, so the face's own orientation in the cube does not matter.
struct CubeFace {
    vec3 major;
    vec3 u;
    vec3 v;
};

CubeFace cube_face(vec3 dir) {
    vec3 a = abs(dir);
    if (a.x >= a.y && a.x >= a.z) {
        return CubeFace(vec3(dir.x < 0.0 ? -1.0 : 1.0, 0.0, 0.0), vec3(0.0, 0.0, 1.0),
                        vec3(0.0, 1.0, 0.0));
    }
    if (a.y >= a.z) {
        return CubeFace(vec3(0.0, dir.y < 0.0 ? -1.0 : 1.0, 0.0), vec3(1.0, 0.0, 0.0),
                        vec3(0.0, 0.0, 1.0));
    }
    return CubeFace(vec3(0.0, 0.0, dir.z < 0.0 ? -1.0 : 1.0), vec3(1.0, 0.0, 0.0),
                    vec3(0.0, 1.0, 0.0));
}

// `dir`'s position on its face in [-1, 1]^2.
vec2 face_coordinates(CubeFace face, vec3 dir) {
    return vec2(dot(dir, face.u), dot(dir, face.v)) / dot(dir, face.major);
}

// The direction through the centre of the texel `dir` falls in.
vec3 cube_texel_centre(vec3 dir, float size) {
    CubeFace face = cube_face(dir);
    vec2 texel = clamp(floor((face_coordinates(face, dir) * 0.5 + 0.5) * size), 0.0, size - 1.0);
    vec2 centre = (texel + 0.5) / size * 2.0 - 1.0;
    return face.major + face.u * centre.x + face.v * centre.y;
}

// The same on a cube map, over the texel grid of the face the receiver lands on. A tap past
// the face's edge is moved to the centre of the texel it falls in on the next face, so every
// comparison still reads one texel against the plane's depth along that texel's own ray.
float cube_shadow_gap(Light light, vec3 p, vec3 n, bool filtered, out float gap) {
    gap = 1e30;
    vec3 light_position = light.position_kind.xyz;
    float far = light.direction_far.w;
    vec3 v = p - light_position;
    float distance = length(v);
    if (!(distance > 0.0) || !(far > 0.0)) {
        return 1.0;
    }
    CubeFace face = cube_face(v);
    float size = float(textureSize(u_cube_shadows, 0).x);
    float layer = light.intensity_shadow.w;
    vec2 position = (face_coordinates(face, v) * 0.5 + 0.5) * size - 0.5;  // texel centres at integers
    vec2 base = floor(position + 0.5);  // the texel the receiver is in
    vec2 g = position - base;
    float texel = light.params.z * distance;
    float bias = kShadowBiasTexels * texel;
    vec2 c0 = ((base + 0.5) / size) * 2.0 - 1.0;
    float texel_step = 2.0 / size;
    vec3 dir0 = face.major + face.u * c0.x + face.v * c0.y;
    float towards_light = dot(n, -v);
    ShadowTaps taps = kNoTaps;
    TapWeights weights;
    for (int pass = 0; tap_pass(pass, filtered, taps, g, weights); ++pass) {
        for (int j = 0; j < 3; ++j) {
            for (int i = 0; i < 3; ++i) {
                float w = weights.x[i] * weights.y[j];
                if (!weights.wide && w == 0.0) {
                    continue;
                }
                vec2 offset = vec2(i - 1, j - 1) * texel_step;
                vec3 dir = dir0 + face.u * offset.x + face.v * offset.y;
                if (any(greaterThan(abs(c0 + offset), vec2(1.0)))) {
                    dir = cube_texel_centre(dir, size);  // past the face's edge: the next face's
                }
                float depth = ray_plane_distance(dir, n, towards_light);
                float stored = textureLod(u_cube_shadows, vec4(dir, layer), 0.0).r;
                add_tap(taps, w, weights.near_x[i] * weights.near_y[j], stored, depth, bias, far);
            }
        }
    }
    gap = taps.gap;
    return shadow_result(taps, texel, dot(n, -v / distance));
}

float cube_shadow(Light light, vec3 p, vec3 n, bool filtered) {
    float gap;
    return cube_shadow_gap(light, p, n, filtered, gap);
}

// Either lookup, as the light's record names its map; 1 (lit) for a light without one.
float light_shadow_gap(Light light, vec3 p, vec3 n, bool filtered, out float gap) {
    gap = 1e30;
    if (light.intensity_shadow.w < 0.0) {
        return 1.0;
    }
    return int(light.params.w) == SHADOW_CUBE ? cube_shadow_gap(light, p, n, filtered, gap)
                                             : map_shadow_gap(light, p, n, filtered, gap);
}
