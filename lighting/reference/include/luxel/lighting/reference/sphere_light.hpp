#pragma once

#include <glm/glm.hpp>

namespace luxel::lighting::reference {

/// One direction towards a spherical light (a point or spot light with a radius), drawn
/// uniformly over the cone the sphere subtends from a receiver: the reference's estimate of
/// the light such a source delivers, penumbrae included (docs/METHOD.md §8.8).
///
/// The sphere shines with radiance L = I / (pi r^2) (I its radiant intensity), so that seen
/// from afar it delivers I cos / d^2 as the point did; a receiver's irradiance is
/// E = integral over the cone of L cos(theta) dw, estimated by L cos(theta) * solid_angle
/// for one uniform direction whose ray reaches the sphere unblocked.
struct SphereSample {
    glm::vec3 direction{0.0f};  ///< unit, from the receiver towards the sphere
    float distance = 0.0f;      ///< to the sphere's near surface along `direction`, m
    double solid_angle = 0.0;   ///< of the whole cone, sr
};

/// False when the sphere does not stand apart from `origin` (radius <= 0, or `origin` on or
/// inside it): the caller takes the light as a point there. `u` in [0, 1)^2.
[[nodiscard]] bool sample_sphere_light(const glm::vec3& origin, const glm::vec3& centre,
                                       float radius, const glm::vec2& u, SphereSample& sample);

}  // namespace luxel::lighting::reference
