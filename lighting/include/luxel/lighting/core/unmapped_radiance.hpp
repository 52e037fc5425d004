#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/lighting/core/light_source.hpp"

namespace luxel::lighting {

class IrradianceProbes;
class RayScene;

/// What a diffuse surface without a light map (a prop, a figure, a mesh left unprepared) sends
/// back to a gather ray: albedo / pi times its direct light from the point, spot and
/// directional lights (one shadow ray each) and the irradiance probes' light there (the rest:
/// what the room sends it, skies and area lights included). The AIM has no texels there, so a
/// gather read such a surface as black and the light maps beside it missed the light it
/// returns: cornell's indirect error 5.11% -> 7.86% with its cube unmapped (docs/RESULTS.md).
/// The probes see through unmapped surfaces (IrradianceProbes), so they do not depend on this.
class UnmappedRadiance {
  public:
    /// The scene the shadow rays are traced in, the lights (kept: only the punctual ones) and
    /// the probes (null: none yet). Read at each exitant() call; set between gathers.
    void set(const RayScene* scene, std::span<const LightSource* const> lights,
             const IrradianceProbes* probes);
    void clear() { *this = UnmappedRadiance{}; }

    /// The radiance leaving `position` (on a surface whose front, unit `normal`, faces the
    /// gather ray) for a diffuse `albedo`. `u` in [0, 1)^2: x picks the light whose shadow ray
    /// is traced, y whether the probes are read (kProbeShare of the calls, weighed up): an
    /// unbiased estimate, which the gathers average over many hits. Never NaN or negative.
    [[nodiscard]] glm::vec3 exitant(const glm::vec3& position, const glm::vec3& normal,
                                    const glm::vec3& albedo, const glm::dvec2& u) const;

    /// The share of exitant() calls that read the probes.
    static constexpr double kProbeShare = 0.25;

    /// The lights past this many (in the order given) are left out of the direct light.
    static constexpr std::size_t kMaxLights = 64;

  private:
    [[nodiscard]] glm::vec3 direct(const glm::vec3& position, const glm::vec3& normal,
                                   double u) const;
    /// What `light` delivers at `origin` unshadowed, and the shadow ray's vector to it.
    [[nodiscard]] glm::vec3 unshadowed(const LightSource& light, const glm::vec3& origin,
                                       const glm::vec3& normal, glm::vec3& to_light) const;

    const RayScene* scene_ = nullptr;
    std::vector<LightSource> lights_;
    const IrradianceProbes* probes_ = nullptr;
};

}  // namespace luxel::lighting
