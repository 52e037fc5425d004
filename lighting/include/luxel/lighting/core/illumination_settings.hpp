#pragma once

#include <cstdint>

#include "luxel/lighting/core/photon_density.hpp"

namespace luxel::lighting {

/// How photons become light maps: the AIM's density estimate and rebuild threshold, the IIM's
/// gather threshold, filter, fade-in and refinement.
struct IlluminationSettings {
    /// The density estimate; its max_radius (metres) is replaced per surface by
    /// max_radius_texels, below.
    DensitySettings density;
    /// The capped search radius in light-map texels of the surface (10 texels = 0.5 m at
    /// luxel-prep's default 5 cm): tied to the light map, not to metres, so a level scaled by
    /// 1e-3 or 1e4 gets the same light maps.
    float max_radius_texels = 10.0f;
    /// A surface's AIM is rebuilt when delta_f exceeds this fraction of the energy stored on
    /// it (relative, so the threshold means the same for a 1 mW and a 1 MW light).
    double aim_threshold = 0.05;
    /// A full AIM rebuild scales the surface's estimates so that their integral over the
    /// surface equals the power of the photons it estimates from (docs/METHOD.md §5.6). A
    /// nearest-N estimate reads high on the shoulders of a peak (its disc, sized by the peak's
    /// photons, is lopsided towards it) and low on the peak; the gathers integrate the AIM
    /// over whole surfaces, so what they see is its total power: cornell's ceiling, lit by a
    /// light 10 cm below it, read 2.5% over its photons and every IIM that sees it inherited
    /// it. Off: the paper's estimate, for measuring the difference.
    bool aim_keeps_power = true;
    /// A surface's texels are gathered again when delta_i exceeds this fraction of its stored
    /// energy.
    double iim_threshold = 0.05;
    /// Seconds over which an updated IIM texel fades in (0: at once): a refinement's or a
    /// photon change's small correction blends in without flicker.
    double blend_seconds = 0.5;
    /// Seconds over which the texels of a local pass (below: re-gathered because geometry
    /// moved next to them) fade in. Shorter than blend_seconds because what they showed is
    /// wrong, not noisy: a crate's dark footprint should light up within a few frames
    /// (docs/RESULTS.md measures it), not over half a second.
    double change_blend_seconds = 0.1;
    /// A completed gather pass is filtered over the surface's own texels with a tent of this
    /// radius (texels; 0: none) before it fades in: docs/RESULTS.md measures the trade.
    int iim_filter_radius = 2;
    /// While a surface's lighting stays unchanged, it is gathered again until this many passes
    /// are averaged in its IIM (1: one pass, no refinement). Each pass takes new samples
    /// (GatherTexel::pass), so the gather's noise falls as 1 / sqrt(passes); refinement
    /// requests come after every other request, so they use budget that would otherwise go
    /// idle, and they stop once done. Only gatherers that sample refine (IrradianceGatherer::
    /// refines()); docs/RESULTS.md measures the trade.
    std::uint32_t refine_passes = 16;
    /// AIM texels whose hemisphere is closed within this many texels (every enclosure ray blocked:
    /// the floor under a box resting on it, the box's bottom) get no light: no photon can
    /// reach them, and a density estimate there would borrow the photons around the object
    /// (its radius grows until it finds some) and leak light under it. 0: no enclosure rays.
    double enclosure_ray_texels = 1.5;
    /// Once three or more passes are averaged, the filter weighs each neighbour by how well
    /// the texels' noise explains their difference: exp(-d^2 / (2 k^2 (var_i + var_j))) with
    /// k this many standard deviations of the texels' means (0: the plain tent). Noise is
    /// smoothed; a feature sharper than the tent (the focus under a glass sphere) is kept.
    float iim_filter_noise_sigmas = 2.5f;
    /// Where geometry moves, appears or goes away, the texels within about the object's own
    /// size of where it was and where it is are gathered again at once, in a pass of their own
    /// that keeps every other texel's refinement (docs/METHOD.md §6.8): without it, a crate
    /// sliding off a floor leaves the floor's IIM dark where it stood until the photons' change
    /// there passes iim_threshold, which a small object's may never do. Off: the paper's
    /// behaviour, for measuring the difference.
    bool local_passes = true;
    /// Local passes waiting are ordered (a turned object's own surfaces, then texels close to
    /// the change, then a slid object's own, then the rest) and a surface's close texels gather
    /// in a pass of their own before its farther ones (docs/METHOD.md §6.8). Off: every local
    /// pass waiting ranks alike, one per surface, for measuring the difference.
    bool order_local_passes = true;
    /// Texels whose centre lies under an object resting on the surface but within a texel of
    /// the open surface (an object's edge crossing them) are gathered at the nearest open point
    /// beside the object, and deeper enclosed texels are left out of the IIM filter
    /// (ContactTexels, docs/METHOD.md §6.12): a bilinear lookup beside the object reads these
    /// texels, and gathered at their centres they showed as a black notch along its base. Off:
    /// every texel is gathered at its centre and filtered with all its neighbours, for measuring
    /// the difference.
    bool contact_texels = true;
    /// A full pass keeps the refinement of the texels whose light it shows unchanged: a texel
    /// restarts at one pass only where the pass's mean difference from the texels' means over
    /// the neighbourhood within change_test_radius texels exceeds this many standard deviations
    /// of the noise (texel_change_test.hpp, docs/METHOD.md §6.9). 0: every texel of the
    /// surface restarts (before issue 19).
    double change_test_sigmas = 3.0;
    /// After each pass the IIM texels along light-map seams (two charts of one object meeting
    /// where the surface runs on smoothly) are moved, by least squares, until both sides'
    /// lookups agree (SeamStitcher, docs/METHOD.md §6.13). Off: each side shows its own pass,
    /// a visible step of the two passes' noise, for measuring the difference.
    bool stitch_seams = true;
    int change_test_radius = 4;
};

}  // namespace luxel::lighting
