#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/lighting/core/photon_map.hpp"

/// The AIM's density estimate (docs/METHOD.md §5.1-5.3): irradiance at a point from the N
/// nearest stored photon hits, E = sum of their power / (pi r^2), r the distance to the N-th
/// (the N-th itself, on the rim, is not summed: see photon_density.cpp).
/// A kd-tree (nanoflann) is built over the hits of one surface and of the surfaces that can
/// contribute to it, and dropped when that surface's AIM is done: only the surface being
/// rebuilt needs a tree in memory.
namespace luxel::lighting {

enum class PhotonSelection {
    Full,          ///< every hit: the full approximated illumination
    IndirectOnly,  ///< hits with at least one diffuse bounce: the indirect part
};

/// How photons within the radius are weighted.
enum class DensityKernel {
    /// Every photon counts fully: E = sum P / (pi r^2), the source's estimate.
    Disc,
    /// w = 1 - (d / r)^2, normalised (E = 2 sum w P / (pi r^2)): photons at the rim, whose
    /// coming and going as r changes is the estimate's main noise, count little. Same mean for
    /// a linear irradiance field, noticeably less noise (docs/PERFORMANCE.md, maps).
    Epanechnikov,
};

struct DensitySettings {
    std::uint32_t nearest = 50;  ///< N
    /// The search radius is capped here (metres): with fewer than N photons within it, the
    /// estimate uses the photons found and this radius, so sparse regions stay finite.
    float max_radius = 0.5f;
    /// The disc filter: a photon counts only if its distance from the tangent plane at the
    /// query is at most this fraction of r, so photons on a wall meeting the floor at a corner
    /// do not brighten the floor.
    float disc_thickness = 0.25f;
    DensityKernel kernel = DensityKernel::Epanechnikov;
};

/// The raw ingredients of one estimate: the power of the photons counted and the radius of the
/// disc they were found in, so a caller that knows how much of the disc lies on the surface can
/// divide by that area instead of pi r^2 (IlluminationMaps does, at surface borders).
struct DensitySample {
    /// The kernel-weighted power, scaled so that power / (pi r^2) is the irradiance.
    glm::dvec3 power{0.0};
    double radius = 0.0;  ///< 0 when nothing was found
};

class PhotonDensity {
  public:
    /// Builds the tree over the hits of `surfaces` (the surface itself and its neighbours),
    /// keeping only those `selection` asks for.
    PhotonDensity(const PhotonMap& map, std::span<const std::uint32_t> surfaces,
                  PhotonSelection selection);
    ~PhotonDensity();
    PhotonDensity(const PhotonDensity&) = delete;
    PhotonDensity& operator=(const PhotonDensity&) = delete;

    /// The photons counted around `position` (see irradiance()).
    [[nodiscard]] DensitySample sample(const glm::vec3& position, const glm::vec3& normal,
                                       const DensitySettings& settings) const;
    /// Irradiance (W/m^2 per channel) at `position` on a surface with unit `normal`. Zero when
    /// no photon is within the capped radius; never NaN.
    [[nodiscard]] glm::vec3 irradiance(const glm::vec3& position, const glm::vec3& normal,
                                       const DensitySettings& settings) const;
    /// Outgoing radiance of a Lambertian surface: albedo * E / pi.
    [[nodiscard]] glm::vec3 radiance(const glm::vec3& position, const glm::vec3& normal,
                                     const glm::vec3& albedo,
                                     const DensitySettings& settings) const;

    [[nodiscard]] std::size_t photon_count() const;

  private:
    struct Tree;
    std::unique_ptr<Tree> tree_;
};

}  // namespace luxel::lighting
