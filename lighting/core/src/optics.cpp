#include "luxel/lighting/core/optics.hpp"

#include <algorithm>
#include <cmath>

namespace luxel::lighting::optics {

glm::vec3 reflect(const glm::vec3& d, const glm::vec3& n) {
    return d - 2.0f * glm::dot(d, n) * n;
}

std::optional<glm::vec3> refract(const glm::vec3& d, const glm::vec3& n, float eta_from,
                                 float eta_to) {
    const float eta = eta_from / eta_to;
    const float cos_incident = std::clamp(-glm::dot(d, n), 0.0f, 1.0f);
    const float sin2_transmitted = eta * eta * (1.0f - cos_incident * cos_incident);
    if (sin2_transmitted >= 1.0f) {
        return std::nullopt;
    }
    const float cos_transmitted = std::sqrt(1.0f - sin2_transmitted);
    return glm::normalize(eta * d + (eta * cos_incident - cos_transmitted) * n);
}

float fresnel_dielectric(float cos_incident, float eta_from, float eta_to) {
    const float cos_i = std::clamp(cos_incident, 0.0f, 1.0f);
    const float sin_t = eta_from / eta_to * std::sqrt(std::max(0.0f, 1.0f - cos_i * cos_i));
    if (sin_t >= 1.0f) {
        return 1.0f;
    }
    const float cos_t = std::sqrt(std::max(0.0f, 1.0f - sin_t * sin_t));
    const float rs = (eta_from * cos_i - eta_to * cos_t) / (eta_from * cos_i + eta_to * cos_t);
    const float rp = (eta_to * cos_i - eta_from * cos_t) / (eta_to * cos_i + eta_from * cos_t);
    return 0.5f * (rs * rs + rp * rp);
}

glm::vec3 fresnel_conductor(float cos_incident, const glm::vec3& f0) {
    const float m = 1.0f - std::clamp(cos_incident, 0.0f, 1.0f);
    const float m5 = m * m * m * m * m;
    return f0 + (glm::vec3(1.0f) - f0) * m5;
}

}  // namespace luxel::lighting::optics
