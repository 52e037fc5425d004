#version 450 core
// Linear HDR radiance -> display: exposure, a tone curve, sRGB encoding. Mirrors
// runtime/src/tone_map.cpp, which does the same on the CPU for PNG files.

in vec2 v_uv;

uniform sampler2D u_hdr;
uniform float u_exposure;
uniform int u_operator;  // 0 clamp, 1 Reinhard, 2 ACES (Narkowicz fit)

layout(location = 0) out vec4 out_color;

vec3 curve(vec3 x) {
    x = max(x, vec3(0.0));
    if (u_operator == 0) {
        return min(x, vec3(1.0));
    }
    if (u_operator == 1) {
        return x / (1.0 + x);
    }
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

vec3 linear_to_srgb(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

void main() {
    vec3 hdr = texture(u_hdr, v_uv).rgb * u_exposure;
    out_color = vec4(linear_to_srgb(curve(hdr)), 1.0);
}
