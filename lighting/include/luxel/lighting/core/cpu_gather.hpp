#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "luxel/lighting/core/gather.hpp"
#include "luxel/lighting/core/irradiance_probes.hpp"
#include "luxel/lighting/core/photon_tracer.hpp"
#include "luxel/lighting/core/radiance_atlas.hpp"
#include "luxel/lighting/core/ray_scene.hpp"
#include "luxel/lighting/core/unmapped_radiance.hpp"

namespace luxel {
class JobSystem;
}

namespace luxel::lighting {

struct CpuGatherSettings {
    std::uint32_t rays_per_texel = 256;
    /// Rays that travel further than this (metres) see nothing: the scene's outside is black.
    float max_distance = 1e6f;
    /// Mirror and glass interactions a ray follows before it gives up (with materials).
    std::uint32_t max_specular = 8;
    /// A ray that meets a diffuse surface without a light map reads its direct light and the
    /// irradiance probes' (UnmappedRadiance, set by the lighting system); false: black, as
    /// before (luxel-bench --sweep unmapped=0).
    bool unmapped_radiance = true;
};

/// The CPU backend: from each texel centre, cosine-weighted Halton directions (bases 2, 3;
/// Cranley-Patterson rotated per texel so neighbouring texels do not share one pattern of
/// bias) traced with Embree; at each hit the AIM radiance is read bilinearly from the hit
/// surface's light map, and E = pi * mean(L) (the cosine-weighted estimator of
/// integral L cos dw). Rays leave from the texel centre moved off the surface along its normal
/// by offset_ray_origin, so they do not hit the surface they start on.
class CpuGatherer final : public IrradianceGatherer {
  public:
    /// Both are read at every gather call (they may change between calls, not during one).
    /// With `jobs`, texels are gathered in parallel.
    CpuGatherer(const RayScene& scene, const RadianceAtlas& atlas, CpuGatherSettings settings = {},
                JobSystem* jobs = nullptr);
    /// With the scene's material table (RayHit::material indexes it), rays follow mirrors and
    /// glass to the diffuse surface they show; without, specular surfaces read as their AIM
    /// (none: black).
    void set_materials(const std::vector<TraceMaterial>* materials) override {
        materials_ = materials;
    }
    /// What a diffuse surface without a light map sends back (null: black). Read at each
    /// gather call; needs the materials for the surface's albedo.
    void set_unmapped(const UnmappedRadiance* unmapped) { unmapped_ = unmapped; }

    [[nodiscard]] std::string_view name() const override { return "cpu"; }
    /// Each pass rotates the ray pattern anew (GatherTexel::pass).
    [[nodiscard]] bool refines() const override { return true; }
    void gather(std::span<const GatherTexel> texels, std::span<glm::vec3> irradiance) override;

    /// Irradiance at one texel (what gather() does per texel).
    [[nodiscard]] glm::vec3 gather_one(const GatherTexel& texel) const;

    /// The radiance gather rays bring back from `origin` along each of `directions`, traced as
    /// gather_one traces its own (the AIM at diffuse hits, mirrors and glass followed with
    /// materials, the sky where a ray leaves; never NaN or negative): for a gatherer that
    /// samples part of the hemisphere itself (HemiPlaneGatherer's horizon band).
    /// With `specular` (one entry per direction), also whether each ray's first hit was a
    /// mirror or glass.
    void trace_gather_rays(const glm::vec3& origin, std::span<const glm::vec3> directions,
                           std::span<glm::vec3> radiance, std::uint32_t seed,
                           std::span<std::uint8_t> specular = {}) const;

    /// The irradiance probes' rays (a ProbeRayTracer): from `origin` along each direction,
    /// the radiance each brings back and where it first meets the light-mapped scene. A ray
    /// passes through diffuse geometry that has no light map and emits nothing: what the
    /// probes light must not hide their light from itself (IrradianceProbes).
    void trace_probe_rays(const glm::vec3& origin, std::span<const glm::vec3> directions,
                          std::span<ProbeRay> rays, std::uint32_t seed) const;

    /// Rays traced since construction (for rays-per-second figures).
    [[nodiscard]] std::uint64_t rays_traced() const { return rays_traced_; }
    [[nodiscard]] const CpuGatherSettings& settings() const { return settings_; }

  private:
    /// The radiance a gather ray brings back, from its first hit (`hit`, already traced) on
    /// through mirrors and glass.
    [[nodiscard]] glm::vec3 trace(glm::vec3 origin, glm::vec3 direction, std::optional<RayHit> hit,
                                  std::uint32_t ray, std::uint32_t seed) const;

    /// Whether a probe ray passes through this hit (diffuse, no light map, no emission).
    /// Whether the hit surface has AIM texels (a page in the atlas).
    [[nodiscard]] bool has_light_map(const RayHit& hit) const;
    /// Whether the hit surface emits (RadianceAtlas::surface_emission).
    [[nodiscard]] bool emits(const RayHit& hit) const;
    [[nodiscard]] bool see_through(const RayHit& hit) const;

    const RayScene* scene_;
    const std::vector<TraceMaterial>* materials_ = nullptr;
    const RadianceAtlas* atlas_;
    const UnmappedRadiance* unmapped_ = nullptr;
    CpuGatherSettings settings_;
    JobSystem* jobs_;
    std::uint64_t rays_traced_ = 0;
};

}  // namespace luxel::lighting
