#include "luxel/lighting/core/lighting_system.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "luxel/scene/components.hpp"

namespace luxel::lighting {
namespace {

/// Slices of at most `slice` texels that cover `texels` (slice >= 1).
std::size_t slices(std::size_t texels, std::size_t slice) {
    return (texels + slice - 1) / slice;
}

/// Within one kind, earlier requests (the maps order them by delta / area) get a priority in
/// (1, 2]; the scheduler's per-kind weights decide between kinds.
double rank_priority(std::size_t rank, std::size_t count) {
    return 1.0 +
           static_cast<double>(count - rank) / static_cast<double>(std::max<std::size_t>(count, 1));
}

bool caps(double share) {
    return std::isfinite(share) && share > 0.0 && share < 1.0;
}

}  // namespace

double LightingSystem::caustic_share(bool catching_up) const {
    const double base = config_.scheduler.max_share[index(WorkKind::CausticSlice)];
    if (!catching_up || !caps(base)) {
        return base;  // an uncapped kind stays uncapped
    }
    const double more = config_.caustic_catch_up_share;
    return caps(more) ? std::max(base, more) : 0.0;
}

LightingSystem::LightingSystem(ecs::Registry& registry, JobSystem& jobs, LightingConfig config,
                               const Clock& clock)
    : registry_(registry),
      jobs_(jobs),
      config_(config),
      photons_(std::make_unique<PhotonWorld>(registry, config.photons)),
      maps_(std::make_unique<IlluminationMaps>(registry, *photons_, config.maps)),
      cpu_gatherer_(
          std::make_unique<CpuGatherer>(photons_->ray_scene(), maps_->aim(), config.gather, &jobs)),
      gatherer_(cpu_gatherer_.get()),
      scheduler_(clock, config.scheduler),
      clock_(&clock),
      plan_(FeaturePlan::from({})) {
    // Gather rays follow mirrors and glass with the photon world's own optics.
    cpu_gatherer_->set_materials(&photons_->materials());
    maps_->set_refinement(gatherer_->refines());
}

LightingSystem::~LightingSystem() = default;

std::string describe(const WarmUpResult& result) {
    switch (result.end) {
        case WarmUpEnd::Converged:
            return "converged";
        case WarmUpEnd::NoProgress:
            return "no progress possible (" + result.why + ")";
        case WarmUpEnd::TimeLimit:
            return "time limit reached, not converged";
    }
    return "not converged";
}

std::string describe_time(const WarmUpResult& result) {
    std::array<std::size_t, kWorkKindCount> order{};
    for (std::size_t kind = 0; kind < kWorkKindCount; ++kind) {
        order[kind] = kind;
    }
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return result.kind_ms[a] > result.kind_ms[b];
    });
    std::string text;
    for (const std::size_t kind : order) {
        if (!(result.kind_ms[kind] >= 1.0)) {
            continue;
        }
        text += (text.empty() ? "" : ", ") + std::string(name(static_cast<WorkKind>(kind))) + " " +
                std::to_string(static_cast<long long>(std::lround(result.kind_ms[kind]))) + " ms";
    }
    return text;
}

std::string LightingSystem::warm_up_stall(int idle_updates) const {
    if (!plan_.photon_tracing()) {
        // "no light in the scene: no lighting work", "no light-mapped surface: ...".
        return plan_.reason(Pass::PhotonTracing);
    }
    if (stats_.schedule.units_done == 0) {
        return "no lighting work to queue, yet the maps are not converged";
    }
    return std::to_string(idle_updates) + " updates in a row traced, rebuilt and gathered nothing";
}

