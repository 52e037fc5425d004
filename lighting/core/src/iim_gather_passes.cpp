#include "iim_gather_passes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <glm/gtc/constants.hpp>

#include "iim_padding.hpp"
#include "iim_pass_filter.hpp"
#include "luxel/lighting/core/texel_change_test.hpp"
#include "map_support.hpp"

namespace luxel::lighting {

using namespace map_support;

namespace {

/// A local pass of its own for the texels closer to a change's box than this share of the
/// box's half-diagonal (the marked region reaches out to the whole half-diagonal).
constexpr float kNearReach = 0.5f;

/// A moved object's surfaces go first only when it turned by more than this.
constexpr float kTurnedDegrees = 20.0f;

/// The unit world axes of a surface's transform (its rotation, scale divided out).
glm::mat3 axes_of(const glm::mat4& to_world) {
    glm::mat3 axes(to_world);
    for (int c = 0; c < 3; ++c) {
        const float length = glm::length(axes[c]);
        axes[c] = length > 0.0f ? axes[c] / length : glm::vec3(0.0f);
    }
    return axes;
}

/// The largest angle, in degrees, any axis turned through from `before` to `after`.
float turned_degrees(const glm::mat3& before, const glm::mat3& after) {
    float least_cosine = 1.0f;
    for (int c = 0; c < 3; ++c) {
        least_cosine = std::min(least_cosine, glm::dot(before[c], after[c]));
    }
    return glm::degrees(std::acos(std::clamp(least_cosine, -1.0f, 1.0f)));
}

/// How close `position` lies to a change's box, in [0, 1]: 1 inside it, falling to 0 at the
/// box's half-diagonal from it, the edge of the region a change marks. An object's effect on
/// the light around it falls off with distance (the floor in front of a doorway a door has
/// left, the footprint of a crate), so the closest texels are gathered first.
float reach_of(const glm::vec3& position, const GeometryChange& box) {
    const float half_diagonal = 0.5f * glm::length(box.max - box.min);
    const glm::vec3 outside = glm::max(glm::max(box.min - position, position - box.max), 0.0f);
    const float distance = glm::length(outside);
    if (!(half_diagonal > 0.0f)) {
        return distance > 0.0f ? 0.0f : 1.0f;
    }
    return std::clamp(1.0f - distance / half_diagonal, 0.0f, 1.0f);
}

}  // namespace

IimGatherPasses::IimGatherPasses(MapRegistry& registry, const AimRebuilder& aims,
                                 const PhotonWorld& world, SurfaceDeltas& deltas,
                                 const IlluminationSettings& settings)
    : registry_(registry), aims_(aims), world_(world), deltas_(deltas), settings_(settings) {}

IimGatherPasses::~IimGatherPasses() = default;

void IimGatherPasses::sync() {
    const std::span<const MapSurface> surfaces = registry_.surfaces();
    for (std::size_t s = states_.size(); s < surfaces.size(); ++s) {
        GatherPassState state;
        state.cursor = surfaces[s].texels.texels.size();  // no pass in progress
        states_.push_back(std::move(state));
        refinements_.emplace_back();
        AxisBox box;
        for (const SurfaceTexel& texel : surfaces[s].texels.texels) {
            box.add(texel.position);
        }
        local_boxes_.push_back(box);
        LocalReach reach;
        reach.axes = axes_of(surfaces[s].to_world);
        reach_.push_back(std::move(reach));
    }
    const auto seams = registry_.seams();
    if (settings_.stitch_seams) {
        for (; seam_objects_ < seams.size(); ++seam_objects_) {
            seams_.add_object(seams[seam_objects_], registry_.iim_pages());
        }
    }
    update_seen();
    if (settings_.local_passes) {
        // Texels next to a change are gathered again at once, reading the AIMs as they are;
        // where the AIMs there were marked for a local rebuild (what they decided from the old
        // geometry: the floor under a crate's new place found open and lit), the texels are
        // gathered again once it is done.
        const std::uint64_t through = aims_.local_current_through();
        after_local_aims_.resize(states_.size());
        for (std::uint32_t surface = 0; surface < after_local_aims_.size(); ++surface) {
            AfterLocalAims& waiting = after_local_aims_[surface];
            if (!waiting.texels.empty() && waiting.serial <= through) {
                mark_changed(surface, waiting.texels);
                for (const std::uint32_t i : waiting.texels) {
                    waiting.flagged[i] = 0;
                }
                waiting.texels.clear();
            }
        }
        for (const MapRegistry::NearbyChange& change : registry_.nearby_changes()) {
            mark_changed(change.surface, change.texels);
            note_reach(change);
            if (aims_.marked_in_last_sync()) {
                AfterLocalAims& waiting = after_local_aims_.at(change.surface);
                if (waiting.texels.empty()) {
                    waiting.serial = aims_.change_serial();
                }
                waiting.flagged.resize(registry_.surface(change.surface).texels.texels.size(), 0);
                for (const std::uint32_t i : change.texels) {
                    if (i < waiting.flagged.size() && waiting.flagged[i] == 0) {
                        waiting.flagged[i] = 1;
                        waiting.texels.push_back(i);
                    }
                }
            }
        }
    }
    const bool any_stale = std::any_of(states_.begin(), states_.end(), [](const auto& state) {
        return !state.stale_local_texels.empty();
    });
    if (any_stale && aims_.current()) {
        for (GatherPassState& state : states_) {
            for (const std::uint32_t i : state.stale_local_texels) {
                if (i < state.changed_texels.size() && state.changed_texels[i] == 0) {
                    state.changed_texels[i] = 1;
                    ++state.changed_count;
                }
            }
            state.stale_local_texels.clear();
        }
    }
}

void IimGatherPasses::set_view(std::optional<ViewHint> view) {
    view_ = view;
    update_seen();
}

void IimGatherPasses::update_seen() {
    const std::span<const MapSurface> surfaces = registry_.surfaces();
    const std::size_t count = std::min(local_boxes_.size(), surfaces.size());
    seen_.assign(count, 1);
    if (!view_) {
        return;
    }
    for (std::size_t s = 0; s < count; ++s) {
        const AxisBox box = transformed(local_boxes_[s], surfaces[s].to_world);
        seen_[s] = in_view(box, view_->view_projection) ? 1 : 0;
    }
}

void IimGatherPasses::mark_changed(std::uint32_t surface, std::span<const std::uint32_t> texels) {
    GatherPassState& state = states_.at(surface);
    state.changed_texels.resize(registry_.surface(surface).texels.texels.size(), 0);
    for (const std::uint32_t i : texels) {
        if (i < state.changed_texels.size() && state.changed_texels[i] == 0) {
            state.changed_texels[i] = 1;
            ++state.changed_count;
        }
    }
}

void IimGatherPasses::note_reach(const MapRegistry::NearbyChange& change) {
    if (change.texels.empty()) {
        return;
    }
    LocalReach& local = reach_.at(change.surface);  // one per state, added with it in sync()
    const MapSurface& mapped = registry_.surface(change.surface);
    const std::size_t total = mapped.texels.texels.size();
    local.reach.resize(total, 0.0f);
    const bool moved = registry_.moved_in_last_sync(change.surface);
    local.moved = local.moved || moved;
    local.turned = local.turned ||
                   (moved && turned_degrees(local.axes, axes_of(mapped.to_world)) > kTurnedDegrees);
    // Runs for every change next to a surface, each frame an object moves: positions only,
    // placed here (MapRegistry::world_texels would also turn every normal).
    for (const std::uint32_t i : change.texels) {
        if (i >= total) {
            continue;
        }
        const float reach =
            moved ? 1.0f
                  : reach_of(glm::vec3(mapped.to_world *
                                       glm::vec4(mapped.texels.texels[i].position, 1.0f)),
                             change.box);
        const bool was_near = local.reach[i] > kNearReach;
        local.reach[i] = std::max(local.reach[i], reach);
        if (!was_near && local.reach[i] > kNearReach) {
            ++local.near;
        }
    }
}

std::size_t IimGatherPasses::pass_size(std::uint32_t surface) const {
    const GatherPassState& state = states_[surface];
    return state.subset.empty() ? registry_.surface(surface).texels.texels.size()
                                : state.subset.size();
}

bool IimGatherPasses::lighting_changed(std::uint32_t s, bool aims_are_current) const {
    const PhotonMap& map = world_.photon_map();
    const SurfacePhotons& photons = map.surface(s);
    const GatherPassState& state = states_[s];
    // An area light's emission changed: its direct light on every surface comes from the
    // gather, so every surface gathers again. Geometry changed near some texels and no means
    // are kept to re-gather only those: the whole surface gathers again.
    return relative(deltas_.indirect(map, s), photons.stored_energy.value()) >
               settings_.iim_threshold ||
           state.emission_version != registry_.emission_version() ||
           (state.read_stale_aim && aims_are_current) || (state.changed_count > 0 && !keeps_mean());
}

double IimGatherPasses::refined_share() const {
    const std::uint32_t wanted = keeps_mean() ? settings_.refine_passes : 1u;
    double done = 0.0;
    double total = 0.0;
    for (std::uint32_t s = 0; s < states_.size(); ++s) {
        const std::size_t texels =
            registry_.live(s) ? registry_.surface(s).texels.texels.size() : 0;
        const RefinementStats& refinement = refinements_[s];
        if (refinement.texel_passes.size() == texels && texels > 0) {
            for (const std::uint32_t passes : refinement.texel_passes) {
                done += static_cast<double>(std::min(passes, wanted));
            }
        } else if (states_[s].completed_once) {
            done += static_cast<double>(texels);
        }
        total += static_cast<double>(texels) * wanted;
    }
    return total > 0.0 ? std::min(done / total, 1.0) : 1.0;
}

bool IimGatherPasses::wants_refinement(std::uint32_t s) const {
    const GatherPassState& state = states_[s];
    const RefinementStats& refinement = refinements_[s];
    return refine_ && state.completed_once && !state.read_stale_aim &&
           refinement.passes_averaged < settings_.refine_passes;
}

bool IimGatherPasses::wants_gather(std::uint32_t s, bool ready, bool current) const {
    const GatherPassState& state = states_[s];
    if (!registry_.live(s) || s >= world_.photon_map().surface_count()) {
        return false;
    }
    const bool changed = lighting_changed(s, current);
    // Refinement only over current AIMs: an average of passes over different AIMs would mix old
    // light into new.
    const bool refine = !changed && current && wants_refinement(s);
    const bool local = state.changed_count > 0;
    return state.in_progress || (ready && (!state.completed_once || changed || local || refine));
}

/// How far refinement of a surface out of view sorts below refinement of one in view (more
/// passes than a surface ever averages).
constexpr double kUnseenRefinement = 1e6;

double IimGatherPasses::priority(std::uint32_t s, bool current) const {
    const PhotonMap& map = world_.photon_map();
    const MapSurface& mapped = registry_.surface(s);
    const GatherPassState& state = states_[s];
    const RefinementStats& refinement = refinements_[s];
    const double delta = deltas_.indirect(map, s);
    const bool changed = lighting_changed(s, current);
    // Local passes first (texels next to a geometry change: small, and what a player sees go
    // wrong, such as the dark footprint of a crate that slid away), the one in progress first;
    // then other passes in progress, the furthest along first, so passes finish one after
    // another instead of all crawling together (a pass shows only when complete); then
    // surfaces never gathered; then the largest delta_i / area, the surfaces in the player's
    // view first (set_view); refinement last: a refinement pass in progress, then the surfaces
    // with the fewest passes averaged, again those in view first. A change never waits for
    // refinement (a refinement pass of a surface whose light or geometry changed is dropped by
    // gather()). A local pass used to wait behind a full pass in progress: a wall's thousands of
    // texels, ten frames at 4 ms, with the crate's footprint dark all the while.
    constexpr double kTop = std::numeric_limits<double>::max();
    const double done = static_cast<double>(state.cursor) /
                        static_cast<double>(std::max<std::size_t>(pass_size(s), 1));
    double rank = delta / safe_area(mapped.texels.area);
    if (state.in_progress && state.local) {
        rank = kTop / 2.0 * (1.0 + done);
    } else if (state.completed_once && state.changed_count > 0 &&
               !(state.in_progress && !state.refines)) {
        // (A refinement pass in progress is dropped for it.) Among the local passes waiting
        // (docs/METHOD.md §6.8): a turned object's own surfaces first (two-rooms' door, turned
        // 60 degrees, was the level's worst region for 60 frames at 4 ms while the walls around
        // the doorway, numbered before it, went first); then texels close to a change
        // (note_reach: the floor a crate left); then a slid object's own surfaces, which carry
        // their light with them (their maps are looked up by light-map UV) where the floor it
        // left does not (cornell's cube went before its footprint and the footprint showed 4
        // frames later); then the rest; within each, those in view and the smaller first.
        const LocalReach* reach = s < reach_.size() ? &reach_[s] : nullptr;
        const bool moved = reach != nullptr && reach->moved;
        const bool turned = moved && reach->turned;
        const bool near = reach != nullptr && !moved && reach->near > 0;
        const double size = static_cast<double>(near ? reach->near : state.changed_count);
        const double tier = turned ? 0.5 : near ? 0.3 : moved ? 0.15 : 0.0;
        rank =
            kTop / 4.0 * (1.0 + tier + 0.06 * (seen(s) ? 1.0 : 0.0) + 0.06 / (1.0 + size / 256.0));
        if (!settings_.order_local_passes) {
            rank = kTop / 4.0;
        }
    } else if (state.in_progress && !state.refines) {
        rank = kTop / 16.0 * (1.0 + done);
    } else if (!state.completed_once) {
        rank = kTop / 32.0;
    } else if (!changed && state.in_progress) {
        rank = -0.5 + 0.25 * done - (seen(s) ? 0.0 : kUnseenRefinement);
    } else if (!changed) {
        rank =
            -static_cast<double>(refinement.passes_averaged) - (seen(s) ? 0.0 : kUnseenRefinement);
    } else if (view_ && seen(s)) {
        // Above every unseen change, below the surfaces never gathered: [max/128, max/64), in
        // the order of delta_i / area.
        const double r = std::max(rank, 0.0);
        rank = kTop / 128.0 * (1.0 + r / (1.0 + r));
    }
    return rank;
}

std::vector<MapRequest> IimGatherPasses::requests() const {
    std::vector<MapRequest> requests;
    const bool ready = aims_.ready();
    const bool current = aims_.current();
    for (std::uint32_t s = 0; s < states_.size(); ++s) {
        if (wants_gather(s, ready, current)) {
            requests.push_back({s, priority(s, current)});
        }
    }
    std::stable_sort(
        requests.begin(), requests.end(),
        [](const MapRequest& l, const MapRequest& r) { return l.priority > r.priority; });
    return requests;
}

std::optional<std::uint32_t> IimGatherPasses::next_surface() const {
    const bool ready = aims_.ready();
    const bool current = aims_.current();
    std::optional<std::uint32_t> best;
    double best_priority = 0.0;
    for (std::uint32_t s = 0; s < states_.size(); ++s) {
        if (wants_gather(s, ready, current)) {
            // Strictly greater: the first of equals, as requests()'s stable sort puts it.
            const double candidate = priority(s, current);
            if (!best || candidate > best_priority) {
                best = s;
                best_priority = candidate;
            }
        }
    }
    return best;
}

void IimGatherPasses::start_pass(std::uint32_t surface) {
    // Changes from now on need another pass; those before are what this pass sees.
    GatherPassState& state = states_[surface];
    const RefinementStats& refinement = refinements_[surface];
    const std::size_t total = registry_.surface(surface).texels.texels.size();
    const bool current = aims_.current();
    const bool changed = lighting_changed(surface, current);
    state.in_progress = true;
    state.cursor = 0;
    state.irradiance.assign(total, glm::vec3(0.0f));
    state.subset.clear();
    state.changed_texels.resize(total, 0);
    // A local pass even when the surface's light changed too (the photons of the groups the
    // moved object's paths crossed, retraced at once): the texels next to the object first,
    // then the full pass that the photons' change asks for.
    state.local = state.completed_once && state.changed_count > 0 && keeps_mean() &&
                  refinement.texel_passes.size() == total;
    state.refines =
        !state.local && state.completed_once && !changed && current && wants_refinement(surface);
    LocalReach* reach = surface < reach_.size() ? &reach_[surface] : nullptr;
    if (state.local) {
        // The texels close to a change's box first, in a pass of their own (the doorway's floor
        // once a door has swung away from it, a crate's footprint); the rest of the marked
        // texels in the next. A moved object's own texels all at once.
        const bool near_only = settings_.order_local_passes && reach != nullptr && !reach->moved &&
                               reach->near > 0 && reach->near < state.changed_count &&
                               reach->reach.size() == total;
        for (std::uint32_t i = 0; i < total; ++i) {
            if (state.changed_texels[i] != 0 && (!near_only || reach->reach[i] > kNearReach)) {
                state.subset.push_back(i);
            }
        }
    } else if (state.refines && refinement.texel_passes.size() == total) {
        // Only the texels still short of refine_passes (after a local pass, the few it
        // restarted); all of them when they are level, as every pass but local ones leaves them.
        for (std::uint32_t i = 0; i < total; ++i) {
            if (refinement.texel_passes[i] < settings_.refine_passes) {
                state.subset.push_back(i);
            }
        }
        if (state.subset.size() == total) {
            state.subset.clear();
        }
    }
    if (state.local) {
        // This pass gathers its changed texels again; the others stay marked.
        for (const std::uint32_t i : state.subset) {
            state.changed_texels[i] = 0;
            if (reach != nullptr && i < reach->reach.size()) {
                reach->near -= reach->reach[i] > kNearReach ? 1 : 0;
                reach->reach[i] = 0.0f;
            }
        }
        state.changed_count -= std::min(state.changed_count, state.subset.size());
        if (reach != nullptr && reach->moved) {
            reach->moved = false;  // the pass takes every texel of a moved surface
            reach->turned = false;
            reach->axes = axes_of(registry_.surface(surface).to_world);
        }
    } else if (!state.refines) {
        // This pass gathers every texel again, the changed ones among them.
        std::fill(state.changed_texels.begin(), state.changed_texels.end(), 0);
        state.changed_count = 0;
        if (reach != nullptr) {
            *reach = LocalReach{};
            reach->axes = axes_of(registry_.surface(surface).to_world);
        }
    }
    ++state.started;
    ++passes_;
    state.aim_rebuilds_at_start = aims_.rebuilds();
    if (state.local) {
        // The rest of the surface keeps its passes: the photons' change (delta_i, below the
        // threshold or a local pass would not run) and the AIM's state stay for the next full
        // pass to consume; only this pass's texels remember a stale AIM.
        state.local_read_stale_aim = !current;
        return;
    }
    state.emission_version = registry_.emission_version();
    state.read_stale_aim = !current;
    deltas_.consume_indirect(world_.photon_map(), surface);
}

std::size_t IimGatherPasses::gather(std::uint32_t surface, std::size_t max_texels,
                                    IrradianceGatherer& gatherer, double now_seconds) {
    const MapSurface& mapped = registry_.surface(surface);
    GatherPassState& state = states_.at(surface);
    if (registry_.page_of(surface) < 0 || mapped.texels.texels.empty() || max_texels == 0) {
        return 0;
    }
    if (state.in_progress && state.refines &&
        (state.changed_count > 0 || lighting_changed(surface, aims_.current()))) {
        state.in_progress = false;  // the light or the geometry changed under a refinement pass
        filters_.erase(surface);
    }
    if (!state.in_progress && !aims_.ready()) {
        // Checked again here, not only when the request was made: photons stored since (by
        // retraces earlier in the same frame) may have made a surface lit without an AIM.
        return 0;
    }
    if (!state.in_progress) {
        start_pass(surface);
    }
    const std::size_t size = pass_size(surface);
    const std::size_t first = state.cursor;
    const std::size_t count = std::min(max_texels, size - first);
    if (count > 0) {
        // Only this call's texels are placed in the world (a unit is a few texels of a surface
        // that may hold thousands).
        std::vector<std::uint32_t> indices(count);
        for (std::size_t k = 0; k < count; ++k) {
            indices[k] = state.subset.empty() ? static_cast<std::uint32_t>(first + k)
                                              : state.subset[first + k];
        }
        std::vector<GatherTexel> batch = registry_.world_texels(surface, indices);
        // A texel under an object's edge is gathered at the open point beside the object
        // (ContactTexels), not at its centre under it.
        const std::span<const TexelCover> cover = aims_.contacts().cover(surface);
        const std::span<const glm::vec3> points = aims_.contacts().gather_points(surface);
        const bool contacts =
            settings_.contact_texels && cover.size() == mapped.texels.texels.size();
        for (std::size_t k = 0; k < count; ++k) {
            batch[k].pass = state.started;
            if (contacts && cover[indices[k]] == TexelCover::Edge) {
                batch[k].position =
                    glm::vec3(mapped.to_world * glm::vec4(points[indices[k]], 1.0f));
            }
        }
        std::vector<glm::vec3> out(count);
        gatherer.gather(batch, out);
        for (std::size_t k = 0; k < count; ++k) {
            state.irradiance[indices[k]] = out[k];
        }
        state.cursor = first + count;
        texels_gathered_ += count;
        if (state.cursor >= size) {
            begin_filter(surface);
        }
    }
    // What is left of this call's texels goes to the filter, at kFilteredPerGathered texels a
    // texel, so a call that gathers the last texels of a large surface does not also filter all
    // of it.
    if (const auto filter = filters_.find(surface); filter != filters_.end()) {
        filter->second->run((max_texels - count) * kFilteredPerGathered);
        if (filter->second->done()) {
            finish_pass(surface, now_seconds);
        }
    }
    return count;
}

std::vector<glm::vec3> IimGatherPasses::fold_pass(std::uint32_t surface) {
    GatherPassState& state = states_[surface];
    RefinementStats& refinement = refinements_[surface];
    const std::size_t count = registry_.surface(surface).texels.texels.size();
    std::vector<glm::vec3> values(count);
    if (!keeps_mean()) {
        refinement = {};
        for (std::size_t i = 0; i < count; ++i) {
            values[i] = sanitized(state.irradiance[i]);
        }
        state.passes_when_done = 1;
        return values;
    }
    // The per-texel mean of the passes (unfiltered) and, for the noise estimate, the sum of
    // squared deviations (Welford's update, in double per step so long runs do not drift), each
    // texel with its own count: a local pass restarts the texels it gathered, and refinement
    // passes then bring those back up while the rest keep theirs. Kept while refinement is on
    // (two vec3 and a count per texel), since a local pass needs the other texels' means.
    const bool have_means = refinement.mean.size() == count && refinement.m2.size() == count &&
                            refinement.texel_passes.size() == count;
    const bool full_pass = !state.refines && !state.local;
    // A full pass (the photons' change, a stale AIM) keeps the texels it shows unchanged
    // (texel_change_test.hpp): empty, every texel restarts.
    std::vector<std::uint8_t> changed;
    if (have_means && full_pass && settings_.change_test_sigmas > 0.0) {
        std::vector<glm::vec3> pass(count);
        for (std::size_t i = 0; i < count; ++i) {
            pass[i] = sanitized(state.irradiance[i]);
        }
        changed = texels_changed(registry_.surface(surface).texels.texels, pass, refinement,
                                 settings_.change_test_radius, settings_.change_test_sigmas);
    }
    const bool restart_all = !have_means || (full_pass && changed.empty());
    if (restart_all) {
        refinement.mean.assign(count, glm::vec3(0.0f));
        refinement.m2.assign(count, glm::vec3(0.0f));
        refinement.texel_passes.assign(count, 0);
    }
    if (refinement.relative_pass_variance.size() != count) {
        refinement.relative_pass_variance.assign(count, -1.0f);
    }
    const auto fold = [&](std::size_t i) {
        const glm::dvec3 x(sanitized(state.irradiance[i]));
        std::uint32_t& n = refinement.texel_passes[i];
        const bool keep = state.refines || (!changed.empty() && changed[i] == 0);
        if (!keep || n == 0) {
            n = 1;
            refinement.mean[i] = glm::vec3(x);
            refinement.m2[i] = glm::vec3(0.0f);
            return;
        }
        texels_kept_ += state.refines ? 0 : 1;
        n += 1;
        const glm::dvec3 old_mean(refinement.mean[i]);
        const glm::dvec3 mean = old_mean + (x - old_mean) / static_cast<double>(n);
        refinement.mean[i] = glm::vec3(mean);
        const glm::dvec3 m2 = glm::dvec3(refinement.m2[i]) + (x - old_mean) * (x - mean);
        refinement.m2[i] = glm::vec3(m2);
        const double mean_squared = glm::dot(mean, mean);
        if (n >= 3 && mean_squared > 0.0) {
            const double pass_variance = (m2.x + m2.y + m2.z) / static_cast<double>(n - 1);
            refinement.relative_pass_variance[i] =
                static_cast<float>(std::min(pass_variance / mean_squared, 1e30));
        }
    };
    if (state.subset.empty() || restart_all) {
        for (std::size_t i = 0; i < count; ++i) {
            fold(i);
        }
    } else {
        for (const std::uint32_t i : state.subset) {
            fold(i);
        }
    }
    std::uint32_t fewest = std::numeric_limits<std::uint32_t>::max();
    for (std::size_t i = 0; i < count; ++i) {
        values[i] = refinement.mean[i];
        fewest = std::min(fewest, refinement.texel_passes[i]);
    }
    state.passes_when_done = count > 0 ? fewest : 0;
    return values;
}

/// The variance of texel i's mean, summed over the channels; infinity where it is unknown. With
/// three passes or more it is measured (m2 / ((n - 1) n)); with fewer, the relative variance of
/// one pass measured before the texel last restarted, scaled by its new mean and divided by
/// its passes; a texel never measured, or one dark then, has none.
double IimGatherPasses::texel_noise(const RefinementStats& refinement, std::size_t i) {
    const std::uint32_t n = refinement.texel_passes[i];
    if (n >= 3) {
        const glm::dvec3 m2(refinement.m2[i]);
        return (m2.x + m2.y + m2.z) / (static_cast<double>(n - 1) * static_cast<double>(n));
    }
    const double relative = refinement.relative_pass_variance[i];
    if (n == 0 || !(relative >= 0.0)) {
        return std::numeric_limits<double>::infinity();
    }
    const glm::dvec3 mean(refinement.mean[i]);
    return relative * glm::dot(mean, mean) / static_cast<double>(n);
}

/// A completed pass's values go into the texels' means (refinement) and a filter starts over
/// them: a tent of radius iim_filter_radius texels over the surface's own texels (final
/// gathering's noise is per texel while indirect light varies slowly, so a small filter removes
/// most of the noise for little bias), noise-aware where a texel knows its noise. The
/// filter runs in slices (gather() gives it the budget its call has left), then finish_pass()
/// fades it in.
void IimGatherPasses::begin_filter(std::uint32_t surface) {
    const MapSurface& mapped = registry_.surface(surface);
    GatherPassState& state = states_[surface];
    const RefinementStats& refinement = refinements_[surface];
    std::vector<glm::vec3> values = fold_pass(surface);
    const std::size_t count = values.size();
    // With three passes or more a texel knows its noise: the variance of its mean, summed over
    // the channels. The filter then leaves out neighbours whose difference is not explained by
    // the noise (a range weight, as a bilateral filter's, in units of the noise): noise is
    // smoothed, while a real feature such as the focus of light under a glass sphere (one
    // texel, several times its neighbours) keeps its value. A texel with fewer passes (all of
    // them early on; after a local pass, the ones it restarted) has no estimate: an infinite
    // variance, so its pairs weigh as in the plain tent, unless it measured its noise before
    // it restarted (texel_noise). No texel with a known noise: the plain tent.
    const double sigmas = static_cast<double>(settings_.iim_filter_noise_sigmas);
    std::vector<double> noise;
    const bool stats_whole = refinement.texel_passes.size() == count &&
                             refinement.relative_pass_variance.size() == count;
    if (sigmas > 0.0 && keeps_mean() && stats_whole) {
        noise.resize(count);
        bool any_known = false;
        for (std::size_t i = 0; i < count; ++i) {
            noise[i] = texel_noise(refinement, i);
            any_known = any_known || std::isfinite(noise[i]);
        }
        if (!any_known) {
            noise.clear();
        }
    }
    auto filter =
        std::make_unique<IimPassFilter>(mapped.texels.texels, std::move(values), std::move(noise),
                                        settings_.iim_filter_radius, sigmas);
    if (settings_.contact_texels) {
        filter->leave_out_enclosed(aims_.contacts().cover(surface));
    }
    if (state.local) {
        filter->restrict_to(state.subset);
    }
    filters_[surface] = std::move(filter);
    state.irradiance.clear();
    state.irradiance.shrink_to_fit();
}

void IimGatherPasses::finish_pass(std::uint32_t surface, double now_seconds) {
    const MapSurface& mapped = registry_.surface(surface);
    GatherPassState& state = states_[surface];
    RefinementStats& refinement = refinements_[surface];
    const auto found = filters_.find(surface);
    if (found == filters_.end()) {
        return;
    }
    const IimPassFilter& filter = *found->second;
    const bool aim_changed = aims_.rebuilds() != state.aim_rebuilds_at_start;
    if (state.local && (state.local_read_stale_aim || aim_changed)) {
        // Kept until every AIM is current, which near objects that move every frame may take
        // long: each texel once, so the list never outgrows the surface.
        std::vector<std::uint32_t>& stale = state.stale_local_texels;
        stale.insert(stale.end(), state.subset.begin(), state.subset.end());
        std::sort(stale.begin(), stale.end());
        stale.erase(std::unique(stale.begin(), stale.end()), stale.end());
    } else if (!state.local && aim_changed) {
        state.read_stale_aim = true;  // an AIM changed under the pass
    }
    const std::int32_t page_id = registry_.page_of(surface);
    IimPage& page = registry_.iim_pages()[static_cast<std::size_t>(page_id)];
    const auto& texels = mapped.texels.texels;
    const std::vector<glm::vec3>& filtered = filter.filtered();
    // Texels a local pass re-gathered because geometry moved next to them fade in over the
    // short change blend: their old value is wrong (a crate's dark footprint), and a player
    // should see the floor lit within frames, not half a second later.
    std::vector<float> fades(texels.size(), static_cast<float>(settings_.blend_seconds));
    if (state.local) {
        for (const std::uint32_t i : state.subset) {
            if (i < fades.size()) {
                fades[i] = static_cast<float>(settings_.change_blend_seconds);
            }
        }
    }
    // The filter's targets: every texel, or after a local pass the ones whose value moved.
    for (const std::uint32_t i : filter.targets()) {
        if (i >= texels.size() || i >= filtered.size()) {
            continue;
        }
        const glm::vec3 e = filtered[i];
        const glm::vec3 value = mapped.content == IimContent::Irradiance
                                    ? e
                                    : mapped.albedo * e * glm::one_over_pi<float>();
        page.commit(texels[i].x, texels[i].y, value, now_seconds, fades[i]);
    }
    fill_padding(registry_, page_id, page, texels, filter.targets(), fades, now_seconds);
    const glm::ivec4 bounds = filter.bounds();
    if (bounds.z >= bounds.x) {
        const int size = page.current.size;
        const int left = std::max(bounds.x - kPaddingRings, 0);
        const int top = std::max(bounds.y - kPaddingRings, 0);
        page.current.mark_changed({left, top, std::min(bounds.z + 1 + kPaddingRings, size) - left,
                                   std::min(bounds.w + 1 + kPaddingRings, size) - top});
    }
    // The seams after the padding: the stitcher reads what the bilinear lookups read.
    seams_.stitch(surface, registry_.iim_pages(), now_seconds, settings_.blend_seconds);
    // Done refining or not, the means stay (fold_pass says why).
    refinement.passes_averaged = state.passes_when_done;
    state.in_progress = false;
    state.completed_once = true;
    filters_.erase(found);
}

}  // namespace luxel::lighting
