#pragma once

#include <cstddef>
#include <cstdint>

#include <glm/glm.hpp>

#include "luxel/lighting/core/axis_box.hpp"

namespace luxel::lighting {

/// Where a level's irradiance probes sit: a regular grid of `counts` probes, `spacing` metres
/// apart, the first at `origin`. Probe (i, j, k) has index i + counts.x * (j + counts.y * k).
struct ProbeGrid {
    glm::vec3 origin{0.0f};
    float spacing = 1.0f;
    glm::ivec3 counts{0};

    [[nodiscard]] std::size_t size() const {
        return static_cast<std::size_t>(counts.x) * static_cast<std::size_t>(counts.y) *
               static_cast<std::size_t>(counts.z);
    }
    [[nodiscard]] std::size_t index(const glm::ivec3& cell) const {
        return static_cast<std::size_t>(cell.x) +
               static_cast<std::size_t>(counts.x) *
                   (static_cast<std::size_t>(cell.y) +
                    static_cast<std::size_t>(counts.y) * static_cast<std::size_t>(cell.z));
    }
    [[nodiscard]] glm::ivec3 cell(std::size_t index) const {
        const auto x = static_cast<std::size_t>(counts.x);
        const auto y = static_cast<std::size_t>(counts.y);
        return {static_cast<int>(index % x), static_cast<int>((index / x) % y),
                static_cast<int>(index / (x * y))};
    }
    /// Where probe `cell` sits before it is moved out of geometry (ProbeState::offset).
    [[nodiscard]] glm::vec3 position(const glm::ivec3& cell) const {
        return origin + spacing * glm::vec3(cell);
    }
    bool operator==(const ProbeGrid&) const = default;
};

/// The grid over `bounds` (a level's geometry): probes `spacing` metres apart, or further where
/// that would take more than `max_probes` (the spacing grows until the grid fits), with one
/// probe past each face so that every point inside lies in a cell of eight probes. An empty
/// or non-finite box, or no probe allowed, gives an empty grid.
[[nodiscard]] ProbeGrid fit_probe_grid(const AxisBox& bounds, float spacing,
                                       std::uint32_t max_probes);

}  // namespace luxel::lighting
