#include "luxel/lighting/core/path_cells.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace luxel::lighting {
namespace {

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

PathCells::PathCells(const AxisBox& region) : region_(region) {
    if (region_.empty() || !finite(region_.min) || !finite(region_.max)) {
        region_ = AxisBox{};
        return;
    }
    // A flat region (a single quad) still gets cells of some size on its flat axis.
    const glm::vec3 extent = glm::max(region_.max - region_.min, glm::vec3(1e-6f));
    region_.max = region_.min + extent;
    cell_size_ = extent / static_cast<float>(kCells);
}

void PathCells::mark(const glm::ivec3& cell) {
    const int index = (cell.z * kCells + cell.y) * kCells + cell.x;
    bits_[static_cast<std::size_t>(index / 64)] |= std::uint64_t{1} << (index % 64);
}

bool PathCells::marked(const glm::ivec3& cell) const {
    const int index = (cell.z * kCells + cell.y) * kCells + cell.x;
    return (bits_[static_cast<std::size_t>(index / 64)] >> (index % 64) & 1u) != 0;
}

void PathCells::add_segment(const glm::vec3& from, const glm::vec3& to) {
    if (region_.empty() || !finite(from) || !finite(to)) {
        outside_ = true;
        return;
    }
    // Clip the segment to the region (slabs), in double: a far end of an escaped path is
    // thousands of metres away.
    const glm::dvec3 a(from);
    const glm::dvec3 d = glm::dvec3(to) - a;
    double t0 = 0.0;
    double t1 = 1.0;
    for (int axis = 0; axis < 3; ++axis) {
        const double lo = region_.min[axis];
        const double hi = region_.max[axis];
        if (std::abs(d[axis]) < 1e-300) {
            if (a[axis] < lo || a[axis] > hi) {
                outside_ = true;
                return;  // parallel to the slab and outside it
            }
            continue;
        }
        double near = (lo - a[axis]) / d[axis];
        double far = (hi - a[axis]) / d[axis];
        if (near > far) {
            std::swap(near, far);
        }
        t0 = std::max(t0, near);
        t1 = std::min(t1, far);
    }
    if (t0 > 0.0 || t1 < 1.0) {
        outside_ = true;
    }
    if (t0 > t1) {
        return;  // wholly outside
    }
    // Walk the cells from the clipped start to the clipped end (Amanatides and Woo), in cell
    // units.
    const glm::dvec3 size(cell_size_);
    const glm::dvec3 g0 = (a + t0 * d - glm::dvec3(region_.min)) / size;
    const glm::dvec3 g1 = (a + t1 * d - glm::dvec3(region_.min)) / size;
    const auto cell_of = [](const glm::dvec3& g) {
        return glm::clamp(glm::ivec3(glm::floor(g)), glm::ivec3(0), glm::ivec3(kCells - 1));
    };
    glm::ivec3 cell = cell_of(g0);
    const glm::ivec3 last = cell_of(g1);
    const glm::dvec3 span = g1 - g0;
    glm::ivec3 step(0);
    glm::dvec3 next(std::numeric_limits<double>::infinity());
    glm::dvec3 delta(std::numeric_limits<double>::infinity());
    for (int axis = 0; axis < 3; ++axis) {
        if (span[axis] > 0.0) {
            step[axis] = 1;
            delta[axis] = 1.0 / span[axis];
            next[axis] = (static_cast<double>(cell[axis]) + 1.0 - g0[axis]) / span[axis];
        } else if (span[axis] < 0.0) {
            step[axis] = -1;
            delta[axis] = -1.0 / span[axis];
            next[axis] = (g0[axis] - static_cast<double>(cell[axis])) / -span[axis];
        }
    }
    // At most one step per cell boundary on each axis; the bound only guards rounding.
    for (int steps = 0; steps <= 3 * kCells; ++steps) {
        mark(cell);
        if (cell == last) {
            break;
        }
        int axis = 0;
        if (next.y < next[axis]) {
            axis = 1;
        }
        if (next.z < next[axis]) {
            axis = 2;
        }
        if (!(next[axis] <= 1.0 + 1e-9)) {
            break;  // rounding left the last cell one short: it is marked below
        }
        cell[axis] += step[axis];
        if (cell[axis] < 0 || cell[axis] >= kCells) {
            break;
        }
        next[axis] += delta[axis];
    }
    mark(last);
}

void PathCells::merge(const PathCells& other) {
    for (std::size_t i = 0; i < bits_.size(); ++i) {
        bits_[i] |= other.bits_[i];
    }
    outside_ = outside_ || other.outside_;
}

void PathCells::clear() {
    bits_.fill(0);
    outside_ = false;
}

bool PathCells::empty() const {
    return !outside_ &&
           std::all_of(bits_.begin(), bits_.end(), [](std::uint64_t word) { return word == 0; });
}

bool PathCells::meets(const AxisBox& box) const {
    if (box.empty()) {
        return false;
    }
    const bool leaves_region =
        !region_.empty() && !(region_.contains(box.min) && region_.contains(box.max));
    if (region_.empty() || (leaves_region && outside_)) {
        return outside_ || !empty();
    }
    if (!region_.meets(box)) {
        return false;
    }
    // The cells the box covers, widened by a hundredth of a cell so that a box face on a cell
    // boundary takes both neighbours (the walk above may have rounded either way).
    const glm::vec3 lo = (glm::max(box.min, region_.min) - region_.min) / cell_size_ - 0.01f;
    const glm::vec3 hi = (glm::min(box.max, region_.max) - region_.min) / cell_size_ + 0.01f;
    const glm::ivec3 first =
        glm::clamp(glm::ivec3(glm::floor(lo)), glm::ivec3(0), glm::ivec3(kCells - 1));
    const glm::ivec3 end =
        glm::clamp(glm::ivec3(glm::floor(hi)), glm::ivec3(0), glm::ivec3(kCells - 1));
    for (int z = first.z; z <= end.z; ++z) {
        for (int y = first.y; y <= end.y; ++y) {
            for (int x = first.x; x <= end.x; ++x) {
                if (marked({x, y, z})) {
                    return true;
                }
            }
        }
    }
    return false;
}

}  // namespace luxel::lighting
