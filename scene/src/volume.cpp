#include "luxel/scene/volume.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "luxel/scene/welding.hpp"

namespace luxel::scene {

bool absorbs_inside(const Material& material) {
    return material.transmission > 0.0f && material.thickness > 0.0f &&
           std::isfinite(material.attenuation_distance) && material.attenuation_distance > 0.0f &&
           glm::any(glm::lessThan(material.attenuation_color, glm::vec3(1.0f)));
}

glm::vec3 beer_lambert(const glm::vec3& colour, float attenuation_distance, float distance) {
    if (!(distance > 0.0f) || !(attenuation_distance > 0.0f) ||
        !std::isfinite(attenuation_distance)) {
        return glm::vec3(1.0f);
    }
    // A large ratio underflows to 0 (and pow(0, x > 0) is 0): never NaN, never above 1.
    const float ratio = std::min(distance / attenuation_distance, 1e30f);
    glm::vec3 kept;
    for (int c = 0; c < 3; ++c) {
        const float base = std::isnan(colour[c]) ? 0.0f : std::clamp(colour[c], 0.0f, 1.0f);
        kept[c] = std::pow(base, ratio);
    }
    return kept;
}

glm::vec3 volume_transmittance(const Material& material, float distance) {
    if (!absorbs_inside(material)) {
        return glm::vec3(1.0f);
    }
    return beer_lambert(material.attenuation_color, material.attenuation_distance, distance);
}

bool is_closed_surface(const Primitive& primitive) {
    if (primitive.indices.size() < 12 || primitive.indices.size() % 3 != 0) {
        return false;  // fewer than four triangles close nothing
    }
    glm::vec3 lo(std::numeric_limits<float>::max());
    glm::vec3 hi(std::numeric_limits<float>::lowest());
    for (const glm::vec3& p : primitive.positions) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
            return false;
        }
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    // A hundred-thousandth of the primitive's size: far above float rounding at any scale,
    // far below any gap a modeller means (10 micrometres on a 1 m object).
    const float extent = glm::length(hi - lo);
    if (!(extent > 0.0f) || !std::isfinite(extent)) {
        return false;
    }
    const std::vector<std::uint32_t> id = welded_ids(primitive.positions, 1e-5f * extent);
    // Each undirected edge as (low, high) welded ids, sorted: a closed surface lists every
    // edge exactly twice.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
    edges.reserve(primitive.indices.size());
    for (std::size_t t = 0; t + 2 < primitive.indices.size(); t += 3) {
        std::array<std::uint32_t, 3> corner{};
        for (int c = 0; c < 3; ++c) {
            const std::uint32_t index = primitive.indices[t + static_cast<std::size_t>(c)];
            if (index >= id.size()) {
                return false;
            }
            corner[static_cast<std::size_t>(c)] = id[index];
        }
        if (corner[0] == corner[1] || corner[1] == corner[2] || corner[2] == corner[0]) {
            continue;  // a degenerate triangle covers nothing and joins nothing
        }
        for (int e = 0; e < 3; ++e) {
            const std::uint32_t a = corner[static_cast<std::size_t>(e)];
            const std::uint32_t b = corner[static_cast<std::size_t>((e + 1) % 3)];
            edges.emplace_back(std::min(a, b), std::max(a, b));
        }
    }
    if (edges.empty()) {
        return false;
    }
    std::sort(edges.begin(), edges.end());
    for (std::size_t i = 0; i < edges.size();) {
        std::size_t j = i;
        while (j < edges.size() && edges[j] == edges[i]) {
            ++j;
        }
        if (j - i != 2) {
            return false;
        }
        i = j;
    }
    return true;
}

}  // namespace luxel::scene
