#pragma once

#include <glm/glm.hpp>

#include "luxel/lighting/core/light_source.hpp"
#include "luxel/lighting/reference/reference_scene.hpp"

namespace luxel::lighting::reference {

/// The reference's own emission of caustic photons from a delta light (point, spot,
/// directional) toward one generator sphere. It shares with the real-time CausticEmitter only
/// the light model (LightSource, ReferenceLight::intensity, spot_falloff) and estimates the same
/// integral, the power the light sends into the sphere, by a different construction, so that a
/// bug in either shows up as a difference in docs/RESULTS.md instead of cancelling out:
///
/// - point and spot: a point x uniform on the disc through the sphere's centre, facing the
///   light, of radius R = r d / sqrt(d^2 - r^2) (the tangent cone's cross-section there), and
///   the direction w = (x - a) / |x - a|. Its pdf in solid angle is |x - a|^2 / (pi R^2 cos t)
///   (t between w and the axis), and a photon carries I(w) / (N pdf). A spot's falloff is
///   evaluated per photon, so no cones are clipped (photons outside the spot carry nothing).
///   An apex inside the sphere samples the whole sphere of directions.
/// - directional: a parallel beam over the disc of radius r facing the light, starting outside
///   the scene's bounding sphere, each photon E pi r^2 / N.
class CausticDiscEmitter {
  public:
    CausticDiscEmitter() = default;
    CausticDiscEmitter(const ReferenceLight& light, const BoundingSphere& generator,
                       const BoundingSphere& scene);

    /// False when no photon can carry power: a black or area light, a degenerate sphere, a spot
    /// whose outer cone misses the sphere.
    [[nodiscard]] bool reaches_generator() const { return reaches_; }

    /// Photon of the 2D sample `u` in [0,1)^2, one of `photon_count`; zero power where the
    /// light does not shine (outside a spot).
    [[nodiscard]] EmittedPhoton emit(const glm::dvec2& u, double photon_count) const;

  private:
    enum class Shape { Cone, Sphere, Beam };
    Shape shape_ = Shape::Cone;
    bool reaches_ = false;
    LightSource light_;
    glm::dvec3 intensity_{0.0};        ///< point, spot: W/sr on the axis, before the falloff
    glm::dvec3 apex_{0.0};             ///< point, spot: the light's position
    glm::dvec3 centre_{0.0};           ///< the disc's centre: the sphere's
    glm::dvec3 axis_{0.0, 0.0, -1.0};  ///< unit: apex to centre, or the beam's travel
    glm::dvec3 e1_{1.0, 0.0, 0.0};     ///< the disc's plane
    glm::dvec3 e2_{0.0, 1.0, 0.0};
    double disc_radius_ = 0.0;
    double beam_back_ = 0.0;      ///< directional: how far behind the disc photons start
    glm::dvec3 beam_power_{0.0};  ///< directional: E pi r^2, before dividing by N
};

}  // namespace luxel::lighting::reference
