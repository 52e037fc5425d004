#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "aim_rebuilder.hpp"
#include "luxel/lighting/core/gather.hpp"
#include "luxel/lighting/core/illumination_settings.hpp"
#include "luxel/lighting/core/map_surface.hpp"
#include "luxel/lighting/core/photon_world.hpp"
#include "luxel/lighting/core/seam_stitcher.hpp"
#include "luxel/lighting/core/surface_deltas.hpp"
#include "luxel/lighting/core/view_hint.hpp"
#include "map_registry.hpp"

namespace luxel::lighting {

class IimPassFilter;

/// The maps' third stage, the IIM (docs/METHOD.md §6): which surfaces gather (delta_i over the
/// threshold, an emission changed, a pass read a stale AIM, or refinement), a gather pass in
/// slices, the refinement's running mean and variance, and the filter and fade-in of a completed
/// pass. It owns every surface's GatherPassState and RefinementStats and the filters in progress;
/// it writes the registry's IIM pages and consumes delta_i in the maps' SurfaceDeltas. It reads
/// the AIM stage only to know whether the AIMs are ready and current.
class IimGatherPasses {
  public:
    IimGatherPasses(MapRegistry& registry, const AimRebuilder& aims, const PhotonWorld& world,
                    SurfaceDeltas& deltas, const IlluminationSettings& settings);
    ~IimGatherPasses();
    IimGatherPasses(const IimGatherPasses&) = delete;
    IimGatherPasses& operator=(const IimGatherPasses&) = delete;

    /// Takes in the surfaces the registry added (call after MapRegistry::sync).
    void sync();

    /// Surfaces needing a gather, highest priority first (see IlluminationMaps::gather_requests).
    [[nodiscard]] std::vector<MapRequest> requests() const;
    /// The first of requests(), by one scan.
    [[nodiscard]] std::optional<std::uint32_t> next_surface() const;
    /// See IlluminationMaps::gather.
    std::size_t gather(std::uint32_t surface, std::size_t max_texels, IrradianceGatherer& gatherer,
                       double now_seconds);

    void set_refinement(bool refine) { refine_ = refine; }
    /// Where the player looks, or nothing (every surface counts as seen); sync() follows the
    /// surfaces as they move.
    void set_view(std::optional<ViewHint> view);
    /// Whether surface `s` was in the view at the last sync() (true without a view).
    [[nodiscard]] bool seen(std::uint32_t s) const { return s >= seen_.size() || seen_[s] != 0; }
    [[nodiscard]] const GatherPassState& state(std::uint32_t s) const { return states_.at(s); }
    [[nodiscard]] const RefinementStats& refinement(std::uint32_t s) const {
        return refinements_.at(s);
    }
    [[nodiscard]] std::uint64_t passes() const { return passes_; }
    /// Of the texel passes the surfaces want (refine_passes each, one without refinement),
    /// the share averaged so far, in [0, 1] (1 with no texels): a loading screen's progress.
    [[nodiscard]] double refined_share() const;
    [[nodiscard]] std::uint64_t texels_gathered() const { return texels_gathered_; }
    [[nodiscard]] std::uint64_t texels_kept() const { return texels_kept_; }
    [[nodiscard]] const SeamStitcher& seams() const { return seams_; }

  private:
    /// Filtering a texel costs about a fortieth of gathering it with 64 rays: a gather call's
    /// unused texels of budget filter this many texels each.
    static constexpr std::size_t kFilteredPerGathered = 32;

