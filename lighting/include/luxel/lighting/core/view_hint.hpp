#pragma once

#include <glm/glm.hpp>

#include "luxel/lighting/core/axis_box.hpp"

namespace luxel::lighting {

/// Where the player looks (LightingSystem::set_view): the gather passes that a change asks for
/// and the refinement passes go first for the surfaces the camera's frustum holds, so a change
/// a player watches is fixed before one behind them (docs/METHOD.md §6.10). A hint, not a cull:
/// every surface is still gathered, in the order the budget allows.
struct ViewHint {
    /// World to clip space, OpenGL's convention (inside: -w <= x, y, z <= w).
    glm::mat4 view_projection{1.0f};
};

/// Whether any of the box can be inside the frustum: false only when all eight corners lie
/// outside one of its six planes (conservative: a box near a frustum's corner may pass). A box
/// with a corner behind the eye (w <= 0) is tested by the same planes, which hold for it in
/// homogeneous clip space.
[[nodiscard]] inline bool in_view(const AxisBox& box, const glm::mat4& view_projection) {
    if (box.empty()) {
        return false;
    }
    int outside[6] = {0, 0, 0, 0, 0, 0};
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec4 p = view_projection * glm::vec4((corner & 1) ? box.max.x : box.min.x,
                                                        (corner & 2) ? box.max.y : box.min.y,
                                                        (corner & 4) ? box.max.z : box.min.z, 1.0f);
        outside[0] += p.x < -p.w ? 1 : 0;
        outside[1] += p.x > p.w ? 1 : 0;
        outside[2] += p.y < -p.w ? 1 : 0;
        outside[3] += p.y > p.w ? 1 : 0;
        outside[4] += p.z < -p.w ? 1 : 0;
        outside[5] += p.z > p.w ? 1 : 0;
    }
    for (const int count : outside) {
        if (count == 8) {
            return false;
        }
    }
    return true;
}

}  // namespace luxel::lighting
