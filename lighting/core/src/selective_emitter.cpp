#include "luxel/lighting/core/selective_emitter.hpp"

#include <algorithm>
#include <utility>

#include "luxel/lighting/core/halton.hpp"
#include "luxel/runtime/error.hpp"

namespace luxel::lighting {
namespace {

struct PlanePoint {
    std::uint64_t index;
    glm::dvec2 uv;
};

/// A group reference: which light, which of its groups.
struct GroupRef {
    const LightPhotons* light;
    std::uint32_t local;
    std::uint32_t global;
};

std::vector<GroupRef> all_groups(std::span<const LightPhotons* const> lights) {
    std::vector<GroupRef> refs;
    for (const LightPhotons* light : lights) {
        for (std::uint32_t g = 0; g < light->group_count(); ++g) {
            refs.push_back({light, g, light->first_group() + g});
        }
    }
    return refs;
}

}  // namespace

std::vector<std::vector<std::uint64_t>> partition_into_groups(std::uint32_t groups,
                                                              std::uint32_t per_group) {
    if (groups == 0 || per_group == 0) {
        throw Error("partition_into_groups: need at least one group of one photon");
    }
    std::vector<PlanePoint> points(static_cast<std::size_t>(groups) * per_group);
    for (std::size_t i = 0; i < points.size(); ++i) {
        // Index 0 is the corner (0, 0) in every base; start at 1.
        points[i] = {i + 1, halton2(i + 1)};
    }
    std::vector<std::vector<std::uint64_t>> result;
    result.reserve(groups);
    // Explicit stack of (begin, end, groups): depth is only log2(G), but no recursion is needed.
    struct Range {
        std::size_t begin;
        std::size_t end;
        std::uint32_t groups;
    };
    std::vector<Range> stack{{0, points.size(), groups}};
    while (!stack.empty()) {
        const Range range = stack.back();
        stack.pop_back();
        const auto first = points.begin() + static_cast<std::ptrdiff_t>(range.begin);
        const auto last = points.begin() + static_cast<std::ptrdiff_t>(range.end);
        if (range.groups == 1) {
            std::vector<std::uint64_t> group;
            for (auto it = first; it != last; ++it) {
                group.push_back(it->index);
            }
            std::sort(group.begin(), group.end());
            result.push_back(std::move(group));
            continue;
        }
        glm::dvec2 lo(1.0);
        glm::dvec2 hi(0.0);
        for (auto it = first; it != last; ++it) {
            lo = glm::min(lo, it->uv);
            hi = glm::max(hi, it->uv);
        }
        const int axis = (hi.x - lo.x) >= (hi.y - lo.y) ? 0 : 1;
        const std::uint32_t left_groups = range.groups / 2;
        const std::size_t split = range.begin + static_cast<std::size_t>(left_groups) * per_group;
        // A strict total order (ties by index), so the split is the same on every platform.
        std::nth_element(first, points.begin() + static_cast<std::ptrdiff_t>(split), last,
                         [axis](const PlanePoint& a, const PlanePoint& b) {
                             return a.uv[axis] != b.uv[axis] ? a.uv[axis] < b.uv[axis]
                                                             : a.index < b.index;
                         });
        // Right half pushed first so the left half's groups come out first.
        stack.push_back({split, range.end, range.groups - left_groups});
        stack.push_back({range.begin, split, left_groups});
    }
    return result;
}

LightPhotons::LightPhotons(PhotonEmitter emitter, std::uint32_t first_group, std::uint32_t seed,
                           const SelectiveSettings& settings)
    : emitter_(std::move(emitter)),
      first_group_(first_group),
      seed_(seed),
      per_group_(settings.per_group),
      limits_(settings.limits),
      indices_(partition_into_groups(settings.groups, settings.per_group)) {}

void LightPhotons::set_emitter(PhotonEmitter emitter) {
    emitter_ = std::move(emitter);
}

glm::vec3 LightPhotons::trace(const RayScene& scene, std::span<const TraceMaterial> materials,
                              std::uint32_t group, std::uint32_t photon,
                              std::vector<TracedHop>& hops, TraceCounters& counters) const {
    const std::uint64_t index = indices_.at(group).at(photon);
    const std::uint64_t total = static_cast<std::uint64_t>(indices_.size()) * per_group_;
    const EmittedPhoton emitted =
        emitter_.emit({photon_sample(index, 0, seed_), photon_sample(index, 1, seed_)},
                      {photon_sample(index, 2, seed_), photon_sample(index, 3, seed_)}, total);
    trace_photon(scene, materials, emitted, index, seed_, limits_, hops, counters);
    return emitted.origin;
}

TracedGroup LightPhotons::trace_group(const RayScene& scene,
                                      std::span<const TraceMaterial> materials, std::uint32_t group,
                                      TraceCounters& counters) const {
    TracedGroup traced;
    traced.starts.reserve(per_group_ + 1);
    traced.origins.reserve(per_group_);
    for (std::uint32_t photon = 0; photon < per_group_; ++photon) {
        traced.starts.push_back(static_cast<std::uint32_t>(traced.hops.size()));
        traced.origins.push_back(trace(scene, materials, group, photon, traced.hops, counters));
    }
    traced.starts.push_back(static_cast<std::uint32_t>(traced.hops.size()));
    return traced;
}

EmissionStats run_probes(const RayScene& scene, std::span<const TraceMaterial> materials,
                         std::span<const LightPhotons* const> lights, const PhotonMap& map,
                         std::uint64_t frame, JobSystem& jobs,
                         std::vector<std::uint32_t>& invalid_groups) {
    const std::vector<GroupRef> refs = all_groups(lights);
    std::vector<std::uint8_t> diverged(refs.size(), 0);
    std::vector<TraceCounters> counters(refs.size());
    jobs.parallel_for(
        0, refs.size(),
        [&](std::size_t i) {
            const GroupRef& ref = refs[i];
            const auto photon = static_cast<std::uint32_t>(frame % ref.light->photons_per_group());
            std::vector<TracedHop> hops;
            ref.light->trace(scene, materials, ref.local, photon, hops, counters[i]);
            diverged[i] = map.diverges(ref.global, photon, hops) ? 1 : 0;
        },
        8);
    EmissionStats stats;
    for (std::size_t i = 0; i < refs.size(); ++i) {
        stats.trace += counters[i];
        ++stats.probes;
        if (diverged[i] != 0) {
            ++stats.diverged;
            invalid_groups.push_back(refs[i].global);
        }
    }
    return stats;
}

EmissionStats retrace_groups(const RayScene& scene, std::span<const TraceMaterial> materials,
                             std::span<const LightPhotons* const> lights, PhotonMap& map,
                             std::span<const std::uint32_t> groups, JobSystem& jobs,
                             PathSegmentIndex* index) {
    auto owner = [&](std::uint32_t global) -> std::pair<const LightPhotons*, std::uint32_t> {
        for (const LightPhotons* light : lights) {
            if (global >= light->first_group() &&
                global < light->first_group() + light->group_count()) {
                return {light, global - light->first_group()};
            }
        }
        throw Error("retrace_groups: group " + std::to_string(global) + " belongs to no light");
    };
    std::vector<TracedGroup> traced(groups.size());
    std::vector<TraceCounters> counters(groups.size());
    std::vector<std::vector<PathSegment>> segments(index != nullptr ? groups.size() : 0);
    jobs.parallel_for(0, groups.size(), [&](std::size_t i) {
        const auto [light, local] = owner(groups[i]);
        traced[i] = light->trace_group(scene, materials, local, counters[i]);
        if (index != nullptr) {
            segments[i] = path_segments(traced[i]);
        }
    });
    map.replace_groups(groups, traced);
    EmissionStats stats;
    for (std::size_t i = 0; i < groups.size(); ++i) {
        if (index != nullptr) {
            index->set_group(groups[i], std::move(segments[i]));
        }
        stats.trace += counters[i];
        ++stats.groups_retraced;
    }
    return stats;
}

}  // namespace luxel::lighting
