#include "luxel/ecs/transform.hpp"

#include <cmath>

namespace luxel::ecs {

glm::mat4 Transform::matrix() const noexcept {
    glm::mat4 result = glm::mat4_cast(rotation);
    result[0] *= scale.x;
    result[1] *= scale.y;
    result[2] *= scale.z;
    result[3] = glm::vec4(translation, 1.0f);
    return result;
}

namespace {

/// A unit vector perpendicular to `v` (any one), for degenerate (zero-scale) axes.
glm::vec3 any_perpendicular(const glm::vec3& v) {
    const glm::vec3 other = std::abs(v.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    return glm::normalize(glm::cross(v, other));
}

}  // namespace

Transform Transform::from_matrix(const glm::mat4& matrix) noexcept {
    constexpr float tiny = 1e-12f;
    const glm::vec3 column_x(matrix[0]);
    const glm::vec3 column_y(matrix[1]);
    const glm::vec3 column_z(matrix[2]);

    // Gram-Schmidt: an orthonormal basis (x_axis, y_axis, z_axis) and the diagonal of the upper
    // triangular factor as the scale. Degenerate (zero-length) columns fall back to any axis that
    // completes the basis, with a zero scale along them.
    const float length_x = glm::length(column_x);
    const glm::vec3 x_axis = length_x > tiny ? column_x / length_x : glm::vec3(1, 0, 0);
    glm::vec3 y_rest = column_y - glm::dot(column_y, x_axis) * x_axis;
    const float length_y = glm::length(y_rest);
    const glm::vec3 y_axis = length_y > tiny ? y_rest / length_y : any_perpendicular(x_axis);
    const glm::vec3 z_axis = glm::cross(x_axis, y_axis);

    Transform result;
    result.translation = glm::vec3(matrix[3]);
    result.scale = glm::vec3(length_x, glm::dot(column_y, y_axis), glm::dot(column_z, z_axis));
    result.rotation = glm::normalize(glm::quat_cast(glm::mat3(x_axis, y_axis, z_axis)));
    return result;
}

}  // namespace luxel::ecs
