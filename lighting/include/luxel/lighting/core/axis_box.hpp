#pragma once

#include <limits>
#include <span>

#include <glm/glm.hpp>

namespace luxel::lighting {

/// An axis-aligned box; empty (min > max, meeting nothing) until a point is added. Where the
/// photon world says geometry changed, and what the maps test those places against.
struct AxisBox {
    glm::vec3 min{std::numeric_limits<float>::max()};
    glm::vec3 max{std::numeric_limits<float>::lowest()};

    [[nodiscard]] bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }
    void add(const glm::vec3& p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    [[nodiscard]] bool meets(const AxisBox& other) const {
        return glm::all(glm::lessThanEqual(min, other.max)) &&
               glm::all(glm::lessThanEqual(other.min, max));
    }
    [[nodiscard]] bool contains(const glm::vec3& p) const {
        return glm::all(glm::lessThanEqual(min, p)) && glm::all(glm::lessThanEqual(p, max));
    }
};

/// The box around the points.
[[nodiscard]] inline AxisBox box_around(std::span<const glm::vec3> points) {
    AxisBox box;
    for (const glm::vec3& p : points) {
        box.add(p);
    }
    return box;
}

/// The box around a box's eight corners moved by `transform` (an empty box stays empty): what a
/// moved object or surface covers, from the box of its own vertices, without visiting them.
[[nodiscard]] inline AxisBox transformed(const AxisBox& box, const glm::mat4& transform) {
    AxisBox moved;
    if (box.empty()) {
        return moved;
    }
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 local((corner & 1) ? box.max.x : box.min.x,
                              (corner & 2) ? box.max.y : box.min.y,
                              (corner & 4) ? box.max.z : box.min.z);
        moved.add(glm::vec3(transform * glm::vec4(local, 1.0f)));
    }
    return moved;
}

}  // namespace luxel::lighting
