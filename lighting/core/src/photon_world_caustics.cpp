#include "luxel/lighting/core/photon_world.hpp"

#include <algorithm>
#include <cmath>

#include "luxel/runtime/log.hpp"
#include "luxel/scene/image_decode.hpp"
#include "photon_world_support.hpp"

// PhotonWorld, part 4 of 4: one caustic photon list per (generator, light) pair (docs/METHOD.md
// §7).
namespace luxel::lighting {
namespace {

/// The sphere around a point set's bounding box (centre of the box, radius to the farthest
/// point): not the smallest sphere, but tight for the compact shapes that make caustics.
BoundingSphere sphere_around(const std::vector<glm::vec3>& points) {
    if (points.empty()) {
        return {glm::vec3(0.0f), 0.0f};
    }
    glm::vec3 lo = points.front();
    glm::vec3 hi = points.front();
    for (const glm::vec3& p : points) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    const glm::vec3 centre = 0.5f * (lo + hi);
    float radius2 = 0.0f;
    for (const glm::vec3& p : points) {
        const glm::vec3 offset = p - centre;
        radius2 = std::max(radius2, glm::dot(offset, offset));
    }
    return {centre, std::sqrt(radius2)};
}

BoundingSphere transformed(const BoundingSphere& sphere, const glm::mat4& transform) {
    const float scale =
        std::max({glm::length(glm::vec3(transform[0])), glm::length(glm::vec3(transform[1])),
                  glm::length(glm::vec3(transform[2]))});
    return {glm::vec3(transform * glm::vec4(sphere.centre, 1.0f)), sphere.radius * scale};
}

}  // namespace

using photon_world_support::world_matrix;

void PhotonWorld::sync_caustics(std::span<const ecs::Entity> lights_touched,
                                std::span<const ecs::Entity> generators_touched,
                                bool objects_changed) {
    for (auto& [entity, record] : generators_) {
        const auto found = objects_.find(entity);
        if (found == objects_.end()) {
            record.object = kNoObject;  // a generator without geometry aims nothing
            continue;
        }
        if (record.object != found->second) {
            record.object = found->second;
            record.local_sphere = sphere_around(scene_.mesh(found->second).positions);
        }
        record.world_sphere = transformed(record.local_sphere, scene_.transform(found->second));
    }

    // The pairs that should exist, in (generator, light) order as both maps iterate.
    std::vector<std::pair<ecs::Entity, ecs::Entity>> wanted;
    for (const auto& [generator, record] : generators_) {
        if (record.object == kNoObject || settings_.caustics.photons_per_pair == 0) {
            continue;
        }
        for (const auto& [light, light_record] : lights_) {
            if (light_record->enabled && light != generator) {
                wanted.emplace_back(generator, light);
            }
        }
    }
    // Only when pairs come or go is the list vector rebuilt (merging, so that surviving lists
    // keep their photons); otherwise references into caustics() stay valid across syncs.
    std::vector<std::uint8_t> fresh(wanted.size(), 0);
    const bool same_pairs =
        std::equal(wanted.begin(), wanted.end(), caustic_pairs_.begin(), caustic_pairs_.end(),
                   [](const auto& key, const CausticPair& pair) {
                       return key.first == pair.generator && key.second == pair.light;
                   });
    if (!same_pairs) {
        std::vector<CausticPair> next;
        next.reserve(wanted.size());
        auto existing = caustic_pairs_.begin();
        for (std::size_t i = 0; i < wanted.size(); ++i) {
            const auto& [generator, light] = wanted[i];
            while (existing != caustic_pairs_.end() &&
                   std::make_pair(existing->generator, existing->light) < wanted[i]) {
                ++existing;  // its generator or light went away or was switched off
            }
            if (existing != caustic_pairs_.end() && existing->generator == generator &&
                existing->light == light) {
                next.push_back(std::move(*existing));
                ++existing;
            } else {
                next.push_back(
                    {generator, light,
                     CausticPhotonList(settings_.caustics.photons_per_pair,
                                       settings_.caustics.slices, next_caustic_seed_++)});
                fresh[i] = 1;
            }
        }
        caustic_pairs_ = std::move(next);
    }

    const BoundingSphere scene_bounds = scene_sphere();
    for (std::size_t i = 0; i < caustic_pairs_.size(); ++i) {
        CausticPair& pair = caustic_pairs_[i];
        const bool stale =
            fresh[i] != 0 || objects_changed ||
            std::binary_search(lights_touched.begin(), lights_touched.end(), pair.light) ||
            std::binary_search(generators_touched.begin(), generators_touched.end(),
                               pair.generator);
        if (stale) {
            pair.photons.set_emitter(
                CausticEmitter(lights_.at(pair.light)->photons->emitter().light(),
                               generators_.at(pair.generator).world_sphere, scene_bounds));
        }
    }
}

bool PhotonWorld::caustics_pending() const {
    return std::any_of(caustic_pairs_.begin(), caustic_pairs_.end(),
                       [](const CausticPair& pair) { return pair.photons.needs_retrace(); });
}

CausticFrameStats PhotonWorld::update_caustics(std::uint64_t frame, JobSystem& jobs) {
    CausticFrameStats stats;
    std::vector<CausticPhotonList::SliceWork> work;
    for (CausticPair& pair : caustic_pairs_) {
        if (const auto slice = pair.photons.slice_for_frame(frame)) {
            work.push_back({&pair.photons, *slice});
        }
    }
    if (work.empty()) {
        return stats;  // nothing moved: nothing is traced
    }
    stats.trace = CausticPhotonList::retrace(scene_, materials_, work,
                                             settings_.caustics.max_specular_interactions, jobs);
    stats.slices_retraced = static_cast<std::uint32_t>(work.size());
    return stats;
}

CausticTotals PhotonWorld::caustic_totals() const {
    CausticTotals totals;
    totals.lists = caustic_pairs_.size();
    totals.bytes = caustic_pairs_.capacity() * sizeof(CausticPair);
    for (const CausticPair& pair : caustic_pairs_) {
        totals.stored += pair.photons.stored_count();
        totals.bytes += pair.photons.bytes_used() - sizeof(CausticPhotonList);
    }
    return totals;
}

}  // namespace luxel::lighting
