// Shadow-map lookups. Maps hold linear depth (see shadow.frag), so the bias is in metres: the
// receiver is pushed 1.5 texels along its normal (normal offset: removes acne on surfaces the
// light grazes) and compared one texel (more on slanted surfaces) nearer the light. Filtered
// lookups average 3 x 3 hardware-compared bilinear taps one texel apart (PCF): a soft edge
// about three texels wide; unfiltered ones take one tap.

#include "render/lights.glsl"

// The receiver after the normal offset, and the depth bias in metres, for a texel of world
// size `texel` at the receiver.
vec3 shadow_receiver(vec3 p, vec3 n, float texel) {
    return p + n * (1.5 * texel);
}

float slope_bias(float texel, float cos_theta) {
    float c = clamp(cos_theta, 0.05, 1.0);
    float tan_theta = sqrt(1.0 - c * c) / c;
    return texel * (1.0 + min(tan_theta, 3.0));
}

float cube_shadow(samplerCubeShadow map, Light light, vec3 p, vec3 n, bool filtered) {
    vec3 light_position = light.position_kind.xyz;
    float far = light.direction_far.w;
    float texel = light.params.z * length(p - light_position);
    vec3 v = shadow_receiver(p, n, texel) - light_position;
    float distance = length(v);
    if (!(distance > 0.0)) {
        return 1.0;
    }
    float reference = (distance - slope_bias(texel, dot(n, -v / distance))) / far;
    if (!filtered) {
        return texture(map, vec4(v, reference));
    }
    vec3 axis = v / distance;
    vec3 t = normalize(cross(axis, abs(axis.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0)));
    vec3 b = cross(axis, t);
    float step_size = light.params.z * distance;
    float lit = 0.0;
    for (int j = -1; j <= 1; ++j) {
        for (int i = -1; i <= 1; ++i) {
            lit += texture(map, vec4(v + (t * float(i) + b * float(j)) * step_size, reference));
        }
    }
    return lit / 9.0;
}

float map_shadow(sampler2DShadow map, Light light, vec3 p, vec3 n, bool filtered) {
    bool ortho = int(light.params.w) == SHADOW_ORTHO;
    vec3 origin = light.position_kind.xyz;
    vec3 direction = light.direction_far.xyz;
    float far = light.direction_far.w;
    float texel = ortho ? light.params.z : light.params.z * length(p - origin);
    vec3 q = shadow_receiver(p, n, texel);
    vec4 clip = light.shadow_matrix * vec4(q, 1.0);
    if (!(clip.w > 0.0)) {
        return 1.0;
    }
    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) {
        return 1.0;  // outside the map: outside the spot's cone or the scene's bounds
    }
    vec3 v = q - origin;
    float distance = ortho ? dot(v, direction) : length(v);
    vec3 to_light = ortho ? -direction : -normalize(v);
    float reference = (distance - slope_bias(texel, dot(n, to_light))) / far;
    if (!filtered) {
        return texture(map, vec3(uv, reference));
    }
    vec2 step_size = 1.0 / vec2(textureSize(map, 0));
    float lit = 0.0;
    for (int j = -1; j <= 1; ++j) {
        for (int i = -1; i <= 1; ++i) {
            lit += texture(map, vec3(uv + vec2(i, j) * step_size, reference));
        }
    }
    return lit / 9.0;
}
