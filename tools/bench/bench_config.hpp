#pragma once

// The configurations luxel-bench runs: the paper's, and one-knob variations of it.

#include <cstdint>
#include <string>
#include <vector>

#include "bench_options.hpp"
#include "luxel/lighting/core/lighting_system.hpp"
#include "luxel/lighting/gpu/caustic_pass.hpp"

namespace luxel::bench {

/// One real-time configuration at one budget. `method` names the curve it belongs to (all its
/// budgets), e.g. "paper" or "rays=16".
struct BenchConfig {
    std::string method = "paper";
    double budget_ms = 4.0;
    std::uint32_t groups = 77;  ///< the paper: 77 groups x 40 photons
    std::uint32_t per_group = 40;
    std::uint32_t aim_n = 50;            ///< N nearest photons of the AIM estimate
    std::uint32_t rays = 64;             ///< gather rays per texel (CPU backend)
    std::uint32_t texels_per_unit = 20;  ///< the paper gathers 20 texels per frame
    std::uint32_t filter = 2;            ///< IIM filter radius in texels (luxel's default)
    std::uint32_t local = 1;    ///< local gather passes after a geometry change (1: on, default)
    std::uint32_t refine = 16;  ///< gather passes averaged while lighting is unchanged (default)
    /// Exact invalidation of photon groups whose paths cross moved geometry (1: on, default).
    std::uint32_t exact = 1;
    /// Texels under an object's edge gathered beside it (IlluminationSettings::contact_texels;
    /// 1: on, default).
    std::uint32_t contact = 1;
    /// Gather rays read a surface without a light map as its direct light and the probes'
    /// (CpuGatherSettings::unmapped_radiance; 1: on, default; 0: black, as before).
    std::uint32_t unmapped = 1;
    /// The IIM's light-map seams stitched after each pass (IlluminationSettings::stitch_seams;
    /// 1: on, default).
    std::uint32_t stitch = 1;
    /// A full AIM rebuild keeps its photons' power (IlluminationSettings::aim_keeps_power; 1:
    /// on, default).
    std::uint32_t aim_power = 1;
    /// Local passes ordered by what a change most likely made wrong
    /// (IlluminationSettings::order_local_passes; 1: on, default).
    std::uint32_t local_order = 1;
    /// Irradiance probes for receivers without a light map (1: on, default; 0: none placed,
    /// IrradianceProbeSettings::max_probes = 0).
    std::uint32_t probes = 1;
    /// The irradiance probes' spacing in metres (IrradianceProbeSettings::spacing).
    double probe_spacing = lighting::IrradianceProbeSettings{}.spacing;
    /// How each probe stores its irradiance (IrradianceProbeSettings::basis): "oct" (the
    /// octahedral map, default) or "sh2" (band-2 spherical harmonics).
    std::string probe_basis = "oct";
    /// Seconds a local pass's texels fade in over (IlluminationSettings::change_blend_seconds).
    double change_blend = lighting::IlluminationSettings{}.change_blend_seconds;
    /// Standard deviations by which a full pass must show a texel's light changed before the
    /// texel restarts (IlluminationSettings::change_test_sigmas; 0: every texel restarts).
    double keep = lighting::IlluminationSettings{}.change_test_sigmas;
    std::uint32_t caustic_photons = 10'000;  ///< per (generator, light) pair; the paper's
    std::uint32_t caustic_slices = 8;        ///< ... over 8 frames
    /// Photons all progressive caustic generations may hold together
    /// (CausticSettings::refinement_photons; 0: none, the paper's caustics).
    std::uint32_t caustic_refine = lighting::CausticSettings{}.refinement_photons;
    /// Fresh caustic slices stand in for stale ones after a change (CausticSettings::stand_in).
    std::uint32_t stand_in = 1;
    /// The caustic share while a caustic catches up (LightingConfig::caustic_catch_up_share).
    double catch_up = lighting::LightingConfig{}.caustic_catch_up_share;
    /// The final-gather backend: "cpu" (Embree rays, `rays` per texel) or the hemi-plane
    /// (HemiPlaneGatherer, in the bench's GL context; `rays` does not apply): "gpu" as luxel
    /// runs it (turned each pass, the band it misses and the light behind mirrors and glass
    /// traced by CPU rays), "gpu-turn" (turned, no CPU rays), "gpu-plane" (the paper's plane
    /// alone).
    std::string backend = "cpu";
    /// The camera's caustic kernel of the frame (CausticPass): larsen, box, cone (the round
    /// cone), world (the world-space cone), mip (level-adjusted mip-maps), footprints (the
    /// photon footprints), layer (the caustic layer on light-mapped pixels, Larsen's elsewhere)
    /// or layer-<kernel>. Changes only the image and its caustic pass time.
    std::string kernel = "larsen";
    /// kernel=footprints: CausticPassSettings::footprint_scale and footprint_min_pixels. A sweep
    /// of either runs the footprints kernel with it (the knobs mean nothing with another).
    /// Change only the image.
    double footprint_scale = lighting::CausticPassSettings{}.footprint_scale;
    double footprint_min = lighting::CausticPassSettings{}.footprint_min_pixels;
    /// The frame's anti-aliasing of geometric edges (FrameSettings::anti_aliasing): "on" or
    /// "off". Changes only the image and its anti-aliasing pass time.
    std::string aa = "on";
    /// How the frame reads light maps (FrameSettings::bicubic_light_maps): "bilinear" or
    /// "bicubic". Changes only the image.
    std::string lightmap = "bilinear";
    /// Sky coverage at silhouettes (FrameSettings::sky_edge_coverage): "on" or "off". Changes
    /// only the image of a level with a sky.
    std::string sky_edges = "on";

    [[nodiscard]] lighting::LightingConfig lighting() const;
    /// "groups=77 per_group=40 ..." for logs and the Markdown table.
    [[nodiscard]] std::string knobs() const;
};

/// The paper's configuration at every budget, then each sweep's values (one knob changed from
/// the paper's) at every budget; `budget` sweeps add budgets instead. Values equal to the
/// paper's are not repeated.
[[nodiscard]] std::vector<BenchConfig> make_configs(const Options& options);

}  // namespace luxel::bench
