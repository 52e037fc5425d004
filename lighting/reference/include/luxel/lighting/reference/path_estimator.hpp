#pragma once

#include <array>
#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "luxel/lighting/reference/reference_scene.hpp"
#include "luxel/lighting/reference/sample_stream.hpp"
#include "luxel/lighting/reference/sphere_light.hpp"

/// Path tracing with next-event estimation for the reference (docs/METHOD.md §10.1): irradiance
/// at a light-map texel split by how the light got there, and radiance along a camera ray.
namespace luxel::lighting::reference {

/// How light reached a texel: straight from a light (direct), through one or more specular
/// interactions only (caustic), or through at least one diffuse interaction (indirect).
enum class Component : std::uint8_t { Direct = 0, Indirect = 1, Caustic = 2 };
inline constexpr std::size_t kComponentCount = 3;
[[nodiscard]] const char* component_name(Component component);

/// One estimate per component, W/m^2 per channel (irradiance) or W/(m^2 sr) (radiance).
struct Components {
    std::array<glm::dvec3, kComponentCount> value{};

    [[nodiscard]] glm::dvec3& operator[](Component c) { return value[static_cast<std::size_t>(c)]; }
    [[nodiscard]] const glm::dvec3& operator[](Component c) const {
        return value[static_cast<std::size_t>(c)];
    }
    [[nodiscard]] glm::dvec3 total() const { return value[0] + value[1] + value[2]; }
};

struct PathSettings {
    /// Scattering events (diffuse and specular) one path may have. Russian roulette ends paths
    /// long before for albedo < 1 (expected length 1 / (1 - albedo)); the cap bounds the time of
    /// a path for any albedo and drops at most albedo^cap of the light: 4.5e-5 of it at albedo
    /// 0.999 with the default.
    std::uint32_t max_vertices = 10'000;
    /// Whether a diffuse vertex on a light-mapped surface adds the caustic photon estimate of
    /// its texel (delta-light caustics reflected onward, see PathEstimator).
    bool caustic_bounce = true;
    /// Whether paths go on past their first diffuse vertex. Off, a texel sample holds only
    /// the direct component and area-light caustics: ReferenceIntegrator turns it off when
    /// IndirectPhotons estimate the indirect component.
    bool indirect = true;
    /// Whether the direct light of area lights and skies at a texel counts as indirect. luxel's
    /// IIM holds it (the gathers see emitters and the sky, docs/METHOD.md §6.7, §6.11) while
    /// the renderer draws only delta lights' direct light per pixel: on, the indirect
    /// component is what the IIM should hold, and the direct component what the renderer
    /// adds. luxel-bench compares the light maps so.
    bool gathered_as_indirect = false;
};

/// Counters of the estimator (summed by the caller; the estimator itself is const).
struct PathCounters {
    std::uint64_t rays = 0;
    std::uint64_t truncated = 0;   ///< paths that reached max_vertices
    std::uint64_t non_finite = 0;  ///< contributions dropped for NaN or infinity
};

/// The estimator. Diffuse surfaces are one-sided Lambertian reflectors of their material's
/// albedo (a back face absorbs, as in the photon tracer) and are shaded with their geometric
/// normal, which keeps closed enclosures exactly energy-conserving (the furnace). Specular
/// surfaces scatter as the photon tracer does (scatter_specular). Emitting triangles of area
/// lights emit their radiance from the front.
///
/// At each diffuse vertex: next-event estimation to every light (one shadow ray per delta
/// light; one light sample per area light, combined with the BSDF sample by the power
/// heuristic), then Russian roulette with survival max(albedo), then a cosine-distributed
/// continuation. Light from point, spot and directional lights through specular chains cannot
/// be found from the surface side; at a diffuse vertex on a light-mapped surface the estimator
/// adds the caustic photon estimate of that texel (`caustic_irradiance`, per global texel; may
/// be empty), so such light reflected onward is still counted.
class PathEstimator {
  public:
    PathEstimator(const ReferenceScene& scene, PathSettings settings,
                  std::span<const glm::dvec3> caustic_irradiance = {});

    /// One sample of the irradiance at a texel over the hemisphere of its normal. The caustic
    /// component here holds only area-light caustics (paths can reach area lights through
    /// specular chains); point, spot and directional caustics come from CausticReference.
    [[nodiscard]] Components irradiance(const ReferenceTexel& texel, SampleStream& random,
                                        PathCounters& counters) const;
    /// One sample of the radiance arriving at `origin` from `-direction` (a camera ray).
    [[nodiscard]] glm::dvec3 radiance(const glm::vec3& origin, const glm::vec3& direction,
                                      SampleStream& random, PathCounters& counters) const;

  private:
    /// The radiance of every sky from `direction` for a ray from `origin` that left the scene,
    /// each weighed against its next-event estimates (the sky's and its portals') when the ray
    /// was cosine-sampled with density `pdf` (0: not sampled so, weight 1).
    [[nodiscard]] glm::dvec3 escaped(const glm::vec3& origin, const glm::vec3& direction,
                                     double pdf) const;
    /// A sky's next-event estimate at a diffuse vertex: a direction by the sky's distribution
    /// and, when the level has portals, one towards a point on them, each weighed against the
    /// other and the cosine-sampled continuation (power heuristic).
    [[nodiscard]] glm::dvec3 sky_light(const ReferenceLight& light, const glm::vec3& origin,
                                       const glm::vec3& normal, const glm::vec3& geometric,
                                       SampleStream& random, PathCounters& counters) const;
    /// A point or spot light with a radius: its irradiance at `origin` by the one direction
    /// `sphere` drew over the cone it subtends (0 when blocked or below the horizon).
    [[nodiscard]] glm::dvec3 sphere_light(const ReferenceLight& light, const SphereSample& sphere,
                                          const glm::vec3& origin, const glm::vec3& normal,
                                          const glm::vec3& geometric, PathCounters& counters) const;
    /// Irradiance at a point from every light by next-event estimation, MIS-weighted against
    /// cosine sampling around `normal` for area lights and skies. `geometric` rejects
    /// directions into the surface.
    struct DirectLight {
        glm::dvec3 delta{0.0};     ///< point, spot and directional lights
        glm::dvec3 gathered{0.0};  ///< area lights and skies (what luxel's gathers see)
    };
    [[nodiscard]] DirectLight direct_light(const glm::vec3& point, const glm::vec3& normal,
                                           const glm::vec3& geometric, SampleStream& random,
                                           PathCounters& counters) const;
    /// Where light that reached a texel straight from an area light or the sky is counted.
    [[nodiscard]] Component gathered_direct() const {
        return settings_.gathered_as_indirect ? Component::Indirect : Component::Direct;
    }
    /// Follows a path from `origin` along `direction` with throughput `beta`, adding what it
    /// finds to `out`. `pdf`: solid-angle density of `direction` if a diffuse vertex sampled it
    /// (for MIS), 0 if it is a camera or specular direction. `from_texel`: the first segment
    /// leaves a texel (its emission hit is direct light).
    void trace(glm::vec3 origin, glm::vec3 direction, glm::dvec3 beta, double pdf, bool from_texel,
               SampleStream& random, Components& out, PathCounters& counters) const;

    const ReferenceScene* scene_;
    PathSettings settings_;
    std::span<const glm::dvec3> caustics_;
};

}  // namespace luxel::lighting::reference
