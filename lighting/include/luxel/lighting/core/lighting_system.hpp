#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "luxel/ecs/registry.hpp"
#include "luxel/lighting/core/cpu_gather.hpp"
#include "luxel/lighting/core/feature_plan.hpp"
#include "luxel/lighting/core/illumination_maps.hpp"
#include "luxel/lighting/core/irradiance_probes.hpp"
#include "luxel/lighting/core/photon_world.hpp"
#include "luxel/lighting/core/scheduler.hpp"
#include "luxel/runtime/clock.hpp"
#include "luxel/runtime/jobs.hpp"

namespace luxel::lighting {

/// The lighting system's scheduler defaults: the budget split so that a scene whose lights keep
/// moving (every group retraced, every AIM due, every frame) still gathers IIM texels: retraces
/// may use 45% of a frame's budget, caustic slices 25%, AIM rebuilds 35%; gathers and probes are
/// uncapped (shares of kinds with nothing to do go to the others); irradiance probe passes
/// 25%, so that a level full of probes never starves the light maps.
[[nodiscard]] inline SchedulerSettings default_lighting_schedule() {
    SchedulerSettings settings;
    settings.max_share[index(WorkKind::ProbeGather)] = 0.25;
    settings.max_share[index(WorkKind::GroupRetrace)] = 0.45;
    settings.max_share[index(WorkKind::CausticSlice)] = 0.25;
    settings.max_share[index(WorkKind::AimRebuild)] = 0.35;
    return settings;
}

struct LightingConfig {
    PhotonWorldSettings photons;
    IlluminationSettings maps;
    SchedulerSettings scheduler = default_lighting_schedule();
    /// The CPU gather backend's settings (used unless set_gatherer() installs another).
    CpuGatherSettings gather{64, 1e6f};
    /// Work granularity: texels per gather and AIM unit, groups per retrace unit. Smaller units
    /// fit a tight budget better (a unit that has waited too long runs even if it overruns,
    /// so the largest unit bounds the overrun); larger ones spend less on scheduling.
    std::uint32_t texels_per_gather_unit = 16;
    std::uint32_t texels_per_aim_unit = 128;
    std::uint32_t groups_per_retrace_unit = 2;
    /// Caustic photons per unit: a slice is traced in parts this large (staged until the
    /// slice is complete), so a frame spends its caustic share in units that fit it.
    std::uint32_t caustic_photons_per_unit = 256;
    /// The caustic slices' share of the budget (SchedulerSettings::max_share) while a caustic
    /// list catches up after a change to a settled scene (CausticPhotonList::catching_up): the
    /// moved caustic is shown from fewer photons until its list is retraced and refined back
    /// to the generations it held, so those frames buy more of them. Outside (0, 1): no cap then;
    /// at or under the scheduler's own share: no change.
    double caustic_catch_up_share = 0.5;
    /// The irradiance probes (for receivers without a light map, when the FeaturePlan has them)
    /// and probes per unit of their passes.
    IrradianceProbeSettings probes;
    std::uint32_t probes_per_unit = 4;
    /// During warm_up the gather and AIM units are this many times larger: there is no frame
    /// budget to fit, and fewer, larger units spend less on scheduling and on starting each
    /// unit's parallel loop (the sandbox level's warm-up, docs/PERFORMANCE.md "Warm-up": 301
    /// updates and 5.7 s at 1, 34 and 5.3 s at 16, 19 and 5.2 s at 64).
    std::uint32_t warm_up_unit_scale = 64;
};

/// What one update did (for the HUD, luxel-bench and the frame-budget tests).
struct LightingStats {
    std::uint64_t frame = 0;
    FrameReport schedule;              ///< budget, time per kind of unit, predicted vs actual
    SceneCensus census;                ///< what the plan was made from
    std::uint64_t photons_traced = 0;  ///< global photons (probes and retraces) this frame
    std::uint64_t caustic_photons_traced = 0;
    std::uint64_t aim_texels = 0;
    std::uint64_t texels_gathered = 0;
    std::uint64_t probes_gathered = 0;  ///< irradiance probe passes
    std::size_t stored_hits = 0;
    std::size_t caustic_photons_stored = 0;
    std::size_t caustic_bytes = 0;
};

/// Why LightingSystem::warm_up stopped.
enum class WarmUpEnd : std::uint8_t {
    Converged,   ///< everything converged: the maps show what the lights give
    NoProgress,  ///< an update had no work that could change anything (see WarmUpResult::why)
    TimeLimit,   ///< max_ms passed first: the per-frame budget goes on from there
};

struct WarmUpResult {
    int updates = 0;
    WarmUpEnd end = WarmUpEnd::Converged;
    /// Measured time of each kind's units during the warm-up (the scheduler's own accounting),
    /// for the log line: where a loading screen's seconds went.
    PerKind<double> kind_ms{};
    /// For NoProgress, why nothing could be done, in the FeaturePlan's words ("no light in the
    /// scene: no lighting work", "no light-mapped surface: ..."); empty otherwise.
    std::string why;
};

/// How far a warm-up has come, for a loading screen.
struct WarmUpProgress {
    double elapsed_ms = 0.0;
    int updates = 0;
    /// Of the texel passes the light maps' refinement wants, the share gathered (gathers are
    /// most of a warm-up's time), in [0, 1].
    double share = 0.0;
};
using WarmUpProgressFn = std::function<void(const WarmUpProgress&)>;

/// How it ended, for a log line: "converged", "time limit reached, not converged", "no progress
/// possible (<why>)".
[[nodiscard]] std::string describe(const WarmUpResult& result);
/// Where its time went, largest first, kinds that took under a millisecond left out:
/// "iim_gather 6120 ms, aim_rebuild 1210 ms, group_retrace 320 ms".
[[nodiscard]] std::string describe_time(const WarmUpResult& result);

/// The one façade a game drives lighting with:
///
///     LightingSystem lighting(registry, jobs);   // after the game has added its components
///     each frame: game systems, TransformSystem::update(), lighting.update(budget_ms, t), render
///
/// It learns what changed only through the ECS change lists (PhotonWorld's and
/// IlluminationMaps' observers): moved, added, removed and edited components. Every frame it
/// re-derives the FeaturePlan, queues the work the plan allows (photon probes, group retraces,
/// caustic slices, AIM rebuilds by delta_f/area, IIM gathers by delta_i/area) and lets the
/// Scheduler run what fits `budget_ms`. A budget of 0 pauses lighting: nothing is traced or
/// gathered and the queues wait; a later non-zero budget works the backlog off.
class LightingSystem {
  public:
    /// `clock` times the work units (inject a ManualClock in tests).
    LightingSystem(ecs::Registry& registry, JobSystem& jobs, LightingConfig config = {},
                   const Clock& clock = SteadyClock::instance());
    ~LightingSystem();
    LightingSystem(const LightingSystem&) = delete;
    LightingSystem& operator=(const LightingSystem&) = delete;

