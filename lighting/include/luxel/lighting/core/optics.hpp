#pragma once

#include <optional>

#include <glm/glm.hpp>

/// Specular optics for caustic photons. Directions are unit vectors; `d` points along the
/// travel direction, `n` is the surface normal on the side the ray arrives from (dot(d, n) < 0).
namespace luxel::lighting::optics {

/// Mirror reflection: d - 2 (d . n) n.
[[nodiscard]] glm::vec3 reflect(const glm::vec3& d, const glm::vec3& n);

/// Snell refraction from a medium of index eta_from into eta_to, or nullopt on total internal
/// reflection. The result is a unit vector on the far side of the surface.
[[nodiscard]] std::optional<glm::vec3> refract(const glm::vec3& d, const glm::vec3& n,
                                               float eta_from, float eta_to);

/// Unpolarised Fresnel reflectance of a smooth dielectric interface for light arriving at
/// angle acos(cos_incident) from the normal: the mean of the s and p reflectances. 1 beyond
/// the critical angle (total internal reflection).
[[nodiscard]] float fresnel_dielectric(float cos_incident, float eta_from, float eta_to);

/// Schlick's approximation for conductors (metals): F0 + (1 - F0)(1 - cos)^5 per channel,
/// with F0 the metal's base colour.
[[nodiscard]] glm::vec3 fresnel_conductor(float cos_incident, const glm::vec3& f0);

}  // namespace luxel::lighting::optics
