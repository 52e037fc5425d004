#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/ecs/entity.hpp"
#include "luxel/lighting/core/surface_footprint.hpp"
#include "luxel/lighting/core/surface_texels.hpp"

// What the maps know of one light-mapped surface, split by owner: the registry's part
// (MapSurface), the gather passes' (GatherPassState) and the refinement's (RefinementStats).
namespace luxel::lighting {

/// What an IIM texel holds (as the source does): irradiance for textured surfaces, whose
/// albedo varies within a texel and is applied per pixel; radiance pre-multiplied by the
/// albedo (albedo * E / pi) for uniform ones, saving the renderer a lookup.
enum class IimContent { Irradiance, Radiance };

/// A piece of work the scheduler can order: a surface and its priority (delta / area, W/m^2).
struct MapRequest {
    std::uint32_t surface = 0;
    double priority = 0.0;
};

/// One light-mapped surface as the map registry keeps it: entity, texels, material, transform.
/// Entries without texels belong to surfaces that have no light map.
struct MapSurface {
    ecs::Entity entity;
    SurfaceTexels texels;  ///< object space
    SurfaceFootprint footprint;
    glm::vec3 albedo{0.5f};
    /// The material's emitted radiance (before AreaLight's scale and switch; 0 when not
    /// emissive). RadianceAtlas::surface_emission holds what the surface emits now.
    glm::vec3 material_emission{0.0f};
    IimContent content = IimContent::Radiance;
    glm::mat4 to_world{1.0f};
    /// World metres per page texel (the object-space scale times the transform's).
    double world_metres_per_texel = 0.0;
};

/// A surface's gather passes (docs/METHOD.md §6.5): the one in progress, and what the last one
/// to start saw.
struct GatherPassState {
    bool in_progress = false;
    /// The next texel of the pass in progress; the surface's texel count when none is.
    std::size_t cursor = 0;
    /// The pass in progress's irradiance per texel; it is filtered and committed (faded in)
    /// when the pass completes, so a surface never shows half a pass.
    std::vector<glm::vec3> irradiance;
    /// The pass in progress refines (averages into) the IIM instead of replacing it.
    bool refines = false;
    /// The pass in progress re-gathers only the texels near a geometry change (docs/METHOD.md
    /// §6.8), replacing their values and keeping every other texel's refinement.
    bool local = false;
    /// The texels (indices into the surface's texels) the pass in progress gathers; empty: all.
    std::vector<std::uint32_t> subset;
    /// Per texel, whether geometry changed near it since the pass that last covered it (a
    /// crate moved off the floor: the floor under it now sees the room). Cleared by the pass
    /// that gathers it again.
    std::vector<std::uint8_t> changed_texels;
    std::size_t changed_count = 0;
    /// The local pass in progress read an AIM that was out of date (read_stale_aim's case for a
    /// local pass, which keeps the surface's own flag as it is).
    bool local_read_stale_aim = false;
    /// Texels of completed local passes that read a stale AIM: changed again once every AIM is
    /// current, so a crate's footprint is not left at the light of the AIM before the move.
    std::vector<std::uint32_t> stale_local_texels;
    /// Passes averaged once the pass in progress is in (set when its gathering completes).
    std::uint32_t passes_when_done = 0;
    /// Passes started on this surface (each gathers with new samples).
    std::uint32_t started = 0;
    /// MapRegistry::emission_version() when the last pass started.
    std::uint64_t emission_version = 0;
    /// AimRebuilder::rebuilds() when the last pass started.
    std::uint64_t aim_rebuilds_at_start = 0;
    /// The last pass read an AIM that was out of date (a rebuild was pending when it started,
    /// or completed while it ran): it gathers again once every AIM is current. Without this a
    /// pass that starts between a retrace and the AIM rebuild it causes consumes delta_i and
    /// leaves the IIM on the old AIM for good.
    bool read_stale_aim = false;
    /// A pass has completed on this surface.
    bool completed_once = false;
};

/// The refinement of a surface's IIM (docs/METHOD.md §6.6): passes averaged since its lighting
/// last changed, their mean irradiance per texel before filtering, and the sum of squared
/// deviations from it (Welford), kept only while refining is possible.
struct RefinementStats {
    /// The fewest passes any texel has averaged (a local pass restarts its texels at 1).
    std::uint32_t passes_averaged = 0;
    std::vector<glm::vec3> mean;
    std::vector<glm::vec3> m2;
    /// Per texel, the passes averaged in its mean.
    std::vector<std::uint32_t> texel_passes;
    /// Per texel, the relative variance of one pass's value (summed over the channels, over the
    /// squared mean's) as last measured with three passes or more; < 0: never measured. Kept
    /// when the texel's passes restart: a gather's noise relative to its value is a property
    /// of the texel's surroundings, which a change elsewhere barely moves, so the filter can
    /// still tell a real feature (the focus under a glass sphere) from noise right after a
    /// restart instead of blurring it for the three passes it takes to measure again.
    std::vector<float> relative_pass_variance;
};

/// Counters since construction.
struct MapCounters {
    std::uint64_t aim_rebuilds = 0;
    std::uint64_t aim_texels = 0;
    std::uint64_t gather_passes = 0;
    std::uint64_t texels_gathered = 0;
    std::uint64_t enclosed_texels = 0;  ///< AIM texels found enclosed (set to 0)
    /// Enclosed texels found under an object's edge, gathered at the open point beside it
    /// (docs/METHOD.md §6.12), counted at each rebuild that found them.
    std::uint64_t edge_texels = 0;
    /// Texels that a full pass found unchanged and folded into their mean (their refinement
    /// kept: IlluminationSettings::change_test_sigmas).
    std::uint64_t texels_kept = 0;
    /// Seam stitches done (one per committed pass of a surface on a seam), and the IIM texels
    /// the stitcher's systems hold.
    std::uint64_t seam_stitches = 0;
    std::uint64_t seam_texels = 0;
};

}  // namespace luxel::lighting