    /// Whether what surface `s` gathers has changed since its last pass (delta_i over the
    /// threshold, an emission changed, or the pass read a stale AIM that is current now).
    [[nodiscard]] bool lighting_changed(std::uint32_t s, bool aims_are_current) const;
    /// Whether surface `s` belongs in requests(), given the AIMs' ready() and current().
    [[nodiscard]] bool wants_gather(std::uint32_t s, bool ready, bool current) const;
    /// Its place in requests(), given wants_gather(s, ..., current).
    [[nodiscard]] double priority(std::uint32_t s, bool current) const;
    /// Whether surface `s` wants a refinement pass.
    [[nodiscard]] bool wants_refinement(std::uint32_t s) const;
    /// Starts a pass over `surface`: what changed until now is what it sees.
    void start_pass(std::uint32_t surface);
    /// Which surfaces the view holds, where they are now.
    void update_seen();
    /// Marks some of the surface's texels as changed (MapRegistry::nearby_changes).
    void mark_changed(std::uint32_t surface, std::span<const std::uint32_t> texels);
    /// Whether the per-texel means are kept (refinement on), which local passes need: without
    /// them a geometry change re-gathers the whole surface.
    [[nodiscard]] bool keeps_mean() const { return refine_ && settings_.refine_passes > 1; }
    /// The texels of the pass in progress: its subset's size, or all of the surface's.
    [[nodiscard]] std::size_t pass_size(std::uint32_t surface) const;
    /// Folds a completed pass into the per-texel means (Welford) and returns what the filter
    /// reads: the means, or without them the pass's own values.
    std::vector<glm::vec3> fold_pass(std::uint32_t surface);
    [[nodiscard]] static double texel_noise(const RefinementStats& refinement, std::size_t i);
    /// A pass's last texel is gathered: updates the mean and starts its filter.
    void begin_filter(std::uint32_t surface);
    /// The filter is done: fades the pass into the IIM.
    void finish_pass(std::uint32_t surface, double now_seconds);

    MapRegistry& registry_;
    const AimRebuilder& aims_;
    const PhotonWorld& world_;
    SurfaceDeltas& deltas_;
    const IlluminationSettings& settings_;
    SeamStitcher seams_;
    /// The registry's seam objects taken in so far.
    std::size_t seam_objects_ = 0;
    std::vector<GatherPassState> states_;       ///< by surface
    std::vector<RefinementStats> refinements_;  ///< by surface
    /// Completed passes being filtered, by surface.
    std::map<std::uint32_t, std::unique_ptr<IimPassFilter>> filters_;
    bool refine_ = false;
    std::uint64_t passes_ = 0;
    std::uint64_t texels_gathered_ = 0;
    std::uint64_t texels_kept_ = 0;
    std::optional<ViewHint> view_;
    std::vector<AxisBox> local_boxes_;  ///< by surface: its texels' box in its own space
    std::vector<std::uint8_t> seen_;    ///< by surface, from view_ at the last sync()
    /// Per surface, what the local passes waiting know of their texels (docs/METHOD.md §6.8):
    /// the object moved itself (every texel shows the old place's light), and per changed
    /// texel its reach, how close it lies to a change's box (1 inside it, 0 at the edge of
    /// the region the change marks; 1 for a moved object's own texels); texels reached by more
    /// than kNearReach are gathered in a local pass of their own before the rest.
    struct LocalReach {
        bool moved = false;
        /// The object turned by more than kTurnedDegrees since its last pass: its texels face
        /// other things now. A slide leaves what they face much as it was (cornell's cube),
        /// and its surfaces go with the texels close to a change.
        bool turned = false;
        glm::mat3 axes{1.0f};      ///< the surface's world axes (unit) at its last pass
        std::vector<float> reach;  ///< by texel; 0 when not marked
        std::size_t near = 0;      ///< marked texels whose reach is over kNearReach
    };
    std::vector<LocalReach> reach_;
    /// Notes the reach of `change` on the texels it marked.
    void note_reach(const MapRegistry::NearbyChange& change);
    /// By surface: texels next to changes, to be marked again once the local AIM rebuilds of
    /// the changes up to `serial` (AimRebuilder::change_serial, the oldest of them) are done.
    /// One set per surface, so a level whose objects move every frame while the AIM units get
    /// no budget holds at most a flag per texel.
    struct AfterLocalAims {
        std::uint64_t serial = 0;
        std::vector<std::uint8_t> flagged;  ///< by texel
        std::vector<std::uint32_t> texels;
    };
    std::vector<AfterLocalAims> after_local_aims_;
};

}  // namespace luxel::lighting
