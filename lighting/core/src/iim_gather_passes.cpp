#include "iim_gather_passes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <glm/gtc/constants.hpp>

#include "iim_pass_filter.hpp"
#include "map_support.hpp"

namespace luxel::lighting {

using namespace map_support;

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
    }
}

bool IimGatherPasses::lighting_changed(std::uint32_t s, bool aims_are_current) const {
    const PhotonMap& map = world_.photon_map();
    const SurfacePhotons& photons = map.surface(s);
    const GatherPassState& state = states_[s];
    // An area light's emission changed: its direct light on every surface comes from the
    // gather, so every surface gathers again.
    return relative(deltas_.indirect(map, s), photons.stored_energy.value()) >
               settings_.iim_threshold ||
           state.emission_version != registry_.emission_version() ||
           (state.read_stale_aim && aims_are_current);
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
    return state.in_progress || (ready && (!state.completed_once || changed || refine));
}

double IimGatherPasses::priority(std::uint32_t s, bool current) const {
    const PhotonMap& map = world_.photon_map();
    const MapSurface& mapped = registry_.surface(s);
    const GatherPassState& state = states_[s];
    const RefinementStats& refinement = refinements_[s];
    const double delta = deltas_.indirect(map, s);
    const bool changed = lighting_changed(s, current);
    // Passes in progress first, the furthest along first, so passes finish one after
    // another instead of all crawling together (a pass shows only when complete); then
    // surfaces never gathered; then the largest delta_i / area; refinement last: a
    // refinement pass in progress, then the surfaces with the fewest passes averaged.
    // A change never waits for refinement (a refinement pass of a surface whose light
    // changed is dropped and started afresh by gather()).
    const double done =
        static_cast<double>(state.cursor) / static_cast<double>(mapped.texels.texels.size());
    double rank = delta / safe_area(mapped.texels.area);
    if (state.in_progress && !state.refines) {
        rank = std::numeric_limits<double>::max() / 2.0 * (1.0 + done);
    } else if (!state.completed_once) {
        rank = std::numeric_limits<double>::max() / 4.0;
    } else if (!changed && state.in_progress) {
        rank = -0.5 + 0.25 * done;
    } else if (!changed) {
        rank = -static_cast<double>(refinement.passes_averaged);
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
    state.in_progress = true;
    state.cursor = 0;
    state.irradiance.assign(registry_.surface(surface).texels.texels.size(), glm::vec3(0.0f));
    const bool current = aims_.current();
    state.refines = state.completed_once && !lighting_changed(surface, current) && current &&
                    wants_refinement(surface);
    ++state.started;
    state.emission_version = registry_.emission_version();
    state.aim_rebuilds_at_start = aims_.rebuilds();
    state.read_stale_aim = !current;
    deltas_.consume_indirect(world_.photon_map(), surface);
    ++passes_;
}

std::size_t IimGatherPasses::gather(std::uint32_t surface, std::size_t max_texels,
                                    IrradianceGatherer& gatherer, double now_seconds) {
    const MapSurface& mapped = registry_.surface(surface);
    GatherPassState& state = states_.at(surface);
    if (registry_.page_of(surface) < 0 || mapped.texels.texels.empty() || max_texels == 0) {
        return 0;
    }
    if (state.in_progress && state.refines && lighting_changed(surface, aims_.current())) {
        state.in_progress = false;  // the light changed under a refinement pass
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
    const std::size_t total = mapped.texels.texels.size();
    const std::size_t first = state.cursor;
    const std::size_t count = std::min(max_texels, total - first);
    if (count > 0) {
        std::vector<GatherTexel> all = registry_.world_texels(surface);
        for (GatherTexel& texel : all) {
            texel.pass = state.started;
        }
        const std::span<const GatherTexel> batch(all.data() + first, count);
        gatherer.gather(batch, std::span<glm::vec3>(state.irradiance.data() + first, count));
        state.cursor = first + count;
        texels_gathered_ += count;
        if (state.cursor >= total) {
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

/// A completed pass's values go into the surface's mean (refinement) and a filter starts over
/// them: a tent of radius iim_filter_radius texels over the surface's own texels (final
/// gathering's noise is per texel while indirect light varies slowly, so a small filter removes
/// most of the noise for little bias), noise-aware from the third pass. The filter runs in
/// slices (gather() gives it the budget its call has left), then finish_pass() fades it in.
void IimGatherPasses::begin_filter(std::uint32_t surface) {
    const MapSurface& mapped = registry_.surface(surface);
    GatherPassState& state = states_[surface];
    RefinementStats& refinement = refinements_[surface];
    const std::size_t count = mapped.texels.texels.size();
    const bool refining = state.refines && refinement.passes_averaged > 0 &&
                          refinement.mean.size() == count && refinement.m2.size() == count;
    state.passes_when_done = refining ? refinement.passes_averaged + 1 : 1;
    const std::uint32_t passes = state.passes_when_done;
    // The per-texel mean of the passes (unfiltered) and, for the noise estimate, the sum of
    // squared deviations (Welford's update, in double per step so long runs do not drift).
    // Kept only while more passes may be averaged in.
    const bool keep_mean = refine_ && settings_.refine_passes > 1;
    std::vector<glm::vec3> values(count);
    if (keep_mean) {
        refinement.mean.resize(count);
        refinement.m2.resize(count);
        for (std::size_t i = 0; i < count; ++i) {
            const glm::dvec3 x(sanitized(state.irradiance[i]));
            if (!refining) {
                refinement.mean[i] = glm::vec3(x);
                refinement.m2[i] = glm::vec3(0.0f);
            } else {
                const glm::dvec3 old_mean(refinement.mean[i]);
                const glm::dvec3 mean = old_mean + (x - old_mean) / static_cast<double>(passes);
                refinement.mean[i] = glm::vec3(mean);
                refinement.m2[i] =
                    glm::vec3(glm::dvec3(refinement.m2[i]) + (x - old_mean) * (x - mean));
            }
            values[i] = refinement.mean[i];
        }
    } else {
        refinement.mean = {};
        refinement.m2 = {};
        for (std::size_t i = 0; i < count; ++i) {
            values[i] = sanitized(state.irradiance[i]);
        }
    }
    // With three passes or more each texel knows its noise: the variance of its mean, summed
    // over the channels. The filter then leaves out neighbours whose difference is not
    // explained by the noise (a range weight, as a bilateral filter's, in units of the noise):
    // noise is smoothed, while a real feature such as the focus of light under a glass sphere
    // (one texel, several times its neighbours) keeps its value. Fewer passes: the plain tent.
    const double sigmas = static_cast<double>(settings_.iim_filter_noise_sigmas);
    std::vector<double> noise;
    if (sigmas > 0.0 && passes >= 3 && keep_mean) {
        noise.resize(count);
        const double scale = 1.0 / (static_cast<double>(passes - 1) * static_cast<double>(passes));
        for (std::size_t i = 0; i < count; ++i) {
            const glm::dvec3 m2(refinement.m2[i]);
            noise[i] = (m2.x + m2.y + m2.z) * scale;
        }
    }
    filters_[surface] =
        std::make_unique<IimPassFilter>(mapped.texels.texels, std::move(values), std::move(noise),
                                        settings_.iim_filter_radius, sigmas);
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
    if (aims_.rebuilds() != state.aim_rebuilds_at_start) {
        state.read_stale_aim = true;  // an AIM changed under the pass
    }
    const std::int32_t page_id = registry_.page_of(surface);
    IimPage& page = registry_.iim_pages()[static_cast<std::size_t>(page_id)];
    const auto& texels = mapped.texels.texels;
    const std::vector<glm::vec3>& filtered = filter.filtered();
    for (std::size_t i = 0; i < texels.size() && i < filtered.size(); ++i) {
        const glm::vec3 e = filtered[i];
        const glm::vec3 value = mapped.content == IimContent::Irradiance
                                    ? e
                                    : mapped.albedo * e * glm::one_over_pi<float>();
        page.commit(texels[i].x, texels[i].y, value, now_seconds, settings_.blend_seconds);
    }
    // Fill the padding so bilinear lookups at the border hold.
    const int size = page.current.size;
    for (const SurfaceTexel& texel : texels) {
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
                const int x = texel.x + dx;
                const int y = texel.y + dy;
                if (x < 0 || y < 0 || x >= size || y >= size ||
                    registry_.owner(page_id, x, y) >= 0) {
                    continue;
                }
                page.commit(x, y, page.current.at(texel.x, texel.y), now_seconds,
                            settings_.blend_seconds);
            }
        }
    }
    const glm::ivec4 bounds = filter.bounds();
    const int left = std::max(bounds.x - 1, 0);
    const int top = std::max(bounds.y - 1, 0);
    page.current.mark_changed(
        {left, top, std::min(bounds.z + 2, size) - left, std::min(bounds.w + 2, size) - top});
    refinement.passes_averaged = state.passes_when_done;
    if (refinement.passes_averaged >= settings_.refine_passes) {
        // Done refining: the IIM holds the filtered mean.
        refinement.mean = {};
        refinement.m2 = {};
    }
    state.in_progress = false;
    state.completed_once = true;
    filters_.erase(found);
}

}  // namespace luxel::lighting
