#include "luxel/lighting/core/irradiance_probes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>

#include "luxel/lighting/core/octahedral.hpp"
#include "luxel/lighting/core/splitmix.hpp"
#include "luxel/runtime/jobs.hpp"

namespace luxel::lighting {
namespace {

/// How a distance texel weighs a ray at cosine c from its direction: c^50, a cone about as
/// wide as the texel (DDGI's sharpness for 8x8 squares), by squaring (a pow per ray and texel
/// was most of a probe's time). Below the cutoff the weight is under 3e-4 and skipped.
float depth_weight(float c) {
    const float c2 = c * c;
    const float c4 = c2 * c2;
    const float c8 = c4 * c4;
    const float c16 = c8 * c8;
    const float c32 = c16 * c16;
    return c32 * c16 * c2;
}
constexpr float kDepthCutoff = 0.85f;
/// A probe with more than this share of its hits on back faces sits inside geometry or outside
/// a closed level (rays that hit nothing do not count: above open ground they see the sky).
constexpr float kInsideShare = 0.25f;
/// A probe moves at most this share of the spacing to leave geometry (beyond, it would stand
/// for another cell's light).
constexpr float kMaxOffsetShare = 0.45f;

/// A hash of (probe, pass) to three numbers in [0, 1): the pass's rotation of the ray pattern.
glm::vec3 pass_numbers(std::size_t probe, std::uint32_t pass) {
    std::uint64_t h = (static_cast<std::uint64_t>(probe) << 32) ^ pass;
    glm::vec3 out;
    for (int i = 0; i < 3; ++i) {
        out[i] = unit_interval(splitmix64(h));
    }
    return out;
}

/// A uniformly distributed rotation from three uniform numbers (Shoemake's unit quaternion).
glm::mat3 random_rotation(const glm::vec3& u) {
    const float a = std::sqrt(1.0f - u.x);
    const float b = std::sqrt(u.x);
    const float t1 = glm::two_pi<float>() * u.y;
    const float t2 = glm::two_pi<float>() * u.z;
    const glm::quat q(b * std::cos(t2), a * std::sin(t1), a * std::cos(t1), b * std::sin(t2));
    return glm::mat3_cast(glm::normalize(q));
}

/// Ray i of n on the sphere: the spherical Fibonacci pattern, as even as n points get.
glm::vec3 fibonacci_direction(std::uint32_t i, std::uint32_t n) {
    const float golden = 0.618033988749895f;  // 1 / phi
    const float z = 1.0f - (2.0f * static_cast<float>(i) + 1.0f) / static_cast<float>(n);
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    float turns = static_cast<float>(i) * golden;
    turns -= std::floor(turns);
    const float phi = glm::two_pi<float>() * turns;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

/// The direction at the centre of interior texel (x, y) of a `size`-square octahedral map.
glm::vec3 texel_direction(int x, int y, int size) {
    const float n = static_cast<float>(size);
    return octahedral_decode(
        glm::vec2((static_cast<float>(x) + 0.5f) / n, (static_cast<float>(y) + 0.5f) / n) * 2.0f -
        1.0f);
}

constexpr std::size_t kIrradianceTexels =
    static_cast<std::size_t>(kProbeIrradianceSize) * kProbeIrradianceSize;

/// The irradiance map's texel directions, row by row, as three arrays (computed once): the
/// convolution below runs over texels in its inner loop, which the compiler vectorises.
struct TexelDirections {
    std::array<float, kIrradianceTexels> x{};
    std::array<float, kIrradianceTexels> y{};
    std::array<float, kIrradianceTexels> z{};
};
const TexelDirections& irradiance_texel_directions() {
    static const TexelDirections directions = [] {
        TexelDirections out;
        for (int ty = 0; ty < kProbeIrradianceSize; ++ty) {
            for (int tx = 0; tx < kProbeIrradianceSize; ++tx) {
                const glm::vec3 d = texel_direction(tx, ty, kProbeIrradianceSize);
                const std::size_t t = static_cast<std::size_t>(ty) * kProbeIrradianceSize +
                                      static_cast<std::size_t>(tx);
                out.x[t] = d.x;
                out.y[t] = d.y;
                out.z[t] = d.z;
            }
        }
        return out;
    }();
    return directions;
}

/// Writes a `size`-square octahedral map into its tile of size + 2 texels with the border that
/// makes bilinear filtering seamless: across each edge of the square lies the same edge,
/// mirrored about its midpoint; across each corner, the opposite corner.
template <class Value, class Interior>
void fill_tile(int size, std::span<Value> tile, const Interior& interior) {
    const int n = size;
    const auto put = [&](int x, int y, const Value& value) {
        tile[static_cast<std::size_t>(y) * static_cast<std::size_t>(n + 2) +
             static_cast<std::size_t>(x)] = value;
    };
    for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
            put(x + 1, y + 1, interior(x, y));
        }
    }
    for (int k = 0; k < n; ++k) {
        put(k + 1, 0, interior(n - 1 - k, 0));
        put(k + 1, n + 1, interior(n - 1 - k, n - 1));
        put(0, k + 1, interior(0, n - 1 - k));
        put(n + 1, k + 1, interior(n - 1, n - 1 - k));
    }
    put(0, 0, interior(n - 1, n - 1));
    put(n + 1, 0, interior(0, n - 1));
    put(0, n + 1, interior(n - 1, 0));
    put(n + 1, n + 1, interior(0, 0));
}

/// Bilinear lookup towards `direction` in a tile written by fill_tile (as a GPU sampler with
/// linear filtering reads the same tile).
template <class Value>
Value sample_tile(int size, std::span<const Value> tile, const glm::vec3& direction) {
    const int side = size + 2;
    const glm::vec2 square = octahedral_encode(direction);
    // In tile texels (centres at t + 0.5), the interior starting after the border.
    const glm::vec2 f = (square * 0.5f + 0.5f) * static_cast<float>(size) + 1.0f - 0.5f;
    const glm::ivec2 t0 =
        glm::clamp(glm::ivec2(glm::floor(f)), glm::ivec2(0), glm::ivec2(side - 2));
    const glm::vec2 w = glm::clamp(f - glm::vec2(t0), glm::vec2(0.0f), glm::vec2(1.0f));
    const auto at = [&](int x, int y) {
        return tile[static_cast<std::size_t>(y) * static_cast<std::size_t>(side) +
                    static_cast<std::size_t>(x)];
    };
    const Value top = glm::mix(at(t0.x, t0.y), at(t0.x + 1, t0.y), w.x);
    const Value bottom = glm::mix(at(t0.x, t0.y + 1), at(t0.x + 1, t0.y + 1), w.x);
    return glm::mix(top, bottom, w.y);
}

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

IrradianceProbes::IrradianceProbes(ProbeGrid grid, IrradianceProbeSettings settings)
    : grid_(grid),
      settings_(settings),
      states_(grid.size()),
      sums_(grid.size()),
      wants_(grid.size(), Want::Stale),
      pass_index_(grid.size(), 0) {
    settings_.rays_per_probe = std::max<std::uint32_t>(settings_.rays_per_probe, 1);
    settings_.refine_passes = std::max<std::uint32_t>(settings_.refine_passes, 1);
}

void IrradianceProbes::lighting_changed() {
    std::fill(wants_.begin(), wants_.end(), Want::Stale);
}

std::size_t IrradianceProbes::pending() const {
    return static_cast<std::size_t>(
        std::count_if(wants_.begin(), wants_.end(), [](Want w) { return w != Want::None; }));
}

double IrradianceProbes::refined_share() const {
    if (states_.empty()) {
        return 1.0;
    }
    double done = 0.0;
    for (std::size_t i = 0; i < states_.size(); ++i) {
        if (wants_[i] == Want::None) {
            done += 1.0;
        } else if (wants_[i] == Want::Refine) {
            done += static_cast<double>(sums_[i].passes) / settings_.refine_passes;
        }
    }
    return std::clamp(done / static_cast<double>(states_.size()), 0.0, 1.0);
}

std::size_t IrradianceProbes::gather(std::size_t count, const ProbeRayTracer& tracer,
                                     JobSystem* jobs) {
    const std::size_t total = states_.size();
    if (count == 0 || total == 0 || !tracer) {
        return 0;
    }
    // Stale probes first, then refinement, each from the cursor on.
    std::vector<std::size_t> stale;
    std::vector<std::size_t> refine;
    for (std::size_t k = 0; k < total && stale.size() < count; ++k) {
        const std::size_t i = (cursor_ + k) % total;
        if (wants_[i] == Want::Stale) {
            stale.push_back(i);
        } else if (wants_[i] == Want::Refine && refine.size() < count) {
            refine.push_back(i);
        }
    }
    std::vector<std::size_t> chosen = std::move(stale);
    for (std::size_t k = 0; k < refine.size() && chosen.size() < count; ++k) {
        chosen.push_back(refine[k]);
    }
    if (chosen.empty()) {
        return 0;
    }
    cursor_ = (chosen.back() + 1) % total;
    if (jobs != nullptr && chosen.size() > 1) {
        jobs->parallel_for(0, chosen.size(),
                           [&](std::size_t k) { gather_probe(chosen[k], tracer); });
    } else {
        for (const std::size_t i : chosen) {
            gather_probe(i, tracer);
        }
    }
    ++version_;
    return chosen.size();
}

void IrradianceProbes::gather_probe(std::size_t index, const ProbeRayTracer& tracer) {
    const std::uint32_t n = settings_.rays_per_probe;
    const bool fresh = wants_[index] == Want::Stale;
    Accumulator& sum = sums_[index];
    ProbeState& state = states_[index];
    const glm::mat3 rotation = random_rotation(pass_numbers(index, pass_index_[index]++));
    std::vector<glm::vec3> directions(n);
    for (std::uint32_t i = 0; i < n; ++i) {
        directions[i] = rotation * fibonacci_direction(i, n);
    }
    std::vector<ProbeRay> rays(n);
    const glm::vec3 home = grid_.position(grid_.cell(index));
    glm::vec3 offset = fresh ? glm::vec3(0.0f) : state.offset;
    const auto seed = static_cast<std::uint32_t>(index * 2654435761u) ^ pass_index_[index];
    tracer(home + offset, directions, rays, seed);
    if (fresh) {
        // Inside geometry (a pillar, a wall the grid cuts): move out through the nearest back
        // face if that is close, else leave the probe out.
        const auto inside = [&] {
            const auto back = std::count_if(rays.begin(), rays.end(),
                                            [](const ProbeRay& r) { return r.back_face; });
            const auto hits =
                std::count_if(rays.begin(), rays.end(), [](const ProbeRay& r) { return r.hit; });
            return static_cast<float>(back) > kInsideShare * static_cast<float>(hits);
        };
        if (inside()) {
            std::size_t nearest = n;
            for (std::uint32_t i = 0; i < n; ++i) {
                if (rays[i].back_face &&
                    (nearest == n || rays[i].distance < rays[nearest].distance)) {
                    nearest = i;
                }
            }
            const float step = nearest < n ? rays[nearest].distance + 0.05f * grid_.spacing
                                           : std::numeric_limits<float>::infinity();
            bool out = false;
            if (step <= kMaxOffsetShare * grid_.spacing) {
                offset = directions[nearest] * step;
                tracer(home + offset, directions, rays, seed);
                out = !inside();
            }
            if (!out) {
                sum = {};
                state = {};
                wants_[index] = Want::None;
                return;
            }
        }
        sum = {};
        state.offset = offset;
    }
    // This pass's radiance projected (uniform directions: weight 4 pi / n each) and its
    // distances folded into the texels.
    const float max_depth = 2.0f * grid_.spacing;
    const float weight = 4.0f * glm::pi<float>() / static_cast<float>(n);
    for (ProbeRay& ray : rays) {
        ray.radiance =
            finite(ray.radiance) ? glm::max(ray.radiance, glm::vec3(0.0f)) : glm::vec3(0.0f);
    }
    if (settings_.basis == ProbeBasis::Sh2) {
        for (std::uint32_t i = 0; i < n; ++i) {
            const ShBasis y = sh_basis(directions[i]);
            for (std::size_t c = 0; c < kShCoefficients; ++c) {
                sum.radiance_sum.c[c] += rays[i].radiance * (y[c] * weight);
            }
        }
    } else {
        // Each texel's irradiance, E(t) = sum_i L_i max(0, t . w_i) 4 pi / n: the cosine
        // convolution done exactly for the texel's direction, nothing truncated. Rays outside,
        // texels inside and branch-free, so that the inner loop vectorises (tests/bench
        // ProbePass measures it).
        const TexelDirections& texels = irradiance_texel_directions();
        std::array<float, kIrradianceTexels> red{};
        std::array<float, kIrradianceTexels> green{};
        std::array<float, kIrradianceTexels> blue{};
        for (std::uint32_t i = 0; i < n; ++i) {
            const glm::vec3 w = directions[i];
            const glm::vec3 l = rays[i].radiance;
            if (l.x == 0.0f && l.y == 0.0f && l.z == 0.0f) {
                continue;  // a ray that left the level, or met a black surface
            }
            for (std::size_t t = 0; t < kIrradianceTexels; ++t) {
                const float c =
                    std::max(0.0f, texels.x[t] * w.x + texels.y[t] * w.y + texels.z[t] * w.z);
                red[t] += l.x * c;
                green[t] += l.y * c;
                blue[t] += l.z * c;
            }
        }
        sum.irradiance_sum.resize(kIrradianceTexels, glm::vec3(0.0f));
        for (std::size_t t = 0; t < kIrradianceTexels; ++t) {
            sum.irradiance_sum[t] += glm::vec3(red[t], green[t], blue[t]) * weight;
        }
    }
    for (int ty = 0; ty < kProbeDepthSize; ++ty) {
        for (int tx = 0; tx < kProbeDepthSize; ++tx) {
            const glm::vec3 texel = texel_direction(tx, ty, kProbeDepthSize);
            glm::vec3& cell = sum.depth_sum[static_cast<std::size_t>(ty) * kProbeDepthSize +
                                            static_cast<std::size_t>(tx)];
            for (std::uint32_t i = 0; i < n; ++i) {
                const float c = glm::dot(texel, directions[i]);
                if (c <= kDepthCutoff) {
                    continue;
                }
                const float w = depth_weight(c);
                const float d = std::isfinite(rays[i].distance)
                                    ? std::clamp(rays[i].distance, 0.0f, max_depth)
                                    : max_depth;
                cell += glm::vec3(w, w * d, w * d * d);
            }
        }
    }
    ++sum.passes;
    publish(index);
    wants_[index] = sum.passes < settings_.refine_passes ? Want::Refine : Want::None;
}

void IrradianceProbes::publish(std::size_t index) {
    const Accumulator& sum = sums_[index];
    ProbeState& state = states_[index];
    const float passes = static_cast<float>(std::max<std::uint32_t>(sum.passes, 1));
    if (settings_.basis == ProbeBasis::Sh2) {
        ShRgb radiance;
        for (std::size_t c = 0; c < kShCoefficients; ++c) {
            radiance.c[c] = sum.radiance_sum.c[c] / passes;
        }
        state.irradiance = convolve_cosine(radiance);
    } else {
        state.irradiance_map.resize(kProbeIrradianceTexels);
        fill_tile<glm::vec3>(kProbeIrradianceSize, state.irradiance_map, [&](int x, int y) {
            const std::size_t t =
                static_cast<std::size_t>(y) * kProbeIrradianceSize + static_cast<std::size_t>(x);
            return t < sum.irradiance_sum.size() ? sum.irradiance_sum[t] / passes : glm::vec3(0.0f);
        });
    }
    state.active = true;
    const float max_depth = 2.0f * grid_.spacing;
    fill_tile<glm::vec2>(kProbeDepthSize, state.depth, [&](int x, int y) {
        const glm::vec3& cell = sum.depth_sum[static_cast<std::size_t>(y) * kProbeDepthSize +
                                              static_cast<std::size_t>(x)];
        return cell.x > 0.0f ? glm::vec2(cell.y / cell.x, cell.z / cell.x)
                             : glm::vec2(max_depth, max_depth * max_depth);
    });
}

glm::vec2 IrradianceProbes::depth_towards(std::size_t index, const glm::vec3& direction) const {
    return sample_tile<glm::vec2>(kProbeDepthSize, states_[index].depth, direction);
}

glm::vec3 IrradianceProbes::probe_irradiance(std::size_t index, const glm::vec3& normal) const {
    const ProbeState& state = states_[index];
    if (settings_.basis == ProbeBasis::Sh2) {
        return evaluate(state.irradiance, normal);
    }
    if (state.irradiance_map.size() != kProbeIrradianceTexels) {
        return glm::vec3(0.0f);
    }
    return glm::max(sample_tile<glm::vec3>(kProbeIrradianceSize, state.irradiance_map, normal),
                    glm::vec3(0.0f));
}

glm::vec3 IrradianceProbes::irradiance(const glm::vec3& point, const glm::vec3& normal,
                                       std::optional<glm::vec3> viewer) const {
    if (states_.empty() || !finite(point) || !finite(normal) || !(grid_.spacing > 0.0f)) {
        return glm::vec3(0.0f);
    }
    const float normal_length = glm::length(normal);
    if (!(normal_length > 0.0f)) {
        return glm::vec3(0.0f);
    }
    const glm::vec3 n = normal / normal_length;
    const glm::vec3 g = (point - grid_.origin) / grid_.spacing;
    const glm::ivec3 last = glm::max(grid_.counts - 1, glm::ivec3(0));
    const glm::ivec3 base =
        glm::clamp(glm::ivec3(glm::floor(g)), glm::ivec3(0), glm::max(last - 1, glm::ivec3(0)));
    const glm::vec3 alpha = glm::clamp(g - glm::vec3(base), glm::vec3(0.0f), glm::vec3(1.0f));
    // The point the visibility test looks from: off the surface, so that the surface itself
    // does not hide the probes in front of it.
    glm::vec3 towards_viewer = n;
    if (viewer && finite(*viewer)) {
        const glm::vec3 v = *viewer - point;
        const float length = glm::length(v);
        if (length > 0.0f) {
            towards_viewer = v / length;
        }
    }
    // DDGI's weights (0.2 along the normal, 0.8 towards the viewer, 0.3 of 0.75 spacing).
    const glm::vec3 biased = point + (0.2f * n + 0.8f * towards_viewer) * (0.225f * grid_.spacing);
    glm::vec3 sum(0.0f);
    float weights = 0.0f;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::ivec3 step((corner & 1) != 0, (corner & 2) != 0, (corner & 4) != 0);
        const glm::ivec3 cell = glm::min(base + step, last);
        const std::size_t index = grid_.index(cell);
        const ProbeState& probe = states_[index];
        if (!probe.active) {
            continue;
        }
        const glm::vec3 trilinear = glm::mix(1.0f - alpha, alpha, glm::vec3(step));
        const glm::vec3 position = grid_.position(cell) + probe.offset;
        // Probes behind the surface count less (smoothly: a hard cut shows the grid).
        const glm::vec3 to_probe = position - point;
        const float to_probe_length = glm::length(to_probe);
        float weight = 1.0f;
        if (to_probe_length > 0.0f) {
            const float facing = (glm::dot(to_probe / to_probe_length, n) + 1.0f) * 0.5f;
            weight = facing * facing + 0.2f;
        }
        // Chebyshev: the chance that the probe sees the biased point, from its distances.
        const glm::vec3 from_probe = biased - position;
        const float distance = glm::length(from_probe);
        if (distance > 0.0f) {
            const glm::vec2 moments = depth_towards(index, from_probe / distance);
            if (distance > moments.x) {
                const float variance = std::abs(moments.y - moments.x * moments.x);
                const float excess = distance - moments.x;
                const float denominator = variance + excess * excess;
                float visible = denominator > 0.0f ? variance / denominator : 0.0f;
                visible = visible * visible * visible;
                weight *= visible;
            }
        }
        weight = std::max(weight, 1e-6f);
        // Weights this small are a probe the test says is hidden: crush them further, so that
        // a visible probe's light dominates (DDGI's threshold).
        constexpr float kCrush = 0.2f;
        if (weight < kCrush) {
            weight *= weight * weight / (kCrush * kCrush);
        }
        weight *= trilinear.x * trilinear.y * trilinear.z;
        sum += weight * probe_irradiance(index, n);
        weights += weight;
    }
    if (!(weights > 0.0f)) {
        return glm::vec3(0.0f);
    }
    const glm::vec3 result = sum / weights;
    return finite(result) ? glm::max(result, glm::vec3(0.0f)) : glm::vec3(0.0f);
}

