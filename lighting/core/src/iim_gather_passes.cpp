#include "luxel/lighting/core/illumination_maps.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <glm/gtc/constants.hpp>

#include "iim_pass_filter.hpp"
#include "map_support.hpp"

// IlluminationMaps, part 3 of 3: the IIM's gather passes (docs/METHOD.md §6): which surfaces
// gather, a pass in slices, refinement, and the filter and fade-in of a completed pass.
namespace luxel::lighting {

using namespace map_support;

bool IlluminationMaps::lighting_changed(std::uint32_t s, bool aims_are_current) const {
    const PhotonMap& map = world_.photon_map();
    const SurfacePhotons& photons = map.surface(s);
    const MapSurface& mapped = surfaces_[s];
    // An area light's emission changed: its direct light on every surface comes from the
    // gather, so every surface gathers again.
    return relative(deltas_.indirect(map, s), photons.stored_energy.value()) >
               settings_.iim_threshold ||
           mapped.gather.emission_version != emission_version_ ||
           (mapped.gather.read_stale_aim && aims_are_current);
}

bool IlluminationMaps::wants_refinement(std::uint32_t s) const {
    const MapSurface& mapped = surfaces_[s];
    return refine_ && mapped.gather.completed_once && !mapped.gather.read_stale_aim &&
           mapped.refinement.passes_averaged < settings_.refine_passes;
}

bool IlluminationMaps::wants_gather(std::uint32_t s, bool ready, bool current) const {
    const MapSurface& mapped = surfaces_[s];
    if (mapped.texels.texels.empty() || !registry_.valid(mapped.entity) ||
        s >= world_.photon_map().surface_count()) {
        return false;
    }
    const bool changed = lighting_changed(s, current);
    // Refinement only over current AIMs: an average of passes over different AIMs would mix old
    // light into new.
    const bool refine = !changed && current && wants_refinement(s);
    return mapped.gather.in_progress ||
           (ready && (!mapped.gather.completed_once || changed || refine));
}

double IlluminationMaps::gather_priority(std::uint32_t s, bool current) const {
    const PhotonMap& map = world_.photon_map();
    const MapSurface& mapped = surfaces_[s];
    const double delta = deltas_.indirect(map, s);
    const bool changed = lighting_changed(s, current);
    // Passes in progress first, the furthest along first, so passes finish one after
    // another instead of all crawling together (a pass shows only when complete); then
    // surfaces never gathered; then the largest delta_i / area; refinement last: a
    // refinement pass in progress, then the surfaces with the fewest passes averaged.
    // A change never waits for refinement (a refinement pass of a surface whose light
    // changed is dropped and started afresh by gather()).
    const double done = static_cast<double>(mapped.gather.cursor) /
                        static_cast<double>(mapped.texels.texels.size());
    double priority = delta / safe_area(mapped.texels.area);
    if (mapped.gather.in_progress && !mapped.gather.refines) {
        priority = std::numeric_limits<double>::max() / 2.0 * (1.0 + done);
    } else if (!mapped.gather.completed_once) {
        priority = std::numeric_limits<double>::max() / 4.0;
    } else if (!changed && mapped.gather.in_progress) {
        priority = -0.5 + 0.25 * done;
    } else if (!changed) {
        priority = -static_cast<double>(mapped.refinement.passes_averaged);
    }
    return priority;
}

std::vector<MapRequest> IlluminationMaps::gather_requests() const {
    std::vector<MapRequest> requests;
    const bool ready = aims_ready();
    const bool current = aims_current();
    for (std::uint32_t s = 0; s < surfaces_.size(); ++s) {
        if (wants_gather(s, ready, current)) {
            requests.push_back({s, gather_priority(s, current)});
        }
    }
    std::stable_sort(
        requests.begin(), requests.end(),
        [](const MapRequest& l, const MapRequest& r) { return l.priority > r.priority; });
    return requests;
}

std::optional<std::uint32_t> IlluminationMaps::next_gather_surface() const {
    const bool ready = aims_ready();
    const bool current = aims_current();
    std::optional<std::uint32_t> best;
    double best_priority = 0.0;
    for (std::uint32_t s = 0; s < surfaces_.size(); ++s) {
        if (wants_gather(s, ready, current)) {
            // Strictly greater: the first of equals, as gather_requests()'s stable sort puts it.
            const double priority = gather_priority(s, current);
            if (!best || priority > best_priority) {
                best = s;
                best_priority = priority;
            }
        }
    }
    return best;
}

std::size_t IlluminationMaps::gather(std::uint32_t surface, std::size_t max_texels,
                                     IrradianceGatherer& gatherer, double now_seconds) {
    MapSurface& mapped = surfaces_.at(surface);
    const std::int32_t page_id = aim_.surface_page.at(surface);
    if (page_id < 0 || mapped.texels.texels.empty() || max_texels == 0) {
        return 0;
    }
    if (mapped.gather.in_progress && mapped.gather.refines &&
        lighting_changed(surface, aims_current())) {
        mapped.gather.in_progress = false;  // the light changed under a refinement pass
        filters_.erase(surface);
    }
    if (!mapped.gather.in_progress && !aims_ready()) {
        // Checked again here, not only when the request was made: photons stored since (by
        // retraces earlier in the same frame) may have made a surface lit without an AIM.
        return 0;
    }
    const std::size_t total = mapped.texels.texels.size();
    if (!mapped.gather.in_progress) {
        // Changes from now on need another pass; those before are what this pass sees.
        mapped.gather.in_progress = true;
        mapped.gather.cursor = 0;
        mapped.gather.irradiance.assign(total, glm::vec3(0.0f));
        const bool current = aims_current();
        mapped.gather.refines = mapped.gather.completed_once &&
                                !lighting_changed(surface, current) && current &&
                                wants_refinement(surface);
        ++mapped.gather.started;
        mapped.gather.emission_version = emission_version_;
        mapped.gather.aim_rebuilds_at_start = counters_.aim_rebuilds;
        mapped.gather.read_stale_aim = !current;
        deltas_.consume_indirect(world_.photon_map(), surface);
        ++counters_.gather_passes;
    }
    const std::size_t first = mapped.gather.cursor;
    const std::size_t count = std::min(max_texels, total - first);
    if (count > 0) {
        std::vector<GatherTexel> all = world_texels(surface);
        for (GatherTexel& texel : all) {
            texel.pass = mapped.gather.started;
        }
        const std::span<const GatherTexel> batch(all.data() + first, count);
        gatherer.gather(batch,
                        std::span<glm::vec3>(mapped.gather.irradiance.data() + first, count));
        mapped.gather.cursor = first + count;
        counters_.texels_gathered += count;
        if (mapped.gather.cursor >= total) {
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
void IlluminationMaps::begin_filter(std::uint32_t surface) {
    MapSurface& mapped = surfaces_[surface];
    const std::size_t count = mapped.texels.texels.size();
    const bool refining = mapped.gather.refines && mapped.refinement.passes_averaged > 0 &&
                          mapped.refinement.mean.size() == count &&
                          mapped.refinement.m2.size() == count;
    mapped.gather.passes_when_done = refining ? mapped.refinement.passes_averaged + 1 : 1;
    const std::uint32_t passes = mapped.gather.passes_when_done;
    // The per-texel mean of the passes (unfiltered) and, for the noise estimate, the sum of
    // squared deviations (Welford's update, in double per step so long runs do not drift).
    // Kept only while more passes may be averaged in.
    const bool keep_mean = refine_ && settings_.refine_passes > 1;
    std::vector<glm::vec3> values(count);
    if (keep_mean) {
        mapped.refinement.mean.resize(count);
        mapped.refinement.m2.resize(count);
        for (std::size_t i = 0; i < count; ++i) {
            const glm::dvec3 x(sanitized(mapped.gather.irradiance[i]));
            if (!refining) {
                mapped.refinement.mean[i] = glm::vec3(x);
                mapped.refinement.m2[i] = glm::vec3(0.0f);
            } else {
                const glm::dvec3 old_mean(mapped.refinement.mean[i]);
                const glm::dvec3 mean = old_mean + (x - old_mean) / static_cast<double>(passes);
                mapped.refinement.mean[i] = glm::vec3(mean);
                mapped.refinement.m2[i] =
                    glm::vec3(glm::dvec3(mapped.refinement.m2[i]) + (x - old_mean) * (x - mean));
            }
            values[i] = mapped.refinement.mean[i];
        }
    } else {
        mapped.refinement.mean = {};
        mapped.refinement.m2 = {};
        for (std::size_t i = 0; i < count; ++i) {
            values[i] = sanitized(mapped.gather.irradiance[i]);
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
            const glm::dvec3 m2(mapped.refinement.m2[i]);
            noise[i] = (m2.x + m2.y + m2.z) * scale;
        }
    }
    filters_[surface] =
        std::make_unique<IimPassFilter>(mapped.texels.texels, std::move(values), std::move(noise),
                                        settings_.iim_filter_radius, sigmas);
    mapped.gather.irradiance.clear();
    mapped.gather.irradiance.shrink_to_fit();
}

void IlluminationMaps::finish_pass(std::uint32_t surface, double now_seconds) {
    MapSurface& mapped = surfaces_[surface];
    const auto found = filters_.find(surface);
    if (found == filters_.end()) {
        return;
    }
    const IimPassFilter& filter = *found->second;
    if (counters_.aim_rebuilds != mapped.gather.aim_rebuilds_at_start) {
        mapped.gather.read_stale_aim = true;  // an AIM changed under the pass
    }
    const auto page_id = static_cast<std::size_t>(aim_.surface_page[surface]);
    IimPage& page = iim_pages_[page_id];
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
    const auto& owners = owners_[page_id];
    const int size = page.current.size;
    for (const SurfaceTexel& texel : texels) {
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
                const int x = texel.x + dx;
                const int y = texel.y + dy;
                if (x < 0 || y < 0 || x >= size || y >= size ||
                    owners[static_cast<std::size_t>(y) * static_cast<std::size_t>(size) +
                           static_cast<std::size_t>(x)] >= 0) {
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
    mapped.refinement.passes_averaged = mapped.gather.passes_when_done;
    if (mapped.refinement.passes_averaged >= settings_.refine_passes) {
        // Done refining: the IIM holds the filtered mean.
        mapped.refinement.mean = {};
        mapped.refinement.m2 = {};
    }
    mapped.gather.in_progress = false;
    mapped.gather.completed_once = true;
    filters_.erase(found);
}

}  // namespace luxel::lighting
