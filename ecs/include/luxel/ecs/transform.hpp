#pragma once

#include <glm/ext/matrix_transform.hpp>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace luxel::ecs {

/// An entity's placement relative to its parent (or to the world, without a Parent): translation,
/// rotation and scale, applied as scale, then rotation, then translation. Units are metres.
///
/// Written by game code; change it through Registry::patch/replace (or mark_updated after writing
/// through a reference) so the TransformSystem sees the change. An aggregate:
///     registry.emplace<Transform>(e, glm::vec3(0, 1, 0));                  // translation only
///     registry.emplace<Transform>(e, glm::vec3(0), glm::angleAxis(a, up)); // and rotation
struct Transform {
    glm::vec3 translation{0.0f};
    glm::quat rotation = glm::identity<glm::quat>();
    glm::vec3 scale{1.0f};

    /// The local-to-parent matrix T * R * S.
    [[nodiscard]] glm::mat4 matrix() const noexcept;

    /// The TRS nearest to an affine matrix: translation from the last column, rotation and scale
    /// from a QR decomposition of the upper 3x3 (Gram-Schmidt on the columns, x first). Exact for
    /// matrices built from a TRS; a shear (a parent with non-uniform scale above a rotated child)
    /// cannot be represented and is dropped. A mirroring matrix yields a negative z scale.
    [[nodiscard]] static Transform from_matrix(const glm::mat4& matrix) noexcept;

    friend bool operator==(const Transform&, const Transform&) = default;
};

/// The local-to-world matrix of an entity with a Transform, computed by the TransformSystem from
/// its Transform and its ancestors'. Read-only for game code: the system overwrites it. Changes
/// are recorded as Updated only when the matrix actually changes, so an observer of
/// WorldTransform learns exactly what moved (the lighting system's input).
struct WorldTransform {
    glm::mat4 matrix{1.0f};

    [[nodiscard]] glm::vec3 position() const noexcept { return glm::vec3(matrix[3]); }

    friend bool operator==(const WorldTransform&, const WorldTransform&) = default;
};

}  // namespace luxel::ecs
