#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/lighting/core/probe_grid.hpp"
#include "luxel/lighting/core/spherical_harmonics.hpp"

namespace luxel {
class JobSystem;
}

namespace luxel::lighting {

/// How a probe stores its irradiance over the sphere of normals.
enum class ProbeBasis : std::uint8_t {
    /// An octahedral map of irradiance (kProbeIrradianceSize texels square), each texel the
    /// cosine-weighted sum of the pass's rays about its direction, filtered bilinearly: as
    /// DDGI stores it. Follows a room's contrast (a bright lamp-lit wall behind, an open side
    /// in front) to a few per cent where band-2 harmonics are off by tens of per cent on the
    /// dim side (docs/RESULTS.md, "irradiance probes").
    Octahedral,
    /// Band-2 spherical harmonics (nine coefficients per channel, Ramamoorthi & Hanrahan):
    /// twelve times smaller, smooth, but their truncation ringing misses dim directions next
    /// to bright ones.
    Sh2,
};

struct IrradianceProbeSettings {
    /// The finest spacing (metres); a level that would need more than max_probes gets a
    /// coarser grid (fit_probe_grid).
    float spacing = 0.5f;
    std::uint32_t max_probes = 4096;
    /// Rays per probe and pass (uniform on the sphere, a new rotation each pass).
    std::uint32_t rays_per_probe = 256;
    /// Passes averaged while the lighting holds still: the SH noise falls as 1/sqrt(passes).
    std::uint32_t refine_passes = 4;
    ProbeBasis basis = ProbeBasis::Octahedral;
};

/// The interior of one probe's distance square (texels per side, octahedral map) and the tile
/// it is stored in, with a one-texel border that repeats the square's octahedral neighbours so
/// that bilinear filtering across the fold is seamless (the GPU's and irradiance()'s alike).
inline constexpr int kProbeDepthSize = 8;
inline constexpr int kProbeDepthTile = kProbeDepthSize + 2;
inline constexpr std::size_t kProbeDepthTexels =
    static_cast<std::size_t>(kProbeDepthTile) * kProbeDepthTile;
/// The same for the irradiance map (ProbeBasis::Octahedral): 16 texels square. The bilinear
/// filter's own error grows with the texel (a bright patch's edge is curved): 12 texels gave
/// 5.7% rms over the normals of a lit wall where 16 give 2.6%, as band-2 harmonics do there
/// (tests/maps, TheOctahedralMapHoldsTheDimSideThatHarmonicsMiss).
inline constexpr int kProbeIrradianceSize = 16;
inline constexpr int kProbeIrradianceTile = kProbeIrradianceSize + 2;
inline constexpr std::size_t kProbeIrradianceTexels =
    static_cast<std::size_t>(kProbeIrradianceTile) * kProbeIrradianceTile;

/// What one probe shows the renderer.
struct ProbeState {
    /// ProbeBasis::Sh2: irradiance coefficients (the cosine convolution folded in),
    /// E(n) = evaluate(irradiance, n).
    ShRgb irradiance;
    /// ProbeBasis::Octahedral: irradiance (W/m^2) per octahedral texel, rows of
    /// kProbeIrradianceTile with the same border as `depth`; empty for the other basis.
    std::vector<glm::vec3> irradiance_map;
    /// Where the probe was moved from its grid position to leave the geometry it sat in.
    glm::vec3 offset{0.0f};
    /// false: inside geometry (or not gathered yet); it takes no part in interpolation.
    bool active = false;
    /// Per octahedral texel, the mean distance to the first hit and its mean square (metres,
    /// m^2), rows of kProbeDepthTile: Chebyshev's inequality on them says how likely a point
    /// at a given distance is to be seen from the probe (the visibility test that stops light
    /// leaking through walls).
    std::array<glm::vec2, kProbeDepthTexels> depth{};
};

/// One probe ray's result, from the tracer.
struct ProbeRay {
    glm::vec3 radiance{0.0f};
    float distance = 0.0f;   ///< to the first hit; the tracer's max distance if nothing
    bool hit = false;        ///< met the light-mapped scene (false: left the level)
    bool back_face = false;  ///< hit the back of a surface: the probe may be inside geometry
};

/// Traces rays that share an origin (CpuGatherer::trace_probe_rays): the radiance each brings
/// back from the AIM-lit scene, and where it first hits.
using ProbeRayTracer =
    std::function<void(const glm::vec3& origin, std::span<const glm::vec3> directions,
                       std::span<ProbeRay> rays, std::uint32_t seed)>;

/// The irradiance probes: indirect light for receivers that have no light map (a skinned
/// character, a prop, a level not prepared), the way engines ship it. A grid of probes, each
/// gathered on the CPU from the same AIM-lit scene the IIM gathers from, stored as band-2
/// spherical harmonics of irradiance and interpolated per pixel by irradiance(), weighted by
/// trilinear position, by which side of the receiver the probe lies on, and by Chebyshev
/// visibility from each probe's distance moments (as in Majercik et al., "Dynamic Diffuse
/// Global Illumination with Ray-Traced Irradiance Fields", JCGT 2019), so that a wall between
/// a probe and a receiver keeps the probe's light out.
///
/// The probes see the light-mapped scene only: a ray passes through geometry that has no
/// light map and emits nothing (a character, a prop, a moving crate), so a receiver lit by the
/// probes does not darken its own light, and a moving object does not make its probes gather
/// again. Which probes gather next: those never gathered or whose lighting changed (stale:
/// each keeps showing its old light until its new pass replaces it), then refinement passes;
/// within a class in grid order, from a cursor that moves on.
class IrradianceProbes {
  public:
    IrradianceProbes(ProbeGrid grid, IrradianceProbeSettings settings);

