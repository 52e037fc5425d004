#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace luxel::scene {

/// One id per position, positions within `tolerance` of each other (per axis) sharing one, ids
/// numbered from 0 in order of first appearance: an exporter's seam copies a position exactly,
/// but a mesh made with trigonometry closes its seam with cos(2 pi) and sin(2 pi), a rounding
/// away from where it started. Each position looks for an earlier one in the 8 cells (twice the
/// tolerance wide) that can hold one, so the cost is linear in the positions.
[[nodiscard]] std::vector<std::uint32_t> welded_ids(const std::vector<glm::vec3>& positions,
                                                    float tolerance);

}  // namespace luxel::scene