WarmUpResult LightingSystem::warm_up(double now_seconds, double max_ms,
                                     const WarmUpProgressFn& progress, double progress_every_ms) {
    // Updates in a row whose units traced, rebuilt and gathered nothing before the warm-up gives
    // up: units can run without effect (gathers waiting for an AIM that no unit will build), and
    // a pass's last filter slices gather nothing but take at most one update on a surface within
    // luxel-prep's texel budget.
    constexpr int kIdleUpdates = 8;
    const Stopwatch watch(*clock_);
    WarmUpResult result;
    // Larger units while no frame waits; back to the frame's size however the warm-up ends.
    struct UnitScale {
        std::uint32_t& scale;
        bool& refine;
        ~UnitScale() {
            scale = 1;
            refine = true;
        }
    } const unit_scale{unit_scale_, refine_caustics_};
    unit_scale_ = std::max<std::uint32_t>(config_.warm_up_unit_scale, 1);
    refine_caustics_ = false;
    const SchedulerTotals before = scheduler_.totals();
    double reported_ms = 0.0;
    const auto report = [&] {
        if (progress) {
            reported_ms = watch.elapsed_ms();
            progress({reported_ms, result.updates, maps_->refined_share()});
        }
    };
    const auto finish = [&](WarmUpEnd end, std::string why) {
        report();
        result.end = end;
        result.why = std::move(why);
        for (std::size_t kind = 0; kind < kWorkKindCount; ++kind) {
            result.kind_ms[kind] =
                scheduler_.totals().kinds[kind].actual_ms - before.kinds[kind].actual_ms;
        }
        return result;
    };
    int idle = 0;
    while (watch.elapsed_ms() < max_ms) {
        // Stamped one blend time early: what the loading screen built shows in full at
        // `now_seconds` instead of fading in from black.
        update(std::numeric_limits<double>::infinity(), now_seconds - config_.maps.blend_seconds);
        ++result.updates;
        if (progress && watch.elapsed_ms() - reported_ms >= progress_every_ms) {
            report();
        }
        if (plan_.census().converged) {
            return finish(WarmUpEnd::Converged, {});
        }
        const bool worked = stats_.photons_traced + stats_.caustic_photons_traced +
                                stats_.aim_texels + stats_.texels_gathered +
                                stats_.probes_gathered >
                            0;
        idle = worked ? 0 : idle + 1;
        // With an unlimited budget every queued unit ran: an update that ran none leaves the
        // next one exactly where it was. Without an enabled light there is nothing to build:
        // the maps start black, and the passes that would clear what lights switched off left
        // in them (FeaturePlan) have nothing to clear at load; the frames' budget does it if a
        // game warms up later.
        const bool unlit = stats_.census.lights_enabled == 0;
        if (unlit || stats_.schedule.units_done == 0 || idle >= kIdleUpdates) {
            return finish(WarmUpEnd::NoProgress, warm_up_stall(idle));
        }
    }
    return finish(WarmUpEnd::TimeLimit, {});
}

void LightingSystem::set_gatherer(IrradianceGatherer* gatherer) {
    gatherer_ = gatherer != nullptr ? gatherer : cpu_gatherer_.get();
    gatherer_->set_materials(&photons_->materials());
    maps_->set_refinement(gatherer_->refines());
}

SceneCensus LightingSystem::take_census() const {
    SceneCensus census;
    census.lights_total = static_cast<std::uint32_t>(photons_->light_count());
    census.lights_enabled = static_cast<std::uint32_t>(photons_->active_lights().size());
    census.caustic_generators = static_cast<std::uint32_t>(photons_->generator_count());
    std::uint32_t mapped = 0;
    for (const MapSurface& surface : maps_->surfaces()) {
        mapped += surface.texels.texels.empty() ? 0u : 1u;
    }
    census.lightmapped_surfaces = mapped;
    census.unmapped_receivers = unmapped_receivers_;
    census.probes_pending = probes_ != nullptr && probes_->pending() > 0;
    census.dynamic_objects = static_cast<std::uint32_t>(photons_->dynamic_object_count());
    const PhotonSyncStats& sync = photons_->last_sync();
    census.moving_objects = sync.objects_moved;
    census.geometry_changes = sync.meshes_changed;
    std::uint32_t specular = 0;
    for (const TraceMaterial& material : photons_->materials()) {
        specular += material.scattering != Scattering::Diffuse ? 1u : 0u;
    }
    census.specular_materials = specular;
    const std::uint64_t probe_cycle = config_.photons.selective.per_group;
    census.maps_pending = !maps_->aim_requests().empty() || !maps_->gather_requests().empty();
    census.converged = photons_->pending_groups().empty() && !photons_->caustics_pending() &&
                       !census.maps_pending && !census.probes_pending &&
                       scheduler_.pending_total() == 0 && frames_since_change_ >= probe_cycle;
    return census;
}

