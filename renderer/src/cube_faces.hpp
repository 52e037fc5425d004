#pragma once

#include <array>
#include <cstddef>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace luxel::renderer {

/// The view matrix for rendering face `face` (0..5: +x, -x, +y, -y, +z, -z) of a cube map
/// centred at `origin` into a framebuffer. These axes follow the GL cube-map face conventions,
/// so a lookup with direction (p - origin) reads what was rendered towards p (shadow cubes and
/// specular probes both rely on it).
[[nodiscard]] inline glm::mat4 cube_face_view(const glm::vec3& origin, int face) {
    static const std::array<std::array<glm::vec3, 2>, 6> faces = {{
        {glm::vec3(1, 0, 0), glm::vec3(0, -1, 0)},
        {glm::vec3(-1, 0, 0), glm::vec3(0, -1, 0)},
        {glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)},
        {glm::vec3(0, -1, 0), glm::vec3(0, 0, -1)},
        {glm::vec3(0, 0, 1), glm::vec3(0, -1, 0)},
        {glm::vec3(0, 0, -1), glm::vec3(0, -1, 0)},
    }};
    const auto& axes = faces[static_cast<std::size_t>(face)];
    return glm::lookAt(origin, origin + axes[0], axes[1]);
}

}  // namespace luxel::renderer
