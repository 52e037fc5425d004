#pragma once

#include <glm/glm.hpp>

#include "luxel/lighting/core/ray_scene.hpp"

/// Photon differentials (docs/METHOD.md §7.4): the ray differentials of Igehy (1999) carried by
/// a caustic photon, as S. Larsen (2006, §2.10, §4.4.5) proposes for close-ups. Two offset
/// photons, one step apart in the emission's two sample directions, are followed to first order
/// through every specular interaction; at the diffuse hit they span the patch the photon stands
/// for. A photon in a focus gets a small patch, one in a thin splash a wide one, so a density
/// estimate that spreads each photon over its own patch keeps its power and widens only where
/// the photons are sparse.
namespace luxel::lighting {

/// The first-order offsets of a photon's ray: d(position) and d(direction) per unit step of the
/// two emission offsets u and v. `valid` turns false when an offset ray leaves the path (total
/// internal reflection where the photon refracts, a tangent hit): the footprint is then unknown.
struct PhotonDifferential {
    glm::vec3 dp_u{0.0f};
    glm::vec3 dp_v{0.0f};
    glm::vec3 dd_u{0.0f};
    glm::vec3 dd_v{0.0f};
    bool valid = true;
};

/// The differential at emission for a photon that stands for `area` m^2 of emitting surface
/// (position offsets) and `solid_angle` sr of directions (direction offsets), both already
/// the photon's share: offsets of sqrt(area) and sqrt(solid_angle) along two unit vectors
/// perpendicular to `direction` (and to each other), so the patch they span is the share.
[[nodiscard]] PhotonDifferential emission_differential(const glm::vec3& direction, double area,
                                                       double solid_angle);

/// Igehy's transfer: the photon travelled `distance` along `direction` and hit a plane of
/// normal `normal`; the offsets move onto that plane.
void transfer(PhotonDifferential& differential, const glm::vec3& direction, float distance,
              const glm::vec3& normal);

/// The change of the unit shading normal per world displacement in the hit triangle's plane
/// (zero for a mesh without vertex normals): what curves a smooth sphere's refraction.
[[nodiscard]] glm::mat3 shading_normal_jacobian(const RayScene& scene, const RayHit& hit);

/// Mirror reflection of `direction` about the unit normal `normal` (facing the photon), whose
/// change per displacement is `normal_jacobian`.
void reflect(PhotonDifferential& differential, const glm::vec3& direction, const glm::vec3& normal,
             const glm::mat3& normal_jacobian);

/// Refraction from `direction` into `refracted` across `normal` (facing the photon) with
/// eta = eta_from / eta_to. Invalidates the differential where an offset ray would be totally
/// reflected.
void refract(PhotonDifferential& differential, const glm::vec3& direction,
             const glm::vec3& refracted, const glm::vec3& normal, const glm::mat3& normal_jacobian,
             float eta);

/// The area of the patch the offsets span at the hit, |dp_u x dp_v| (m^2); 0 when invalid or
/// not finite.
[[nodiscard]] float footprint_area(const PhotonDifferential& differential);

}  // namespace luxel::lighting