    /// One frame of lighting work within `budget_ms`; `now_seconds` stamps IIM updates for
    /// their fade-in.
    const LightingStats& update(double budget_ms, double now_seconds);

    /// What a game does behind a loading screen: updates with an unlimited budget at
    /// `now_seconds` (the game holds still) until everything has converged, an update finds
    /// nothing it could do (no light, nothing light-mapped: it would never converge), or
    /// `max_ms` has passed on the system's clock. The first maps then do not have to be built
    /// a budget's worth at a time while the player watches.
    /// `progress`, when given, is called after an update whenever `progress_every_ms` have
    /// passed on the system's clock since the last call, and once at the end.
    WarmUpResult warm_up(double now_seconds, double max_ms, const WarmUpProgressFn& progress = {},
                         double progress_every_ms = 500.0);

    /// Replaces the gather backend (e.g. lighting/gpu's HemiPlaneGatherer); null restores the
    /// CPU one. The gatherer must outlive its use here.
    void set_gatherer(IrradianceGatherer* gatherer);
    /// Where the player looks, for the next update()s (nullopt: nowhere in particular): the
    /// gather passes of surfaces in view go first, among changes and among refinements
    /// (ViewHint). The renderer's camera, each frame.
    void set_view(std::optional<ViewHint> view) { maps_->set_view(view); }

