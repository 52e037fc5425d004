#include "luxel/lighting/reference/caustic_disc_emitter.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/constants.hpp>

namespace luxel::lighting::reference {
namespace {

/// Two unit vectors completing `axis` (unit) to an orthonormal basis.
void basis_around(const glm::dvec3& axis, glm::dvec3& e1, glm::dvec3& e2) {
    const glm::dvec3 helper =
        std::abs(axis.x) < 0.9 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
    e1 = glm::normalize(glm::cross(axis, helper));
    e2 = glm::cross(axis, e1);
}

bool positive(const glm::dvec3& v) {
    return v.x > 0.0 || v.y > 0.0 || v.z > 0.0;
}

}  // namespace

CausticDiscEmitter::CausticDiscEmitter(const ReferenceLight& light, const BoundingSphere& generator,
                                       const BoundingSphere& scene)
    : light_(light.source), intensity_(light.intensity), centre_(generator.centre) {
    const double r = static_cast<double>(generator.radius);
    if (!(r > 0.0) || !std::isfinite(r)) {
        return;
    }
    switch (light.source.kind) {
        case LightKind::Point:
        case LightKind::Spot: {
            if (!positive(intensity_)) {
                return;
            }
            apex_ = glm::dvec3(light.source.position);
            const glm::dvec3 to_centre = centre_ - apex_;
            const double d = glm::length(to_centre);
            if (!(d > r)) {
                shape_ = Shape::Sphere;  // inside the sphere: every direction reaches it
                reaches_ = true;
                return;
            }
            shape_ = Shape::Cone;
            axis_ = to_centre / d;
            basis_around(axis_, e1_, e2_);
            disc_radius_ = r * d / std::sqrt(d * d - r * r);
            reaches_ = true;
            if (light.source.kind == LightKind::Spot) {
                // The sphere's cone (half-angle asin(r / d)) against the spot's outer cone.
                const double half = std::asin(std::clamp(r / d, 0.0, 1.0));
                const double outer = static_cast<double>(light.source.outer_cone);
                const double apart = std::acos(
                    std::clamp(glm::dot(axis_, glm::normalize(glm::dvec3(light.source.direction))),
                               -1.0, 1.0));
                reaches_ = apart < outer + half;
            }
            return;
        }
        case LightKind::Directional: {
            const glm::dvec3 irradiance(light.source.power);
            if (!positive(irradiance)) {
                return;
            }
            shape_ = Shape::Beam;
            axis_ = glm::normalize(glm::dvec3(light.source.direction));
            basis_around(axis_, e1_, e2_);
            disc_radius_ = r;
            beam_power_ = irradiance * (glm::pi<double>() * r * r);
            // Start outside the scene's bounding sphere, whatever side the beam comes from.
            beam_back_ = glm::length(centre_ - glm::dvec3(scene.centre)) +
                         static_cast<double>(scene.radius) + r + 1.0;
            reaches_ = true;
            return;
        }
        case LightKind::Area:
        case LightKind::Sky:
            return;  // area-light and sky caustics are path traced (PathEstimator)
    }
}

EmittedPhoton CausticDiscEmitter::emit(const glm::dvec2& u, double photon_count) const {
    EmittedPhoton photon;
    if (!reaches_ || !(photon_count > 0.0)) {
        photon.power = glm::vec3(0.0f);
        return photon;
    }
    const double two_pi = 2.0 * glm::pi<double>();
    const double radial = disc_radius_ * std::sqrt(std::clamp(u.x, 0.0, 1.0));
    const double phi = two_pi * u.y;
    const glm::dvec3 on_disc = centre_ + radial * (std::cos(phi) * e1_ + std::sin(phi) * e2_);
    switch (shape_) {
        case Shape::Beam:
            photon.origin = glm::vec3(on_disc - beam_back_ * axis_);
            photon.direction = glm::vec3(axis_);
            photon.power = glm::vec3(beam_power_ / photon_count);
            return photon;
        case Shape::Sphere: {
            // Uniform over the sphere of directions: pdf 1 / (4 pi).
            const double z = 1.0 - 2.0 * u.x;
            const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
            const glm::dvec3 w(s * std::cos(phi), s * std::sin(phi), z);
            double scale = 4.0 * glm::pi<double>() / photon_count;
            if (light_.kind == LightKind::Spot) {
                scale *= spot_falloff(light_, glm::dot(w, glm::dvec3(light_.direction)));
            }
            photon.origin = glm::vec3(apex_);
            photon.direction = glm::vec3(w);
            photon.power = glm::vec3(intensity_ * scale);
            return photon;
        }
        case Shape::Cone: {
            const glm::dvec3 offset = on_disc - apex_;
            const double distance2 = glm::dot(offset, offset);
            const double distance = std::sqrt(distance2);
            const glm::dvec3 w = offset / distance;
            const double cosine = glm::dot(w, axis_);
            // 1 / pdf in solid angle: pi R^2 cos theta / |x - a|^2.
            double scale =
                glm::pi<double>() * disc_radius_ * disc_radius_ * cosine / distance2 / photon_count;
            if (light_.kind == LightKind::Spot) {
                scale *= spot_falloff(light_, glm::dot(w, glm::dvec3(light_.direction)));
            }
            photon.origin = glm::vec3(apex_);
            photon.direction = glm::vec3(w);
            photon.power = glm::vec3(intensity_ * scale);
            return photon;
        }
    }
    return photon;
}

}  // namespace luxel::lighting::reference
