// Irradiance from the irradiance probes (lighting/include/luxel/lighting/core/irradiance_probes.hpp),
// for receivers without a light map: IrradianceProbes::irradiance on the CPU, step for step
// (tests/maps_gpu compares the two). The records and the distance atlas are uploaded by
// lighting/gpu's IrradianceProbeTextures.

struct ProbeRecord {
    vec4 position;       // xyz world position (grid + offset), w: 1 = active
    vec4 irradiance[9];  // SH band 0-2 irradiance coefficients (cosine convolution folded in),
                         // with u_probe_basis 1; zero with the octahedral atlas
};

layout(std430, binding = 2) readonly buffer ProbeRecords {
    ProbeRecord u_probe[];
};
layout(binding = 18) uniform sampler2D u_probe_depth;  // RG32F: mean distance, mean square
layout(binding = 19) uniform sampler2D u_probe_irradiance;  // RGBA16F: irradiance, u_probe_basis 0

uniform int u_probes_on;
uniform vec3 u_probe_origin;
uniform float u_probe_spacing;
uniform vec3 u_probe_counts;
uniform int u_probe_tiles_per_row;
uniform int u_probe_basis;  // 0: octahedral irradiance tiles (ProbeBasis::Octahedral), 1: SH

const int PROBE_DEPTH_SIZE = 8;         // kProbeDepthSize (tiles one texel wider each side)
const int PROBE_IRRADIANCE_SIZE = 16;   // kProbeIrradianceSize

float probe_sign_not_zero(float x) {
    return x >= 0.0 ? 1.0 : -1.0;
}

vec2 probe_octahedral_encode(vec3 d) {
    float l1 = abs(d.x) + abs(d.y) + abs(d.z);
    if (!(l1 > 0.0)) {
        return vec2(0.0);
    }
    vec2 p = d.xy / l1;
    if (d.z < 0.0) {
        p = vec2((1.0 - abs(p.y)) * probe_sign_not_zero(p.x),
                 (1.0 - abs(p.x)) * probe_sign_not_zero(p.y));
    }
    return p;
}

vec3 probe_sh_irradiance(int index, vec3 n) {
    ProbeRecord r = u_probe[index];
    vec3 e = r.irradiance[0].rgb * 0.282094792
           + r.irradiance[1].rgb * (0.488602512 * n.y)
           + r.irradiance[2].rgb * (0.488602512 * n.z)
           + r.irradiance[3].rgb * (0.488602512 * n.x)
           + r.irradiance[4].rgb * (1.092548431 * n.x * n.y)
           + r.irradiance[5].rgb * (1.092548431 * n.y * n.z)
           + r.irradiance[6].rgb * (0.315391565 * (3.0 * n.z * n.z - 1.0))
           + r.irradiance[7].rgb * (1.092548431 * n.x * n.z)
           + r.irradiance[8].rgb * (0.546274215 * (n.x * n.x - n.y * n.y));
    return max(e, vec3(0.0));
}

// Bilinear lookup towards `direction` in probe `index`'s tile of an atlas of `size`-square
// octahedral maps with a one-texel border (IrradianceProbes' sample_tile).
vec4 probe_tile_sample(sampler2D atlas, int size, int index, vec3 direction) {
    vec2 square = probe_octahedral_encode(direction);
    ivec2 tile = ivec2(index % u_probe_tiles_per_row, index / u_probe_tiles_per_row);
    vec2 texel = vec2(tile * (size + 2)) + 1.0 + (square * 0.5 + 0.5) * float(size);
    return texture(atlas, texel / vec2(textureSize(atlas, 0)));
}

// Mean distance and mean square from probe `index` towards `direction`.
vec2 probe_depth_towards(int index, vec3 direction) {
    return probe_tile_sample(u_probe_depth, PROBE_DEPTH_SIZE, index, direction).rg;
}

// Probe `index`'s own irradiance for a surface facing `n` (IrradianceProbes::probe_irradiance).
vec3 probe_own_irradiance(int index, vec3 n) {
    if (u_probe_basis == 1) {
        return probe_sh_irradiance(index, n);
    }
    return max(probe_tile_sample(u_probe_irradiance, PROBE_IRRADIANCE_SIZE, index, n).rgb,
               vec3(0.0));
}

int probe_index(ivec3 cell, ivec3 counts) {
    return cell.x + counts.x * (cell.y + counts.y * cell.z);
}

// Irradiance (W/m^2) at `point` facing `normal`, seen from `viewer`; 0 without probes or where
// none is active.
vec3 probe_irradiance(vec3 point, vec3 normal, vec3 viewer) {
    if (u_probes_on == 0 || !(u_probe_spacing > 0.0) || !(dot(normal, normal) > 0.0)) {
        return vec3(0.0);
    }
    vec3 n = normalize(normal);
    ivec3 counts = ivec3(u_probe_counts + 0.5);
    ivec3 last = max(counts - 1, ivec3(0));
    vec3 g = (point - u_probe_origin) / u_probe_spacing;
    ivec3 base = clamp(ivec3(floor(g)), ivec3(0), max(last - 1, ivec3(0)));
    vec3 alpha = clamp(g - vec3(base), vec3(0.0), vec3(1.0));
    vec3 towards_viewer = n;
    float viewer_distance = length(viewer - point);
    if (viewer_distance > 0.0) {
        towards_viewer = (viewer - point) / viewer_distance;
    }
    vec3 biased = point + (0.2 * n + 0.8 * towards_viewer) * (0.225 * u_probe_spacing);
    vec3 sum = vec3(0.0);
    float weights = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
        ivec3 step = ivec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
        ivec3 cell = min(base + step, last);
        int index = probe_index(cell, counts);
        vec4 position = u_probe[index].position;
        if (position.w < 0.5) {
            continue;
        }
        vec3 trilinear = mix(1.0 - alpha, alpha, vec3(step));
        vec3 to_probe = position.xyz - point;
        float to_probe_length = length(to_probe);
        float weight = 1.0;
        if (to_probe_length > 0.0) {
            float facing = (dot(to_probe / to_probe_length, n) + 1.0) * 0.5;
            weight = facing * facing + 0.2;
        }
        vec3 from_probe = biased - position.xyz;
        float distance = length(from_probe);
        if (distance > 0.0) {
            vec2 moments = probe_depth_towards(index, from_probe / distance);
            if (distance > moments.x) {
                float variance = abs(moments.y - moments.x * moments.x);
                float excess = distance - moments.x;
                float denominator = variance + excess * excess;
                float visible = denominator > 0.0 ? variance / denominator : 0.0;
                weight *= visible * visible * visible;
            }
        }
        weight = max(weight, 1e-6);
        const float crush = 0.2;
        if (weight < crush) {
            weight *= weight * weight / (crush * crush);
        }
        weight *= trilinear.x * trilinear.y * trilinear.z;
        sum += weight * probe_own_irradiance(index, n);
        weights += weight;
    }
    return weights > 0.0 ? max(sum / weights, vec3(0.0)) : vec3(0.0);
}
