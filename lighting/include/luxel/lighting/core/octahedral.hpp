#pragma once

#include <cmath>

#include <glm/glm.hpp>

namespace luxel::lighting {

/// The octahedral map of the sphere onto the square [-1, 1]^2 (Cigolle et al., "A Survey of
/// Efficient Representations for Independent Unit Vectors", JCGT 2014): the upper hemisphere
/// fills the inner diamond, the lower one the four corners. An irradiance probe's distances
/// are stored in a small square this way; shaders/render/irradiance_probes.glsl has the same
/// functions, bit for bit in intent.

/// +1 for x >= 0 (the map's folds need a sign that is never 0).
[[nodiscard]] inline float sign_not_zero(float x) {
    return x >= 0.0f ? 1.0f : -1.0f;
}

/// The square point of unit direction `d`.
[[nodiscard]] inline glm::vec2 octahedral_encode(const glm::vec3& d) {
    const float l1 = std::abs(d.x) + std::abs(d.y) + std::abs(d.z);
    if (!(l1 > 0.0f)) {
        return glm::vec2(0.0f);
    }
    glm::vec2 p(d.x / l1, d.y / l1);
    if (d.z < 0.0f) {
        p = glm::vec2((1.0f - std::abs(p.y)) * sign_not_zero(p.x),
                      (1.0f - std::abs(p.x)) * sign_not_zero(p.y));
    }
    return p;
}

/// The unit direction of square point `p` in [-1, 1]^2.
[[nodiscard]] inline glm::vec3 octahedral_decode(const glm::vec2& p) {
    glm::vec3 v(p.x, p.y, 1.0f - std::abs(p.x) - std::abs(p.y));
    if (v.z < 0.0f) {
        v = glm::vec3((1.0f - std::abs(p.y)) * sign_not_zero(p.x),
                      (1.0f - std::abs(p.x)) * sign_not_zero(p.y), v.z);
    }
    return glm::normalize(v);
}

}  // namespace luxel::lighting
