#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "luxel/ecs/registry.hpp"
#include "luxel/lighting/components.hpp"
#include "luxel/lighting/core/gather.hpp"
#include "luxel/lighting/core/iim_page.hpp"
#include "luxel/lighting/core/illumination_settings.hpp"
#include "luxel/lighting/core/light_map_seams.hpp"
#include "luxel/lighting/core/map_surface.hpp"
#include "luxel/lighting/core/photon_world.hpp"
#include "luxel/lighting/core/radiance_atlas.hpp"
#include "luxel/lighting/core/surface_deltas.hpp"
#include "luxel/lighting/core/view_hint.hpp"

/// Photons into light maps (docs/METHOD.md §5-6): the AIM of each light-mapped
/// surface from its photons, and the IIM from final gathering over the AIM-lit scene.
namespace luxel::lighting {

class MapRegistry;
class AimRebuilder;
class IimGatherPasses;

/// The maps' public face: three stages, each a class of its own with its own state, over one
/// SurfaceDeltas (delta_f and delta_i) that the maps own:
/// - MapRegistry: surfaces, pages and page-texel owners, transforms, the emission table;
/// - AimRebuilder: which AIMs need a rebuild, the rebuild in slices (writes the AIM pages);
/// - IimGatherPasses: which surfaces gather, passes in slices, refinement, filter and fade-in
///   (writes the IIM pages).
class IlluminationMaps {
  public:
    /// Follows `world`'s surfaces (call sync() after PhotonWorld::sync()).
    IlluminationMaps(ecs::Registry& registry, const PhotonWorld& world,
                     IlluminationSettings settings = {});
    ~IlluminationMaps();
    IlluminationMaps(const IlluminationMaps&) = delete;
    IlluminationMaps& operator=(const IlluminationMaps&) = delete;

    /// Takes in surfaces the photon world added and transforms of entities that moved.
    void sync();

    /// Surfaces whose AIM needs rebuilding, highest delta_f / area first (never-built surfaces
    /// holding photons first of all).
    [[nodiscard]] std::vector<MapRequest> aim_requests() const;
    /// Rebuilds one surface's AIM from the photons on it (one kd-tree at a time, dropped
    /// afterwards), dilates it into the chart padding, and resets the surface's delta_f.
    ///
    /// Each texel's estimate divides by the part of its disc that lies on the surface
    /// (SurfaceFootprint), not by pi r^2. That is why only the surface's own photons count:
    /// photons of a coplanar neighbour across a seam would be counted over an area that
    /// excludes the neighbour. The source gathers from neighbours to soften the darkening at
    /// borders; measuring the area removes it.
    ///
    /// A rebuild may run in slices of `max_texels` texels across frames (the scheduler keeps
    /// units small so they fit a budget): the tree lives until the pass completes, and
    /// aim_requests() lists the pass in progress first. While a pass of another surface is in
    /// progress, the call continues that pass instead. Returns the texels done.
    /// With `jobs`, the slice's texels are estimated in parallel (the same values).
    std::size_t rebuild_aim(std::uint32_t surface,
                            std::size_t max_texels = std::numeric_limits<std::size_t>::max(),
                            JobSystem* jobs = nullptr);
    /// The first of aim_requests(), without listing and sorting them all: what an AIM unit
    /// works on when it runs (nullopt: nothing to rebuild).
    [[nodiscard]] std::optional<std::uint32_t> next_aim_surface() const;

    /// Surfaces whose IIM needs gathering (a pass in progress, or delta_i over the threshold),
    /// highest delta_i / area first. No new pass starts while a surface holding photons has
    /// no AIM yet.
    [[nodiscard]] std::vector<MapRequest> gather_requests() const;
    /// Gathers up to `max_texels` texels of the surface's pass (starting one, and resetting
    /// delta_i, if none is in progress) and returns how many were gathered. When the pass
    /// completes, it is filtered (iim_filter_radius) and committed into the IIM at
    /// `now_seconds`, to fade in over the blend time.
    std::size_t gather(std::uint32_t surface, std::size_t max_texels, IrradianceGatherer& gatherer,
                       double now_seconds);
    /// The first of gather_requests() (the pass furthest along, ...), without listing and
    /// sorting them all: what a gather unit works on when it runs (nullopt: nothing to gather).
    [[nodiscard]] std::optional<std::uint32_t> next_gather_surface() const;

    /// Of the texel passes the surfaces' refinement wants, the share gathered so far, in [0, 1]:
    /// what a loading screen shows as its progress.
    [[nodiscard]] double refined_share() const;
    /// Whether every surface holding photons has had its first AIM (gather passes wait).
    [[nodiscard]] bool aims_ready() const;
    /// Whether no AIM needs rebuilding (aim_requests() is empty).
    [[nodiscard]] bool aims_current() const;
    /// Whether passes over unchanged lighting are averaged (set from the gatherer in use:
    /// IrradianceGatherer::refines(); LightingSystem does it).
    void set_refinement(bool refine);
    /// Where the player looks (nullopt: nowhere in particular): gathers of surfaces in view go
    /// first among changes and among refinements.
    void set_view(std::optional<ViewHint> view);

    /// The AIM pages both gather backends read.
    [[nodiscard]] const RadianceAtlas& aim() const;
    [[nodiscard]] std::span<const IimPage> iim_pages() const;
    /// For tests that play the gatherer; readers (the renderer) get the const pages.
    [[nodiscard]] std::span<IimPage> iim_pages();
    /// Per surface; entries without texels belong to surfaces that have no light map.
    [[nodiscard]] std::span<const MapSurface> surfaces() const;
    /// Surface `s`'s gather passes and refinement (the gather stage's state).
    [[nodiscard]] const GatherPassState& gather_state(std::uint32_t s) const;
    [[nodiscard]] const RefinementStats& refinement(std::uint32_t s) const;
    [[nodiscard]] const IlluminationSettings& settings() const { return settings_; }
    /// Counters since construction, from both stages.
    [[nodiscard]] MapCounters counters() const;
    /// Bumped whenever a surface's emission changes (an area light switched, rescaled, added):
    /// the direct light of area lights reaches the IIM through the gather, so every surface
    /// gathers again (gather_requests) after a change.
    [[nodiscard]] std::uint64_t emission_version() const;
    /// Every light-map seam's samples (light_map_seams.hpp), stitched or not: what
    /// seam_mismatch measures.
    [[nodiscard]] std::vector<SeamSample> seam_samples() const;
    /// The world-space texel centres of a surface (what its gathers start from).
    [[nodiscard]] std::vector<GatherTexel> world_texels(std::uint32_t surface) const;

  private:
    IlluminationSettings settings_;
    /// delta_f and delta_i: this reader's positions in the photon map's change counts. The AIM
    /// stage consumes delta_f, the gather stage delta_i.
    SurfaceDeltas deltas_;
    std::unique_ptr<MapRegistry> registry_;
    std::unique_ptr<AimRebuilder> aims_;
    std::unique_ptr<IimGatherPasses> gathers_;
};

}  // namespace luxel::lighting
