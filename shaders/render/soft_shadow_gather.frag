#version 450 core
// Soft shadows, second pass (docs/METHOD.md §8.8): the direct light of one light with a radius
// r, its hard shadow (soft_shadow_inputs.frag) spread over the penumbra the sphere casts. After
// R.-H. Yao's image-space gathering (after Robison and Shirley): first the mean distance d from
// the receiver to the occluders among the pixels around it, then the hard shadow averaged over
// the disc of the receiver's plane that the penumbra spans,
//     w = r d / (D - d)      (D the receiver's distance to the light's centre),
// which is the width over which a sphere of radius r goes from hidden to seen past an edge
// d in front of the receiver. The hard shadow's edge is the centre's, the middle of the
// penumbra, and a disc's share on one side of a straight edge is the share of the sphere's
// disc the edge leaves visible: for an edge parallel to the receiver the average is exact.
//
// Both searches are discs in world metres across the light's ray (a tap's offset on the
// receiver's plane is measured square to the direction of the light, so on a floor the light
// meets at theta the disc stretches to an ellipse 1 / cos(theta) long towards the light, as the
// penumbra does), read at the pixels under a fixed spiral of taps (the same at every pixel, so
// the result is smooth, not noisy); a tap on another surface (off the receiver's plane) or off
// the disc does not count.

#include "common/radiometry.glsl"
#include "render/direct_lights.glsl"

layout(binding = 0) uniform sampler2D u_albedo;
layout(binding = 1) uniform sampler2D u_normal;
layout(binding = 2) uniform sampler2D u_position;
layout(binding = 3) uniform sampler2D u_shadow;  // soft_shadow_inputs.frag

uniform vec3 u_camera;
uniform vec3 u_forward;             // the camera's view direction, unit
uniform float u_pixels_per_metre;   // at 1 m of view depth (perspective) or anywhere (ortho)
uniform int u_perspective;
uniform float u_radius;             // the light's, m
uniform mat4 u_view_projection;     // the camera's: world to clip

layout(location = 0) out vec4 out_radiance;

// Taps of the blocker search and of the filter. The search looks as far as the penumbra of an
// occluder 4/5 of the way to the light (d / (D - d) = 4); both stop at kMaxPixels on screen,
// which bounds the pass's cost (a wider penumbra is averaged over that disc).
const int kFirstTaps = 8;
const int kSearchTaps = 24;
const int kFilterTaps = 48;
const float kSearchScale = 4.0;
const float kMaxPixels = 32.0;

// Tap i of n on a Vogel spiral filling the unit disc evenly.
vec2 spiral(int i, int n) {
    float radius = sqrt((float(i) + 0.5) / float(n));
    float angle = float(i) * 2.39996323;  // the golden angle
    return radius * vec2(cos(angle), sin(angle));
}

struct Receiver {
    vec3 p;
    vec3 n;
    vec3 l;  // unit, towards the light's centre
    float metres_per_pixel;
    float tolerance;  // off its plane by more than this: another surface
};

// The pixel `offset` from `pixel`, when it shows the receiver's plane within `reach` metres of
// it across the light's ray: its shadow inputs in `shadow`, that distance squared in `across2`.
bool tap(ivec2 pixel, vec2 offset, Receiver receiver, float reach, out vec2 shadow,
         out float across2) {
    ivec2 q = pixel + ivec2(round(offset));
    ivec2 size = textureSize(u_position, 0);
    shadow = vec2(0.0);
    across2 = 0.0;
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) {
        return false;
    }
    vec4 position = texelFetch(u_position, q, 0);
    vec3 d = position.xyz - receiver.p;
    vec3 across = d - receiver.l * dot(d, receiver.l);  // square to the light's ray
    across2 = dot(across, across);
    if (position.w == 0.0 || abs(dot(d, receiver.n)) > receiver.tolerance ||
        across2 > reach * reach) {
        return false;
    }
    shadow = texelFetch(u_shadow, q, 0).xy;
    return true;
}

