#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/lighting/core/light_source.hpp"
#include "luxel/lighting/core/photon_map.hpp"
#include "luxel/lighting/core/ray_scene.hpp"

namespace luxel::lighting {

/// How a surface scatters photons.
enum class Scattering {
    Diffuse,     ///< Lambertian with `albedo`: photons are stored, then Russian roulette
    Mirror,      ///< metal: reflect with Schlick Fresnel of `tint`
    Dielectric,  ///< glass, water: Fresnel-weighted choice of reflection or refraction
};

struct TraceMaterial {
    Scattering scattering = Scattering::Diffuse;
    glm::vec3 albedo{0.5f};  ///< diffuse reflectance
    glm::vec3 tint{1.0f};    ///< mirror F0 or dielectric transmittance colour
    float ior = 1.5f;
    /// A dielectric solid's inside (KHR_materials_volume, scene::beer_lambert): a path of d
    /// metres inside keeps attenuation_color ^ (d / attenuation_distance); infinity: clear.
    glm::vec3 attenuation_color{1.0f};
    float attenuation_distance = std::numeric_limits<float>::infinity();
    /// A dielectric whose triangles close up (scene::is_closed_surface): behind its faces lies
    /// its inside, a medium of index `ior` that a ray enters and leaves. An open sheet (a pane
    /// as one quad, a water surface) is one interface with no second side to it.
    bool closed = false;
};

/// The sample of dimension `dim` for photon `index` of a light with `seed`: the Halton radical
/// inverse in the dim-th prime for the first 32 dimensions, Cranley-Patterson rotated per light
/// from dimension 4 on (dimensions 0-3 pick the emission and must not move, they define the
/// groups); a hash beyond, for very long paths. Deterministic and independent of threads.
[[nodiscard]] double photon_sample(std::uint64_t index, std::uint32_t dim, std::uint32_t seed);

/// The normals at a hit turned toward the side the ray arrived from.
struct FacingNormals {
    bool front = true;  ///< the ray hit the side the triangle's winding faces
    glm::vec3 geometric{0.0f};
    glm::vec3 shading{0.0f};  ///< never bent past the face: falls back to `geometric`
};
[[nodiscard]] FacingNormals facing_normals(const RayHit& hit, const glm::vec3& direction);

/// One specular interaction, shared by global and caustic photons: a mirror reflects with
/// Schlick's conductor Fresnel on `power`; a dielectric reflects when `xi` falls below the
/// Fresnel reflectance (or on total internal reflection) and refracts otherwise, tinting the
/// transmitted power, so the expected power splits R : 1 - R. Arriving at a dielectric's back
/// face, the segment just travelled lay inside it: its absorption is applied first (a closed
/// solid's inside; a diffuse surface inside a medium, a pool's floor, is not). Updates origin
/// (offset off the surface on the right side), direction and power. Returns whether the ray
/// passed through the surface (refracted) rather than reflecting off it.
bool scatter_specular(const TraceMaterial& material, const RayHit& hit,
                      const FacingNormals& normals, double xi, glm::vec3& origin,
                      glm::vec3& direction, glm::vec3& power);

/// What radiance carried along a ray is multiplied by where the ray refracts through a closed
/// dielectric's surface, arriving on its front (`front`: from air into the medium) or its back:
/// (eta_from / eta_to)^2, since L / eta^2 is what a ray keeps across an interface. Photons carry
/// power, which refraction keeps, so they never apply it; an estimator that follows a ray
/// backwards through glass reads radiance and must (docs/METHOD.md §6.4): through a solid the
/// two factors cancel, but a ray that starts inside it (from a floor under a glass block resting
/// on it) or ends on a diffuse surface inside it does not pass both. 1 for anything else: an
/// open sheet is drawn and measured as a thin pane (docs/UNITS.md, "Glass"), whose second
/// surface the model leaves out, and the factor of its one interface would not cancel.
[[nodiscard]] float refracted_radiance_scale(const TraceMaterial& material, bool front);

/// Whether a path is inside a closed dielectric, and what that solid's volume absorbs
/// (KHR_materials_volume). scatter_specular absorbs a segment where it leaves through a solid's
/// back face; a segment that ends on a diffuse surface inside the solid (a floor under a glass
/// block resting on it, and the floor's light going back into the block) never meets that face,
/// and every tracer (photons, caustic photons, the gather, the reference's paths and photons)
/// absorbs it here, so that all of them agree. Open sheets are left as they were: one
/// interface, with no inside to be in.
class ClosedMedium {
  public:
    /// Where the path is after scatter_specular at `material`, arriving on its front or back,
    /// refracted or reflected.
    void update(const TraceMaterial& material, bool front, bool refracted);
    /// Multiplies `power` by the absorption over `distance` metres in the solid the path is
    /// inside (nothing when it is not in one, or the solid is clear).
    void absorb(float distance, glm::vec3& power) const;
    [[nodiscard]] bool inside() const { return inside_; }

  private:
    bool inside_ = false;
    glm::vec3 attenuation_color_{1.0f};
    float attenuation_distance_ = std::numeric_limits<float>::infinity();
};

struct TraceLimits {
    /// A path stops after this many interactions whatever Russian roulette says (a guard for
    /// albedo 1; counted as truncated).
    std::uint32_t max_interactions = 65536;
};

struct TraceCounters {
    std::uint64_t photons = 0;
    std::uint64_t segments = 0;  ///< rays shot
    std::uint64_t diffuse_hits = 0;
    std::uint64_t absorbed_back_faces = 0;
    std::uint64_t truncated = 0;

    TraceCounters& operator+=(const TraceCounters& other);
};

/// Traces one photon from emission and appends its diffuse hits to `hops` (position, power on
/// arrival, surface, object, diffuse bounces so far). Specular interactions are followed and
/// recorded as unstored hops (surface -1) so that path comparison sees them. A diffuse
/// back face absorbs the photon (one-sided surfaces have no light map behind them).
void trace_photon(const RayScene& scene, std::span<const TraceMaterial> materials,
                  const EmittedPhoton& photon, std::uint64_t index, std::uint32_t seed,
                  const TraceLimits& limits, std::vector<TracedHop>& hops, TraceCounters& counters);

}  // namespace luxel::lighting