ProbeGrid fit_probe_grid(const AxisBox& bounds, float spacing, std::uint32_t max_probes) {
    if (bounds.empty() || !finite(bounds.min) || !finite(bounds.max) || !(spacing > 0.0f) ||
        !std::isfinite(spacing) || max_probes < 8) {
        return {};
    }
    const glm::vec3 extent = bounds.max - bounds.min;
    const glm::vec3 centre = (bounds.min + bounds.max) * 0.5f;
    // Probes half a spacing outside each face: none sits on a level's outer walls and floor,
    // and every point inside lies between two probes on each axis.
    const auto counts_for = [&](float s) {
        const glm::dvec3 cells = glm::ceil(glm::dvec3(extent) / static_cast<double>(s));
        return glm::dvec3(cells + 2.0);
    };
    float s = spacing;
    for (int tries = 0; tries < 256; ++tries) {
        const glm::dvec3 counts = counts_for(s);
        if (counts.x * counts.y * counts.z <= static_cast<double>(max_probes)) {
            ProbeGrid grid;
            grid.spacing = s;
            grid.counts = glm::ivec3(counts);
            grid.origin = centre - 0.5f * s * glm::vec3(grid.counts - 1);
            return grid;
        }
        s *= 1.1f;
    }
    return {};
}

}  // namespace luxel::lighting