void LightingSystem::count_unmapped_receivers() {
    // Meshes come and go only through a sync that reports them, and surfaces only with them:
    // counted again then, not every frame.
    if (photons_->last_sync().meshes_changed == 0 &&
        maps_->surfaces().size() == counted_surfaces_) {
        return;
    }
    counted_surfaces_ = maps_->surfaces().size();
    // Receivers without a light map: mesh objects none of whose surfaces is mapped, and that
    // have a diffuse primitive (glass and mirrors show what they reflect and refract, not
    // indirect light of their own).
    std::vector<ecs::Entity> mapped_entities;
    mapped_entities.reserve(maps_->surfaces().size());
    for (const MapSurface& surface : maps_->surfaces()) {
        if (!surface.texels.texels.empty()) {
            mapped_entities.push_back(surface.entity);
        }
    }
    std::sort(mapped_entities.begin(), mapped_entities.end());
    std::uint32_t unmapped = 0;
    for (const auto& [entity, object] : photons_->mesh_objects()) {
        if (std::binary_search(mapped_entities.begin(), mapped_entities.end(), entity)) {
            continue;
        }
        const auto* instance = registry_.try_get<scene::MeshInstance>(entity);
        if (instance == nullptr || instance->source == nullptr) {
            continue;
        }
        const auto& materials = instance->source->materials;
        const auto& primitives = instance->geometry().primitives;
        const bool diffuse =
            std::any_of(primitives.begin(), primitives.end(), [&](const scene::Primitive& p) {
                if (p.material < 0 || static_cast<std::size_t>(p.material) >= materials.size()) {
                    return true;  // the default material is diffuse
                }
                const scene::Material& m = materials[static_cast<std::size_t>(p.material)];
                return !(m.transmission > 0.0f) && !m.is_specular();
            });
        unmapped += diffuse ? 1u : 0u;
    }
    unmapped_receivers_ = unmapped;
}

const LightingStats& LightingSystem::update(double budget_ms, double now_seconds) {
    now_seconds_ = now_seconds;
    const Stopwatch update_watch(*clock_);
    const bool had_photons = photons_->photon_map().stored_hit_count() > 0;
    photons_->sync();
    maps_->sync();
    const PhotonSyncStats& sync = photons_->last_sync();
    // Only geometry that moved or changed under stored photons needs probes to find the paths
    // it diverted; lights that change invalidate their own groups, and geometry added before
    // anything was traced is simply traced through.
    const bool changed = sync.objects_moved > 0 || (sync.meshes_changed > 0 && had_photons);
    frames_since_change_ = changed ? 0 : frames_since_change_ + 1;

    stats_ = {};
    stats_.frame = frame_;
    count_unmapped_receivers();
    stats_.census = take_census();
    plan_ = FeaturePlan::from(stats_.census);
    sync_probes();
    sync_unmapped_radiance();
    queue_work();
    const std::uint64_t aim_before = maps_->counters().aim_texels;
    const std::uint64_t gathered_before = maps_->counters().texels_gathered;
    // The budget covers the whole update: what syncing and queueing took comes off the
    // scheduler's share. A budget of 0 still pauses; one that syncing used up leaves a sliver,
    // so overdue units keep their guaranteed progress.
    double scheduler_budget = budget_ms;
    if (budget_ms > 0.0) {
        scheduler_budget = std::max(budget_ms - update_watch.elapsed_ms(), 1e-6);
    }
    stats_.schedule = scheduler_.run(scheduler_budget);
    stats_.aim_texels = maps_->counters().aim_texels - aim_before;
    stats_.texels_gathered = maps_->counters().texels_gathered - gathered_before;
    // What the probes see changed: an AIM rebuilt (photons landed differently, a light
    // switched or moved) or an emitter's switch. Each probe gathers a fresh pass from the next
    // update on, showing its old light until then.
    if (probes_ != nullptr && (stats_.aim_texels > 0 || sync.lights_refreshed > 0)) {
        probes_->lighting_changed();
    }
    stats_.stored_hits = photons_->photon_map().stored_hit_count();
    const CausticTotals caustics = photons_->caustic_totals();
    stats_.caustic_photons_stored = caustics.stored;
    stats_.caustic_bytes = caustics.bytes;
    ++frame_;
    return stats_;
}