    [[nodiscard]] const ProbeGrid& grid() const { return grid_; }
    [[nodiscard]] const IrradianceProbeSettings& settings() const { return settings_; }
    [[nodiscard]] std::span<const ProbeState> probes() const { return states_; }
    /// Bumped whenever a probe's state changes: a GPU copy uploads again when it moved.
    [[nodiscard]] std::uint64_t version() const { return version_; }

    /// The light-mapped scene changed (an AIM rebuilt, an emitter switched, static geometry
    /// edited): every probe gathers a fresh pass (distances and light), keeping what it shows
    /// until that pass replaces it.
    void lighting_changed();
    /// Probes that want a pass (reset, stale or still refining).
    [[nodiscard]] std::size_t pending() const;
    /// Share of the refinement passes gathered, in [0, 1] (for a loading screen).
    [[nodiscard]] double refined_share() const;

    /// Gathers one pass of up to `count` probes, the most wanted first (in parallel with
    /// `jobs`); returns how many it gathered.
    std::size_t gather(std::size_t count, const ProbeRayTracer& tracer, JobSystem* jobs);

    /// Irradiance (W/m^2) at `point` on a surface facing `normal`, interpolated from the
    /// probes around it (outside the grid, those of the nearest cell); 0 where no probe
    /// around it is active. What
    /// shaders/render/irradiance_probes.glsl computes per pixel.
    /// `viewer` is where the point is seen from (the camera): the visibility test looks from
    /// the point moved towards it and off the surface, which stays on the viewer's side of a
    /// wall even for a surface that faces the wall from a few centimetres away. Without one
    /// (nullopt) it moves along the normal only.
    [[nodiscard]] glm::vec3 irradiance(const glm::vec3& point, const glm::vec3& normal,
                                       std::optional<glm::vec3> viewer = std::nullopt) const;

    /// Mean distance and mean square towards `direction` from probe `index`, bilinear in its
    /// tile (as the GPU's sampler filters it).
    [[nodiscard]] glm::vec2 depth_towards(std::size_t index, const glm::vec3& direction) const;
    /// Probe `index`'s own irradiance for a surface facing unit `normal`, from its basis
    /// (the octahedral map bilinear in its tile, as the GPU filters it).
    [[nodiscard]] glm::vec3 probe_irradiance(std::size_t index, const glm::vec3& normal) const;

  private:
    /// Running sums of one probe's passes.
    struct Accumulator {
        ShRgb radiance_sum;  ///< Sh2: sum over passes of each pass's projection
        /// Octahedral: per interior texel, the sum over passes of each pass's irradiance.
        std::vector<glm::vec3> irradiance_sum;
        std::array<glm::vec3, static_cast<std::size_t>(kProbeDepthSize) * kProbeDepthSize>
            depth_sum{};  ///< per interior texel: sum of weights, of w * d, of w * d^2
        std::uint32_t passes = 0;
    };
    enum class Want : std::uint8_t { None, Refine, Stale };

    void gather_probe(std::size_t index, const ProbeRayTracer& tracer);
    /// Publishes probe `index`'s accumulator into its state (SH convolved, depth tile with
    /// its border).
    void publish(std::size_t index);

    ProbeGrid grid_;
    IrradianceProbeSettings settings_;
    std::vector<ProbeState> states_;
    std::vector<Accumulator> sums_;
    std::vector<Want> wants_;
    std::vector<std::uint32_t> pass_index_;  ///< passes ever gathered: the ray rotation
    std::size_t cursor_ = 0;
    std::uint64_t version_ = 0;
};

}  // namespace luxel::lighting
