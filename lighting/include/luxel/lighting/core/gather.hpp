#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

/// Final gathering (docs/METHOD.md §6): irradiance at a light-map texel centre from
/// the AIM-lit scene, E = integral over the hemisphere of L(w) cos(theta) dw. One contract, two
/// backends: Embree rays on the CPU (CpuGatherer) and the hemi-plane on the GPU
/// (lighting/gpu HemiPlaneGatherer).
namespace luxel::lighting {

struct TraceMaterial;  // photon_tracer.hpp

/// A texel centre to gather at, in world space.
struct GatherTexel {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f, 1.0f, 0.0f};  ///< unit, the side light is gathered from
    /// Which pass over this texel this is: a sampling gatherer takes new samples for each, so
    /// that passes averaged together (IlluminationSettings::refine_passes) lower the noise.
    std::uint32_t pass = 0;
};

class IrradianceGatherer {
  public:
    virtual ~IrradianceGatherer() = default;
    [[nodiscard]] virtual std::string_view name() const = 0;
    /// Irradiance (W/m^2 per channel) at each texel, from the radiance the atlas holds for
    /// the surfaces the hemisphere sees (what they emit and reflect; not the texel's own
    /// direct light from punctual lights). `irradiance` has one entry per texel. Never NaN or
    /// negative.
    virtual void gather(std::span<const GatherTexel> texels, std::span<glm::vec3> irradiance) = 0;
    /// Whether passes with a different GatherTexel::pass give independent estimates, so that
    /// averaging them converges (a sampling gatherer: yes; a deterministic one: no, and the
    /// maps then do not refine).
    [[nodiscard]] virtual bool refines() const { return false; }
    /// The material table RayHit::material indexes (the photon world's), so that the gather
    /// follows mirrors and glass to the diffuse surfaces they show, as photons do; without
    /// (null), a specular surface reads as its AIM (none: black). Read at every gather call;
    /// LightingSystem sets it on whichever backend it is given.
    virtual void set_materials(const std::vector<TraceMaterial>* materials) { (void)materials; }
};

/// The fraction of the cosine-weighted hemisphere a hemi-plane of half-width `a` at unit
/// distance covers: F(a) = (4/pi) (a / sqrt(1 + a^2)) atan(a / sqrt(1 + a^2)).
/// F(1) = 0.554, F(2) = 0.831; F(a) -> 1 as a grows.
[[nodiscard]] double hemi_plane_coverage(double half_width);

}  // namespace luxel::lighting
