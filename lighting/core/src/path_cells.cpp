#include "luxel/lighting/core/path_cells.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "grid_walk.hpp"

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
    // In cell units, where the region is [0, kCells)^3. Float suffices: an escaped path's far
    // end (1e6 m) is clipped away before any cell is read from it. This runs for every segment
    // of every caustic photon, so it is kept lean (luxel_photon_bench CausticPathCells).
    const glm::vec3 g0 = (from - region_.min) / cell_size_;
    const glm::vec3 span = (to - region_.min) / cell_size_ - g0;
    constexpr auto kSize = static_cast<float>(kCells);
    float t0 = 0.0f;
    float t1 = 1.0f;
    for (int axis = 0; axis < 3; ++axis) {
        if (span[axis] == 0.0f) {
            if (g0[axis] < 0.0f || g0[axis] > kSize) {
                outside_ = true;
                return;  // parallel to the slab and outside it
            }
            continue;
        }
        const float inverse = 1.0f / span[axis];
        float near = -g0[axis] * inverse;
        float far = (kSize - g0[axis]) * inverse;
        if (near > far) {
            std::swap(near, far);
        }
        t0 = std::max(t0, near);
        t1 = std::min(t1, far);
    }
    if (t0 > 0.0f || t1 < 1.0f) {
        outside_ = true;
    }
    if (t0 > t1) {
        return;  // wholly outside
    }
    // The cells from the clipped start to the clipped end; a clipped end on the region's far
    // face (16.0) belongs to the last cell.
    walk_grid(glm::dvec3(g0 + t0 * span), glm::dvec3(g0 + t1 * span), 4 * kCells,
              [&](const glm::i64vec3& cell) {
                  mark(glm::clamp(glm::ivec3(cell), glm::ivec3(0), glm::ivec3(kCells - 1)));
              });
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
