#pragma once

#include <glm/glm.hpp>

#include "luxel/scene/scene.hpp"

namespace luxel::renderer {

/// Where the frame is seen from: world-to-view and view-to-clip matrices (GL conventions, depth
/// in [-1, 1]) and the eye position. The vertical field of view is kept for passes that need a
/// pixel's world size (the caustic filter).
struct FrameCamera {
    glm::mat4 view{1.0f};
    glm::mat4 projection{1.0f};
    glm::vec3 position{0.0f};
    float yfov = 0.8f;  ///< radians

    /// A perspective camera at `eye` looking at `target`.
    [[nodiscard]] static FrameCamera look_at(const glm::vec3& eye, const glm::vec3& target,
                                             const glm::vec3& up, float yfov, float aspect,
                                             float znear = 0.05f, float zfar = 100.0f);
    /// A scene camera (CameraComponent) placed by its entity's WorldTransform: it looks down
    /// the entity's -z axis. `aspect` is the viewport's and replaces the camera's own (which
    /// glTF makes optional anyway); an infinite far plane becomes `default_far`.
    [[nodiscard]] static FrameCamera from_scene(const scene::Camera& camera, const glm::mat4& world,
                                                float aspect, float default_far = 1000.0f);
};

}  // namespace luxel::renderer
