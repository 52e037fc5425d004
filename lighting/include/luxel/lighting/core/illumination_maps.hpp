#pragma once

#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/ecs/observer.hpp"
#include "luxel/ecs/registry.hpp"
#include "luxel/ecs/transform.hpp"
#include "luxel/lighting/components.hpp"
#include "luxel/lighting/core/gather.hpp"
#include "luxel/lighting/core/iim_page.hpp"
#include "luxel/lighting/core/photon_density.hpp"
#include "luxel/lighting/core/photon_world.hpp"
#include "luxel/lighting/core/radiance_atlas.hpp"
#include "luxel/lighting/core/surface_deltas.hpp"
#include "luxel/lighting/core/surface_footprint.hpp"
#include "luxel/lighting/core/surface_texels.hpp"

/// Photons into light maps (docs/METHOD.md §5-6): the AIM of each light-mapped
/// surface from its photons, and the IIM from final gathering over the AIM-lit scene.
namespace luxel::lighting {

/// What an IIM texel holds (as the source does): irradiance for textured surfaces, whose
/// albedo varies within a texel and is applied per pixel; radiance pre-multiplied by the
/// albedo (albedo * E / pi) for uniform ones, saving the renderer a lookup.
enum class IimContent { Irradiance, Radiance };

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
    /// A surface's texels are gathered again when delta_i exceeds this fraction of its stored
    /// energy.
    double iim_threshold = 0.05;
    /// Seconds over which an updated IIM texel fades in (0: at once).
    double blend_seconds = 0.5;
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
};

/// A piece of work the scheduler can order: a surface and its priority (delta / area, W/m^2).
struct MapRequest {
    std::uint32_t surface = 0;
    double priority = 0.0;
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
    /// Passes averaged once the pass in progress is in (set when its gathering completes).
    std::uint32_t passes_when_done = 0;
    /// Passes started on this surface (each gathers with new samples).
    std::uint32_t started = 0;
    /// IlluminationMaps::emission_version() when the last pass started.
    std::uint64_t emission_version = 0;
    /// MapCounters::aim_rebuilds when the last pass started.
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
    std::uint32_t passes_averaged = 0;
    std::vector<glm::vec3> mean;
    std::vector<glm::vec3> m2;
};

/// One light-mapped surface as the maps know it: what the registry keeps (entity, texels,
/// material, transform), whether its AIM exists, its gather passes and its refinement.
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
    bool aim_built = false;
    GatherPassState gather;
    RefinementStats refinement;
};

/// Counters since construction.
struct MapCounters {
    std::uint64_t aim_rebuilds = 0;
    std::uint64_t aim_texels = 0;
    std::uint64_t gather_passes = 0;
    std::uint64_t texels_gathered = 0;
    std::uint64_t enclosed_texels = 0;  ///< AIM texels found enclosed (set to 0)
};