void LightingSystem::queue_work() {
    queue_photon_units();
    queue_map_units();
    queue_probe_units();
}

void LightingSystem::sync_probes() {
    if (!plan_.irradiance_probes()) {
        probes_.reset();  // a pass the scene does not use holds nothing
        probe_grid_surfaces_ = 0;
        return;
    }
    if (probes_ != nullptr && probe_grid_surfaces_ == stats_.census.lightmapped_surfaces) {
        return;
    }
    // The grid covers the light-mapped level (its static geometry): moving objects may leave
    // it, and a grid that followed them would start over each time.
    AxisBox level;
    for (const MapSurface& surface : maps_->surfaces()) {
        for (const SurfaceTexel& texel : surface.texels.texels) {
            level.add(glm::vec3(surface.to_world * glm::vec4(texel.position, 1.0f)));
        }
    }
    const ProbeGrid grid = fit_probe_grid(level, config_.probes.spacing, config_.probes.max_probes);
    if (probes_ == nullptr || !(probes_->grid() == grid)) {
        probes_ = std::make_unique<IrradianceProbes>(grid, config_.probes);
    }
    probe_grid_surfaces_ = stats_.census.lightmapped_surfaces;
}

void LightingSystem::sync_unmapped_radiance() {
    if (probes_ == nullptr) {  // the plan has no receiver without a light map
        unmapped_.clear();
        cpu_gatherer_->set_unmapped(nullptr);
        return;
    }
    std::vector<const LightSource*> lights;
    for (const LightPhotons* light : photons_->active_lights()) {
        lights.push_back(&light->emitter().light());
    }
    unmapped_.set(&photons_->ray_scene(), lights, probes_.get());
    cpu_gatherer_->set_unmapped(&unmapped_);
}

void LightingSystem::queue_probe_units() {
    const std::size_t per_unit =
        static_cast<std::size_t>(std::max<std::uint32_t>(config_.probes_per_unit, 1)) * unit_scale_;
    const std::size_t pending = probes_ != nullptr ? probes_->pending() : 0;
    // While AIM rebuilds are waiting, what a probe gathers now is stale by the next rebuild:
    // one unit a frame keeps the probes following the light without gathering every probe
    // once per rebuild (a warm-up's AIMs converge over tens of updates).
    const std::size_t max_units = maps_->aims_current() ? 64 : 1;
    const std::size_t units = std::min((pending + per_unit - 1) / per_unit, max_units);
    for (std::size_t unit = 0; unit < units; ++unit) {
        scheduler_.enqueue({WorkKind::ProbeGather, unit, rank_priority(unit, units),
                            [this, per_unit] {
                                if (probes_ == nullptr) {
                                    return;
                                }
                                const auto tracer = [this](const glm::vec3& origin,
                                                           std::span<const glm::vec3> directions,
                                                           std::span<ProbeRay> rays,
                                                           std::uint32_t seed) {
                                    cpu_gatherer_->trace_probe_rays(origin, directions, rays, seed);
                                };
                                stats_.probes_gathered += probes_->gather(per_unit, tracer, &jobs_);
                            },
                            static_cast<double>(per_unit)});
    }
    for (std::size_t unit = units; unit < queued_probe_units_; ++unit) {
        scheduler_.cancel(WorkKind::ProbeGather, unit);
    }
    queued_probe_units_ = units;
}