// How far along the light's ray from the receiver the frame shows something in the way: the
// ray marched in kContactSteps (closer together near the receiver) up to `reach`, each point
// looked up in the G-buffer; a point hidden behind the surface the camera sees there, by less
// than that surface could plausibly be thick, lies inside an occluder. 1e30: none found.
//
// Why: the shadow map holds only the occluder's surface the light sees (a box's top), so at the
// foot of a box its distance is the box's height where the edge that shades the receiver (the
// box's far side, which the light does not see) stands right beside it. Read as the penumbra's
// distance it spread light a few centimetres into the umbra along every contact
// (tests/render/soft_shadow_test.cpp, the box). The engines' screen-space contact shadows march
// the same way.
float contact(Receiver receiver, float reach) {
    const int kContactSteps = 8;
    vec2 size = vec2(textureSize(u_position, 0));
    for (int k = 1; k <= kContactSteps; ++k) {
        float f = float(k) / float(kContactSteps);
        float t = reach * f * f;
        vec3 q = receiver.p + receiver.l * t;
        vec4 clip = u_view_projection * vec4(q, 1.0);
        if (!(clip.w > 0.0)) {
            break;
        }
        vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
        if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) {
            break;
        }
        vec4 seen = texelFetch(u_position, ivec2(uv * size), 0);
        if (seen.w == 0.0) {
            continue;
        }
        float behind = distance(u_camera, q) - distance(u_camera, seen.xyz);
        // More than two pixels behind (not the receiver's own plane read a pixel off), less than
        // 5 cm plus a quarter of the distance marched (not an object far in front of it).
        if (behind > 2.0 * receiver.metres_per_pixel && behind < 0.05 + 0.25 * t) {
            return t;
        }
    }
    return 1e30;
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 position = texelFetch(u_position, pixel, 0);
    out_radiance = vec4(0.0, 0.0, 0.0, 1.0);
    if (position.w == 0.0) {
        return;
    }
    vec3 n = texelFetch(u_normal, pixel, 0).xyz;
    Light light = u_lights[0];
    vec3 e = unshadowed_irradiance(light, position.xyz, n);
    if (!any(greaterThan(e, vec3(0.0)))) {
        return;
    }
    vec2 own = texelFetch(u_shadow, pixel, 0).xy;
    float depth = u_perspective != 0 ? max(dot(position.xyz - u_camera, u_forward), 1e-4) : 1.0;
    Receiver receiver;
    receiver.p = position.xyz;
    receiver.n = n;
    vec3 to_light = light.position_kind.xyz - position.xyz;
    float distance_to_light = length(to_light);
    receiver.l = to_light / max(distance_to_light, 1e-6);
    receiver.metres_per_pixel = depth / max(u_pixels_per_metre, 1e-6);
    // Two pixels' worth of the plane's slope and a centimetre: a curved receiver stays one.
    receiver.tolerance = 2.0 * receiver.metres_per_pixel + 0.01;
    // A disc across the ray lies 1 / cos(theta) long on the plane: the screen disc covers that
    // (cos kept above 1/4: a grazing light's penumbra is read over at most four times its width).
    float stretch = 1.0 / max(dot(n, receiver.l), 0.25);

    float search = min(kSearchScale * u_radius,
                       kMaxPixels * receiver.metres_per_pixel / stretch);
    float search_pixels = search * stretch / receiver.metres_per_pixel;
    // The occluders' distances weighed by closeness (the thesis's range function): an edge's
    // distance varies along it (nothing at a contact, most at the shadow's far end), and the
    // near taps say most about the edge that shades this pixel.
    float gap_sum = max(own.y, 0.0);
    float gaps = own.y > 0.0 ? 1.0 : 0.0;
    float lit_taps = own.x;
    float closeness = 1.0 / max(0.25 * search * search, 1e-12);
    // Most pixels lie in the open, far from any shadow: a first look at kFirstTaps of the
    // disc that finds no occluder and the pixel itself lit keeps the hard value (1) at a third
    // of the search's cost (Frame/soft, docs/PERFORMANCE.md).
    bool open = own.x >= 1.0 && own.y <= 0.0;
    if (open && search_pixels >= 1.0) {
        for (int i = 0; i < kFirstTaps; ++i) {
            vec2 shadow;
            float across2;
            if (tap(pixel, spiral(i, kFirstTaps) * search_pixels, receiver, search, shadow,
                    across2) &&
                (shadow.y > 0.0 || shadow.x < 1.0)) {
                open = false;
                break;
            }
        }
    }
    if (!open && search_pixels >= 1.0) {
        for (int i = 0; i < kSearchTaps; ++i) {
            vec2 shadow;
            float across2;
            if (tap(pixel, spiral(i, kSearchTaps) * search_pixels, receiver, search, shadow,
                    across2)) {
                if (shadow.y > 0.0) {
                    float weight = exp(-across2 * closeness);
                    gap_sum += weight * shadow.y;
                    gaps += weight;
                }
                lit_taps += shadow.x;
            }
        }
    }
    float lit = own.x;
    // No occluder around (fully lit) or no light around (the umbra): the hard value stands.
    if (gaps > 0.0 && lit_taps > 0.0) {
        // A pixel in the hard shadow has its own occluder's distance: the edge that shades it.
        // Its neighbours' would widen a contact's penumbra (a box's foot) into its umbra, and
        // so would the map's distance where the frame shows the occluder nearer (contact()).
        float d = own.y > 0.0 ? min(own.y, contact(receiver, search)) : gap_sum / gaps;
        d = min(d, 0.999 * distance_to_light);
        float width = min(u_radius * d / max(distance_to_light - d, 1e-4), search);
        float width_pixels = width * stretch / receiver.metres_per_pixel;
        if (width_pixels >= 0.5) {
            float sum = own.x;
            float count = 1.0;
            for (int i = 0; i < kFilterTaps; ++i) {
                vec2 shadow;
                float across2;
                if (tap(pixel, spiral(i, kFilterTaps) * width_pixels, receiver, width, shadow,
                        across2)) {
                    sum += shadow.x;
                    count += 1.0;
                }
            }
            lit = sum / count;
        }
    }
    vec3 albedo = texelFetch(u_albedo, pixel, 0).rgb;
    out_radiance = vec4(lambert_radiance(albedo, e * lit), 1.0);
}
