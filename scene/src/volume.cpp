#include "luxel/scene/volume.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

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

namespace {

/// A grid cell of the welding tolerance.
struct Cell {
    std::int64_t x, y, z;
    bool operator==(const Cell&) const = default;
};

struct CellHash {
    std::size_t operator()(const Cell& c) const {
        auto h = static_cast<std::uint64_t>(c.x);
        h = h * 0x9E3779B97F4A7C15ull ^ static_cast<std::uint64_t>(c.y);
        h = h * 0x9E3779B97F4A7C15ull ^ static_cast<std::uint64_t>(c.z);
        return static_cast<std::size_t>(h ^ (h >> 29));
    }
};

/// One id per position, positions within `tolerance` of each other (per axis) sharing one:
/// an exporter's seam copies a position exactly, but a mesh made with trigonometry closes
/// its seam with cos(2 pi) and sin(2 pi), a rounding away from where it started. Each position
/// looks for an earlier one in its own grid cell and the 26 around it.
std::vector<std::uint32_t> welded_ids(const std::vector<glm::vec3>& positions, float tolerance) {
    std::unordered_multimap<Cell, std::uint32_t, CellHash> cells;
    cells.reserve(positions.size());
    std::vector<std::uint32_t> id(positions.size());
    std::uint32_t next = 0;
    const double size = static_cast<double>(tolerance);
    for (std::size_t i = 0; i < positions.size(); ++i) {
        const glm::vec3& p = positions[i];
        const Cell cell{static_cast<std::int64_t>(std::floor(static_cast<double>(p.x) / size)),
                        static_cast<std::int64_t>(std::floor(static_cast<double>(p.y) / size)),
                        static_cast<std::int64_t>(std::floor(static_cast<double>(p.z) / size))};
        std::optional<std::uint32_t> found;
        for (std::int64_t dx = -1; dx <= 1 && !found; ++dx) {
            for (std::int64_t dy = -1; dy <= 1 && !found; ++dy) {
                for (std::int64_t dz = -1; dz <= 1 && !found; ++dz) {
                    const auto [first, last] =
                        cells.equal_range({cell.x + dx, cell.y + dy, cell.z + dz});
                    for (auto it = first; it != last; ++it) {
                        const glm::vec3 d = glm::abs(positions[it->second] - p);
                        if (d.x <= tolerance && d.y <= tolerance && d.z <= tolerance) {
                            found = id[it->second];
                            break;
                        }
                    }
                }
            }
        }
        if (found) {
            id[i] = *found;
        } else {
            id[i] = next++;
            cells.emplace(cell, static_cast<std::uint32_t>(i));
        }
    }
    return id;
}

}  // namespace

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