void LightingSystem::queue_photon_units() {
    // Probes: one photon of every group, while something may have changed a path.
    if (plan_.selective_probes()) {
        scheduler_.enqueue({WorkKind::PhotonProbe, 0, 1.0,
                            [this] {
                                const EmissionStats done = photons_->probe(probe_frame_++, jobs_);
                                stats_.photons_traced += done.trace.photons;
                            },
                            1.0});
    } else {
        scheduler_.cancel(WorkKind::PhotonProbe, 0);
    }

    // Group retraces, a few groups per unit, oldest first.
    const std::size_t per_unit = std::max<std::uint32_t>(config_.groups_per_retrace_unit, 1);
    const std::size_t pending = plan_.photon_tracing() ? photons_->pending_groups().size() : 0;
    const std::size_t retrace_units = (pending + per_unit - 1) / per_unit;
    for (std::size_t unit = 0; unit < retrace_units; ++unit) {
        scheduler_.enqueue({WorkKind::GroupRetrace, unit, rank_priority(unit, retrace_units),
                            [this, per_unit] {
                                const EmissionStats done =
                                    photons_->retrace_pending(jobs_, per_unit);
                                stats_.photons_traced += done.trace.photons;
                            },
                            static_cast<double>(per_unit)});
    }
    for (std::size_t unit = retrace_units; unit < queued_retrace_units_; ++unit) {
        scheduler_.cancel(WorkKind::GroupRetrace, unit);
    }
    queued_retrace_units_ = retrace_units;

    // Caustic slices, traced in parts of caustic_photons_per_unit photons that fit a frame's
    // caustic share: the lists that need a retrace first, then (not in the warm-up) the next
    // generation of those still refining (progressive caustics, METHOD 7.6), so a still
    // caustic keeps getting less noisy.
    std::size_t caustic_units = 0;
    const bool refine = refine_caustics_;
    const std::uint32_t photons_per_unit =
        std::max<std::uint32_t>(config_.caustic_photons_per_unit, 1) * unit_scale_;
    if (plan_.caustics() &&
        (photons_->caustics_pending() || (refine && photons_->caustics_refining()))) {
        constexpr std::uint64_t kMaxCausticUnits = 32;  // a frame never has room for more
        const std::uint64_t left = photons_->caustic_photons_left(refine);
        caustic_units = static_cast<std::size_t>(
            std::min(kMaxCausticUnits, (left + photons_per_unit - 1) / photons_per_unit));
    }
    // A caustic catching up after a change to a settled scene is shown from fewer photons until
    // its lists are retraced and refined back (METHOD 7.6): those frames give the caustic
    // slices a larger share.
    scheduler_.set_max_share(WorkKind::CausticSlice,
                             caustic_share(photons_->caustics_catching_up()));
    for (std::size_t unit = 0; unit < caustic_units; ++unit) {
        scheduler_.enqueue({WorkKind::CausticSlice, unit, rank_priority(unit, caustic_units),
                            [this, photons_per_unit, refine] {
                                const CausticFrameStats done =
                                    photons_->trace_caustic_unit(photons_per_unit, refine, jobs_);
                                stats_.caustic_photons_traced += done.trace.photons;
                            },
                            static_cast<double>(photons_per_unit) / 1000.0});
    }
    for (std::size_t unit = caustic_units; unit < queued_caustic_units_; ++unit) {
        scheduler_.cancel(WorkKind::CausticSlice, unit);
    }
    queued_caustic_units_ = caustic_units;
}