    [[nodiscard]] const FeaturePlan& plan() const { return plan_; }
    [[nodiscard]] const LightingStats& stats() const { return stats_; }
    [[nodiscard]] const PhotonWorld& photons() const { return *photons_; }
    [[nodiscard]] PhotonWorld& photons() { return *photons_; }
    /// Read only: the renderer and the tools follow the pages through their versions
    /// (RadiancePage::changes_since); only the lighting system's units write the maps.
    [[nodiscard]] const IlluminationMaps& maps() const { return *maps_; }
    /// The irradiance probes while the FeaturePlan has them (null otherwise): read only, the
    /// renderer follows them through IrradianceProbes::version.
    [[nodiscard]] const IrradianceProbes* irradiance_probes() const { return probes_.get(); }
    [[nodiscard]] const Scheduler& scheduler() const { return scheduler_; }
    [[nodiscard]] const LightingConfig& config() const { return config_; }

  private:
    SceneCensus take_census() const;
    /// The caustic slices' max_share this frame: the scheduler's, or
    /// LightingConfig::caustic_catch_up_share while a caustic list catches up.
    [[nodiscard]] double caustic_share(bool catching_up) const;
    /// Counts the diffuse mesh objects without a light map (SceneCensus::unmapped_receivers)
    /// when meshes or surfaces changed.
    void count_unmapped_receivers();
    /// Why the warm-up can make no progress, after this update and `idle_updates` without any.
    [[nodiscard]] std::string warm_up_stall(int idle_updates) const;
    void queue_work();
    /// Probes, group retraces and caustic slices.
    void queue_photon_units();
    /// Slices of the next AIM rebuild and of the next gather pass.
    void queue_map_units();
    /// Creates, refits or frees the irradiance probes as the plan says.
    void sync_probes();
    /// Gives the CPU gather this frame's lights and probes for what surfaces without a light
    /// map send back (UnmappedRadiance); none while the level has no such receiver.
    void sync_unmapped_radiance();
    /// Units of irradiance probe passes.
    void queue_probe_units();

    ecs::Registry& registry_;
    JobSystem& jobs_;
    LightingConfig config_;
    std::unique_ptr<PhotonWorld> photons_;
    std::unique_ptr<IlluminationMaps> maps_;
    std::unique_ptr<CpuGatherer> cpu_gatherer_;
    std::unique_ptr<IrradianceProbes> probes_;
    UnmappedRadiance unmapped_;  ///< read by cpu_gatherer_ while the level has probes
    /// The light-mapped surface count the probes' grid was fitted to (a new or removed surface
    /// may change the level's extent).
    std::uint32_t probe_grid_surfaces_ = 0;
    std::size_t queued_probe_units_ = 0;
    std::uint32_t unmapped_receivers_ = 0;
    /// The surface count unmapped_receivers_ was counted at (max: never counted).
    std::size_t counted_surfaces_ = std::numeric_limits<std::size_t>::max();
    IrradianceGatherer* gatherer_ = nullptr;
    Scheduler scheduler_;
    const Clock* clock_;
    FeaturePlan plan_;
    LightingStats stats_;
    std::uint64_t frame_ = 0;
    double now_seconds_ = 0.0;
    /// Frames since an object or light last changed: probes keep running for a full probe
    /// cycle (M frames) after the last change, since a path may diverge at any of its photons.
    /// (Starts as "long ago": nothing has moved yet.)
    std::uint64_t frames_since_change_ = std::numeric_limits<std::uint64_t>::max() / 2;
    std::uint64_t probe_frame_ = 0;  ///< advances only when probes run
    std::size_t queued_retrace_units_ = 0;
    std::size_t queued_aim_units_ = 0;
    std::size_t queued_caustic_units_ = 0;
    std::size_t queued_gather_units_ = 0;
    /// LightingConfig::warm_up_unit_scale while warm_up runs, 1 otherwise.
    std::uint32_t unit_scale_ = 1;
    /// Off during the warm-up: its convergence is the lists' first generation, and the frames'
    /// budget refines a still caustic from there (progressive caustics, METHOD 7.6).
    bool refine_caustics_ = true;
};

}  // namespace luxel::lighting
