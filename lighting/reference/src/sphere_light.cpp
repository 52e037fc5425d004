#include "luxel/lighting/reference/sphere_light.hpp"

#include <cmath>

#include <glm/gtc/constants.hpp>

namespace luxel::lighting::reference {

bool sample_sphere_light(const glm::vec3& origin, const glm::vec3& centre, float radius,
                         const glm::vec2& u, SphereSample& sample) {
    const glm::dvec3 to_centre = glm::dvec3(centre) - glm::dvec3(origin);
    const double distance2 = glm::dot(to_centre, to_centre);
    const double r2 = static_cast<double>(radius) * static_cast<double>(radius);
    if (!(radius > 0.0f) || !(distance2 > r2) || !std::isfinite(distance2)) {
        return false;
    }
    const double distance = std::sqrt(distance2);
    const glm::dvec3 w = to_centre / distance;
    // 1 - cos(theta_max) as sin^2 / (1 + cos): the plain difference loses every digit for a
    // small sphere far away, where the cone is a few micro-steradians.
    const double sin2_max = r2 / distance2;
    const double cos_max = std::sqrt(std::max(0.0, 1.0 - sin2_max));
    const double one_minus_cos_max = sin2_max / (1.0 + cos_max);
    const double one_minus_cos = static_cast<double>(u.x) * one_minus_cos_max;
    const double cos_theta = 1.0 - one_minus_cos;
    const double sin_theta = std::sqrt(std::max(0.0, one_minus_cos * (2.0 - one_minus_cos)));
    const double phi = 2.0 * glm::pi<double>() * static_cast<double>(u.y);
    // A frame around w (Frisvad's, with the sign kept continuous by copysign).
    const double sign = std::copysign(1.0, w.z);
    const double a = -1.0 / (sign + w.z);
    const double b = w.x * w.y * a;
    const glm::dvec3 t(1.0 + sign * w.x * w.x * a, sign * b, -sign * w.x);
    const glm::dvec3 s(b, sign + w.y * w.y * a, -w.y);
    const glm::dvec3 direction = glm::normalize(t * (sin_theta * std::cos(phi)) +
                                                s * (sin_theta * std::sin(phi)) + w * cos_theta);
    // The near root of |origin + x direction - centre| = r.
    const double along = distance * cos_theta;
    const double across2 = std::max(0.0, r2 - distance2 * sin_theta * sin_theta);
    sample.direction = glm::vec3(direction);
    sample.distance = static_cast<float>(std::max(0.0, along - std::sqrt(across2)));
    sample.solid_angle = 2.0 * glm::pi<double>() * one_minus_cos_max;
    return true;
}

}  // namespace luxel::lighting::reference