void LightingSystem::queue_map_units() {
    // AIM rebuilds are sequential by nature (one kd-tree at a time): the units are slices of
    // "the next AIM work", each taking the maps' first request when it runs (the rebuild in
    // progress, then unbuilt maps, then the largest delta_f / area; a waiting surface's delta
    // keeps growing while its light keeps changing, which ages it), found by one scan, not by
    // listing and sorting every request.
    //
    // Units naming their surface when queued were built and measured (cornell, the cube moved,
    // 3-4 runs each): 90 frames after the move the indirect error was 11% instead of 7% at 8 ms
    // and 13.5% instead of 12.3% at 4 ms, whether keyed by surface or by rank. A unit named at
    // queue time cannot follow what the frame's own retraces and rebuilds change: after a move
    // the units queued for refinement passes find their surfaces no longer refining and do
    // nothing, while the passes the move needs wait for the next frame's queue.
    const std::size_t slice =
        static_cast<std::size_t>(std::max<std::uint32_t>(config_.texels_per_aim_unit, 1)) *
        unit_scale_;
    // One unit per slice of each requested surface: a unit never crosses to the next surface,
    // so a slice larger than a surface still takes one unit per surface.
    std::size_t aim_slices = 0;
    if (plan_.aim()) {
        for (const MapRequest& request : maps_->aim_requests()) {
            aim_slices += slices(maps_->surfaces()[request.surface].texels.texels.size(), slice);
        }
    }
    constexpr std::size_t kMaxAimUnits = 64;  // a frame never has room for more
    const std::size_t aim_units = std::min(aim_slices, kMaxAimUnits);
    for (std::size_t unit = 0; unit < aim_units; ++unit) {
        scheduler_.enqueue({WorkKind::AimRebuild, unit, rank_priority(unit, aim_units),
                            [this, slice] {
                                if (const auto surface = maps_->next_aim_surface()) {
                                    maps_->rebuild_aim(*surface, slice, &jobs_);
                                }
                            },
                            static_cast<double>(slice)});
    }
    for (std::size_t unit = aim_units; unit < queued_aim_units_; ++unit) {
        scheduler_.cancel(WorkKind::AimRebuild, unit);
    }
    queued_aim_units_ = aim_units;
    // Saturating: a huge configured unit times the warm-up's scale must not wrap to a small one.
    const auto texels_per_unit = static_cast<std::uint32_t>(std::min<std::uint64_t>(
        static_cast<std::uint64_t>(std::max<std::uint32_t>(config_.texels_per_gather_unit, 1)) *
            unit_scale_,
        std::numeric_limits<std::uint32_t>::max()));
    // Gathers, like AIM rebuilds, are slices of "the next gather work" (the maps' first request:
    // the pass furthest along), so passes complete one after another.
    std::size_t gather_slices = 0;
    // The local passes at the head of the requests (texels next to geometry that moved) go
    // before AIM rebuilds: they are small, they fix what a player sees go wrong (a crate's dark
    // footprint), and the AIM they read is stale only where the photons changed, which the
    // full passes after the rebuilds take care of. Without this, the rebuilds that exact
    // invalidation's retraces cause hold the footprint dark for tens of frames at 4 ms.
    std::size_t local_slices = 0;
    bool head = true;
    if (plan_.iim_gather()) {
        for (const MapRequest& request : maps_->gather_requests()) {
            const std::size_t count =
                slices(maps_->surfaces()[request.surface].texels.texels.size(), texels_per_unit);
            const GatherPassState& state = maps_->gather_state(request.surface);
            const bool local = state.in_progress ? state.local : state.changed_count > 0;
            head = head && local;
            // A local pass gathers only its texels: one slice of it is usually all of it. Boosting
            // every slice of a local pass was tried (it showed crate-footprint's pass a few frames
            // sooner at 4 ms) and reverted: a level whose objects keep moving keeps local passes
            // queued, and on a slow machine (the sanitizer build, or a 0.3 ms budget) their
            // boosted units took every frame's budget and no photon was traced in 60 frames.
            local_slices += head ? 1 : 0;
            gather_slices += count;
        }
    }
    constexpr std::size_t kMaxGatherUnits = 256;  // a frame never has room for more
    const std::size_t gather_units = std::min(gather_slices, kMaxGatherUnits);
    // Above every AIM rebuild: ranks are in (1, 2], so with the default weights (gathers 2,
    // AIM rebuilds 3, retraces 5) a boosted unit weighs (6, 8], every AIM unit at most 6, and
    // the retraces (5, 10]: the local pass goes amid the retraces, before any rebuild.
    constexpr double kLocalBoost = 2.0;
    for (std::size_t unit = 0; unit < gather_units; ++unit) {
        const double boost = unit < local_slices ? kLocalBoost : 0.0;
        scheduler_.enqueue({WorkKind::IimGather, unit, boost + rank_priority(unit, gather_units),
                            [this, texels_per_unit] {
                                if (const auto surface = maps_->next_gather_surface()) {
                                    maps_->gather(*surface, texels_per_unit, *gatherer_,
                                                  now_seconds_);
                                }
                            },
                            static_cast<double>(texels_per_unit)});
    }
    for (std::size_t unit = gather_units; unit < queued_gather_units_; ++unit) {
        scheduler_.cancel(WorkKind::IimGather, unit);
    }
    queued_gather_units_ = gather_units;
}

}  // namespace luxel::lighting
