#pragma once

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>

#include <glm/glm.hpp>

namespace luxel::lighting {

/// The cells of a grid of unit cells that the segment from `a` to `b` (both in cell units)
/// passes through, in order from a's cell to b's: a 3D digital differential analyser
/// (Amanatides & Woo), stepping into whichever neighbour the line reaches first. Calls
/// visit(cell) for each (b's cell also when rounding leaves the walk a step short of it, so a
/// cell may be visited twice). Returns false, visiting nothing, when the walk would take more
/// than `max_cells` cells. Shared by the global photons' path index and the caustic lists'
/// path cells, which differ in what a cell is (a hashed key, a bit of a bounded grid).
template <typename Visit>
bool walk_grid(const glm::dvec3& a, const glm::dvec3& b, std::int64_t max_cells, Visit&& visit) {
    glm::i64vec3 cell(static_cast<std::int64_t>(std::floor(a.x)),
                      static_cast<std::int64_t>(std::floor(a.y)),
                      static_cast<std::int64_t>(std::floor(a.z)));
    const glm::i64vec3 last(static_cast<std::int64_t>(std::floor(b.x)),
                            static_cast<std::int64_t>(std::floor(b.y)),
                            static_cast<std::int64_t>(std::floor(b.z)));
    const std::int64_t span =
        std::abs(last.x - cell.x) + std::abs(last.y - cell.y) + std::abs(last.z - cell.z) + 1;
    if (span > max_cells) {
        return false;
    }
    const glm::dvec3 delta = b - a;
    glm::i64vec3 step(0);
    glm::dvec3 next(std::numeric_limits<double>::infinity());
    glm::dvec3 advance(std::numeric_limits<double>::infinity());
    for (int axis = 0; axis < 3; ++axis) {
        if (delta[axis] > 0.0) {
            step[axis] = 1;
            next[axis] = (static_cast<double>(cell[axis] + 1) - a[axis]) / delta[axis];
            advance[axis] = 1.0 / delta[axis];
        } else if (delta[axis] < 0.0) {
            step[axis] = -1;
            next[axis] = (static_cast<double>(cell[axis]) - a[axis]) / delta[axis];
            advance[axis] = -1.0 / delta[axis];
        }
    }
    for (std::int64_t visited = 0; visited < span; ++visited) {
        visit(cell);
        if (cell == last) {
            return true;
        }
        const int axis = next.x <= next.y ? (next.x <= next.z ? 0 : 2) : (next.y <= next.z ? 1 : 2);
        if (step[axis] == 0) {
            break;
        }
        cell[axis] += step[axis];
        next[axis] += advance[axis];
    }
    visit(last);
    return true;
}

}  // namespace luxel::lighting
