#pragma once

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/lighting/core/light_source.hpp"
#include "luxel/lighting/core/photon_differential.hpp"

/// Emission of caustic photons toward one caustic generator (docs/METHOD.md §7.1): a
/// light spends its caustic photons only on the directions that can reach the generator's
/// bounding sphere, and each photon carries the share of the power the light sends that way.
namespace luxel::lighting {

/// A cone of directions around a unit axis; cos_half_angle = -1 is every direction.
struct DirectionCone {
    glm::vec3 axis{0.0f, 0.0f, -1.0f};
    double cos_half_angle = 1.0;

    /// 2 pi (1 - cos): the cone's solid angle in steradians.
    [[nodiscard]] double solid_angle() const;
};

/// The narrowest cone from `apex` that holds the whole sphere (every direction when the apex
/// lies inside the sphere).
[[nodiscard]] DirectionCone cone_toward(const glm::vec3& apex, const BoundingSphere& sphere);

/// A direction inside `cone`, uniform in solid angle, from a 2D sample in [0,1)^2
/// (u.x: cos theta, u.y: azimuth).
[[nodiscard]] glm::vec3 direction_in_cone(const DirectionCone& cone, const glm::dvec2& u);

/// Maps QMC samples to the caustic photons of one (generator, light) pair. The photons are an
/// unbiased estimate of the light's power toward the generator's bounding sphere:
/// - point: uniform in the cone toward the sphere, power I * Omega / N with I = Phi / (4 pi);
/// - spot: the generator's cone clipped to the spot's outer cone (the smaller of the two cones
///   is sampled when one holds the other, nothing is emitted when they are disjoint), power
///   I0 * falloff(w) * Omega_sampled / N with I0 = Phi / (2 pi (1 - cos outer)) and the same
///   smoothstep falloff as PhotonEmitter;
/// - directional: a parallel beam over the disc of the sphere facing the light, starting behind
///   the whole scene, power E * pi r^2 / N;
/// - area: a point x on the light by area, then a direction in the cone from x toward the
///   sphere, power L * max(0, cos theta_x) * Omega(x) * A / N (the estimator of the flux
///   integral L cos dw dA with pdf 1 / (A Omega(x))).
/// So the photons of a pair sum (in expectation, and for point lights exactly) to the power the
/// light sends toward the sphere.
class CausticEmitter {
  public:
    /// An emitter that emits nothing (no light, or a pair that cannot interact).
    CausticEmitter() = default;
    /// `generator`: the generator's world bounding sphere; `scene`: the whole scene's, which
    /// directional beams start behind.
    CausticEmitter(const LightSource& light, const BoundingSphere& generator,
                   const BoundingSphere& scene);

    /// False when no photon of this pair can carry power (a spot aimed away from the
    /// generator, an area light facing away, a black light).
    [[nodiscard]] bool reaches_generator() const { return reaches_; }
    [[nodiscard]] LightKind kind() const { return kind_; }
    /// The cone the photons are sampled in (point and spot lights).
    [[nodiscard]] const DirectionCone& cone() const { return cone_; }
    /// The power the light sends toward the generator's sphere, watts summed over the
    /// channels, before a spot's falloff and an area light's cosine (an upper bound: what
    /// shares the refinement photons between pairs). 0 when it does not reach it.
    [[nodiscard]] double nominal_power() const {
        return reaches_ ? static_cast<double>(power_scale_.x) + power_scale_.y + power_scale_.z
                        : 0.0;
    }

    /// The bounding spheres of the light's other generators whose pairs emit (docs/METHOD.md
    /// §7.1): a ray that also crosses k of them is sampled by k + 1 pairs, so each of them
    /// carries 1 / (k + 1) of its power and overlapping cones count the light there once.
    void set_siblings(std::vector<BoundingSphere> siblings) { siblings_ = std::move(siblings); }
    [[nodiscard]] const std::vector<BoundingSphere>& siblings() const { return siblings_; }
    /// How many pairs of this light sample the ray: 1 + the siblings whose pair could emit it
    /// (for a point, spot or area light, the ray from `apex` crosses the sibling's sphere or
    /// starts inside it; for a directional light or the sky, the whole line crosses it).
    [[nodiscard]] std::uint32_t sampling_pairs(const glm::vec3& apex,
                                               const glm::vec3& direction) const;

    /// Whether some ray this pair emits may cross `sphere` (so that its photons' shares
    /// depend on a sibling there): the cones of a point or spot light, and the beam of a
    /// directional one, tested exactly; area lights and the sky always may.
    [[nodiscard]] bool may_sample(const BoundingSphere& sphere) const;

    /// Photon of direction sample `d` (Halton bases 2, 3) and position sample `p` (bases 5, 7;
    /// area lights and directional beams), one of `photon_count`. Its power is zero when the
    /// sample falls where the light does not shine (outside a spot, behind an area light), and
    /// divided by sampling_pairs where siblings' cones overlap this pair's.
    [[nodiscard]] EmittedPhoton emit(const glm::dvec2& d, const glm::dvec2& p,
                                     std::uint64_t photon_count) const;

    /// The photon differential `photon` (one of `photon_count` emitted by this pair) starts
    /// with (docs/METHOD.md §7.4): the offsets that span its share of what the pair samples.
    /// Point and spot lights: a solid angle of Omega / N; a directional beam: pi r^2 / N of its
    /// disc; an area light samples area and direction together, so each offset takes the
    /// square root of the photon's share of both, A / sqrt(N) and Omega(x) / sqrt(N); the sky
    /// is treated as a beam (its directions' share is left out, which narrows its footprints).
    [[nodiscard]] PhotonDifferential differential(const EmittedPhoton& photon,
                                                  std::uint64_t photon_count) const;

  private:
    /// emit() before the siblings' share; `apex` is where the sampled cone starts.
    [[nodiscard]] EmittedPhoton emit_alone(const glm::dvec2& d, const glm::dvec2& p,
                                           std::uint64_t photon_count, glm::vec3& apex) const;

    LightKind kind_ = LightKind::Point;
    bool reaches_ = false;
    glm::vec3 origin_{0.0f};  ///< point / spot position
    DirectionCone cone_;      ///< point / spot: the cone sampled
    /// point / spot: intensity times the sampled solid angle; directional: E pi r^2;
    /// area: L * A. Divided by the photon count at emission.
    glm::vec3 power_scale_{0.0f};
    // Spot falloff: smoothstep between the cosines of the outer and inner cones.
    glm::vec3 spot_axis_{0.0f, 0.0f, -1.0f};
    float cos_outer_ = -1.0f;
    float cos_inner_ = -1.0f;
    // Directional: the beam's disc (centre moved back behind the scene, radius, basis).
    glm::vec3 beam_centre_{0.0f};
    glm::vec3 beam_direction_{0.0f, 0.0f, -1.0f};
    float beam_radius_ = 0.0f;
    // Area: the generator and the light's triangles with their area CDF and unit normals.
    BoundingSphere generator_;
    TriangleSampler area_;  // area lights
    // An area light's pieces when its radiance varies over it (LightSource::pieces).
    std::shared_ptr<const EmissionPieces> pieces_;
    float piece_scale_ = 1.0f;
    // Sky: its radiance and scale; beams from sampled directions onto the generator's disc,
    // started beam_back_ behind its centre (outside the scene).
    std::shared_ptr<const SkyRadiance> sky_;
    float sky_scale_ = 1.0f;
    float beam_back_ = 0.0f;
    std::vector<BoundingSphere> siblings_;
};

}  // namespace luxel::lighting