class IimPassFilter;

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
    std::size_t rebuild_aim(std::uint32_t surface,
                            std::size_t max_texels = std::numeric_limits<std::size_t>::max());
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

    /// Whether every surface holding photons has had its first AIM (gather passes wait).
    [[nodiscard]] bool aims_ready() const;
    /// Whether no AIM needs rebuilding (aim_requests() is empty).
    [[nodiscard]] bool aims_current() const;
    /// Whether passes over unchanged lighting are averaged (set from the gatherer in use:
    /// IrradianceGatherer::refines(); LightingSystem does it).
    void set_refinement(bool refine) { refine_ = refine; }

    /// The AIM pages both gather backends read.
    [[nodiscard]] const RadianceAtlas& aim() const { return aim_; }
    [[nodiscard]] std::span<const IimPage> iim_pages() const { return iim_pages_; }
    /// For tests that play the gatherer; readers (the renderer) get the const pages.
    [[nodiscard]] std::span<IimPage> iim_pages() { return iim_pages_; }
    /// Per surface; entries without texels belong to surfaces that have no light map.
    [[nodiscard]] std::span<const MapSurface> surfaces() const { return surfaces_; }
    [[nodiscard]] const IlluminationSettings& settings() const { return settings_; }
    [[nodiscard]] const MapCounters& counters() const { return counters_; }
    /// Bumped whenever a surface's emission changes (an area light switched, rescaled, added):
    /// the direct light of area lights reaches the IIM through the gather, so every surface
    /// gathers again (gather_requests) after a change.
    [[nodiscard]] std::uint64_t emission_version() const { return emission_version_; }
    /// The world-space texel centres of a surface (what its gathers start from).
    [[nodiscard]] std::vector<GatherTexel> world_texels(std::uint32_t surface) const;

  private:
    struct AimRebuildState;
    /// Filtering a texel costs about a fortieth of gathering it with 64 rays: a gather call's
    /// unused texels of budget filter this many texels each.
    static constexpr std::size_t kFilteredPerGathered = 32;

    void add_surface(std::uint32_t surface);
    void refresh_transform(std::uint32_t surface);
    /// Sets aim_.surface_emission[surface] from its material and its entity's AreaLight;
    /// returns whether it changed.
    bool refresh_emission(std::uint32_t surface);
    /// Whether what surface `s` gathers has changed since its last pass (delta_i over the
    /// threshold, an emission changed, or the pass read a stale AIM that is current now).
    [[nodiscard]] bool lighting_changed(std::uint32_t s, bool aims_are_current) const;
    /// Whether every enclosure ray from the texel is blocked within `ray_length` metres.
    [[nodiscard]] bool enclosed(const GatherTexel& texel, float ray_length) const;
    /// Whether surface `s` needs an AIM rebuild: never built, in progress, or delta_f over the
    /// threshold.
    [[nodiscard]] bool needs_aim(std::uint32_t s) const;
    /// Its place in aim_requests(), given needs_aim(s).
    [[nodiscard]] double aim_priority(std::uint32_t s) const;
    /// Whether surface `s` belongs in gather_requests(), given aims_ready() and aims_current().
    [[nodiscard]] bool wants_gather(std::uint32_t s, bool ready, bool current) const;
    /// Its place in gather_requests(), given wants_gather(s, ..., current).
    [[nodiscard]] double gather_priority(std::uint32_t s, bool current) const;
    /// Whether surface `s` wants a refinement pass.
    [[nodiscard]] bool wants_refinement(std::uint32_t s) const;
    /// A pass's last texel is gathered: updates the mean and starts its filter.
    void begin_filter(std::uint32_t surface);
    /// The filter is done: fades the pass into the IIM.
    void finish_pass(std::uint32_t surface, double now_seconds);
    /// Fills the padding texels around `surface`'s texels on `page` with the mean of their
    /// owned neighbours, so bilinear lookups at a chart's border do not fetch black.
    void dilate(std::uint32_t surface, RadiancePage& page) const;
    std::int32_t page_index(const scene::Scene* source, int page, int page_size);

    ecs::Registry& registry_;
    const PhotonWorld& world_;
    /// delta_f and delta_i: this reader's positions in the photon map's change counts.
    SurfaceDeltas deltas_;
    IlluminationSettings settings_;
    RadianceAtlas aim_;
    std::vector<IimPage> iim_pages_;
    /// Per page texel, the surface that owns it (-1: padding or unused).
    std::vector<std::vector<std::int32_t>> owners_;
    std::vector<MapSurface> surfaces_;
    std::map<std::pair<const scene::Scene*, int>, std::int32_t> pages_;
    std::map<ecs::Entity, std::vector<std::uint32_t>> surfaces_of_;
    ecs::Observer<ecs::WorldTransform> moves_;
    ecs::Observer<AreaLight> area_changes_;
    std::uint64_t emission_version_ = 0;
    bool refine_ = false;
    MapCounters counters_;
    std::unique_ptr<AimRebuildState> aim_rebuild_;
    /// Completed passes being filtered, by surface.
    std::map<std::uint32_t, std::unique_ptr<IimPassFilter>> filters_;
};

}  // namespace luxel::lighting
