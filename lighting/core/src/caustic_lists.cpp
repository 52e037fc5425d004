#include "caustic_lists.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

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

void CausticLists::add_generator(ecs::Entity entity) {
    generators_[entity] = GeneratorRecord{};
}

void CausticLists::remove_generator(ecs::Entity entity) {
    generators_.erase(entity);
}

void CausticLists::update_spheres(const PhotonGeometry& geometry) {
    for (auto& [entity, record] : generators_) {
        const std::optional<ObjectId> object = geometry.object(entity);
        if (!object) {
            record.object = kNoObject;  // a generator without geometry aims nothing
            record.moved = false;
            continue;
        }
        if (record.object != *object) {
            record.object = *object;
            record.local_sphere = sphere_around(geometry.scene().mesh(*object).positions);
        }
        const BoundingSphere before = record.world_sphere;
        record.world_sphere = transformed(record.local_sphere, geometry.scene().transform(*object));
        record.moved = record.world_sphere.centre != before.centre ||
                       record.world_sphere.radius != before.radius;
    }
}

std::vector<std::uint8_t> CausticLists::merge_pairs(
    const std::vector<std::pair<ecs::Entity, ecs::Entity>>& wanted) {
    // Only when pairs come or go is the list vector rebuilt (merging, so that surviving lists
    // keep their photons); otherwise references into pairs() stay valid across syncs.
    std::vector<std::uint8_t> fresh(wanted.size(), 0);
    const bool same_pairs =
        std::equal(wanted.begin(), wanted.end(), pairs_.begin(), pairs_.end(),
                   [](const auto& key, const CausticPair& pair) {
                       return key.first == pair.generator && key.second == pair.light;
                   });
    if (same_pairs) {
        return fresh;
    }
    std::vector<CausticPair> next;
    next.reserve(wanted.size());
    auto existing = pairs_.begin();
    for (std::size_t i = 0; i < wanted.size(); ++i) {
        const auto& [generator, light] = wanted[i];
        while (existing != pairs_.end() &&
               std::make_pair(existing->generator, existing->light) < wanted[i]) {
            ++existing;  // its generator or light went away or was switched off
        }
        if (existing != pairs_.end() && existing->generator == generator &&
            existing->light == light) {
            next.push_back(std::move(*existing));
            ++existing;
        } else {
            next.push_back({generator, light,
                            CausticPhotonList(settings_.photons_per_pair, settings_.slices,
                                              next_seed_++, settings_.stand_in)});
            fresh[i] = 1;
        }
    }
    pairs_ = std::move(next);
    return fresh;
}

void CausticLists::sync(const PhotonGeometry& geometry, const LightGroups& lights,
                        std::span<const ecs::Entity> lights_touched,
                        std::span<const ecs::Entity> generators_touched,
                        std::span<const GeometryChange> changes) {
    update_spheres(geometry);
    // The pairs that should exist, in (generator, light) order as both maps iterate.
    std::vector<std::pair<ecs::Entity, ecs::Entity>> wanted;
    const std::vector<ecs::Entity> enabled = lights.enabled_entities();
    for (const auto& [generator, record] : generators_) {
        if (record.object == kNoObject || settings_.photons_per_pair == 0) {
            continue;
        }
        for (ecs::Entity light : enabled) {
            if (light != generator) {
                wanted.emplace_back(generator, light);
            }
        }
    }
    const std::vector<std::uint8_t> fresh = merge_pairs(wanted);

    const BoundingSphere scene_bounds = geometry.sphere();
    // The emitters as they will be, without their siblings yet: a stale pair's new one. A
    // geometry change re-aims only the lists whose recorded paths pass where it happened
    // (METHOD 7.2): elsewhere no photon of theirs can have changed its way.
    std::vector<std::optional<CausticEmitter>> aimed(pairs_.size());
    for (std::size_t i = 0; i < pairs_.size(); ++i) {
        const CausticPair& pair = pairs_[i];
        const GeneratorRecord& generator = generators_.at(pair.generator);
        const bool stale =
            fresh[i] != 0 || generator.moved ||
            // A list that recorded no path yet has lost nothing: re-aimed, it cannot keep
            // an aim (a sun's beam start behind the scene) that the change made wrong.
            (!changes.empty() &&
             (pair.photons.path_cells().empty() || pair.photons.paths_meet(changes))) ||
            std::binary_search(lights_touched.begin(), lights_touched.end(), pair.light) ||
            std::binary_search(generators_touched.begin(), generators_touched.end(),
                               pair.generator);
        if (stale) {
            aimed[i] = CausticEmitter(lights.source(pair.light),
                                      generators_.at(pair.generator).world_sphere, scene_bounds);
        }
    }
    set_siblings(aimed, AxisBox{scene_bounds.centre - glm::vec3(scene_bounds.radius),
                                scene_bounds.centre + glm::vec3(scene_bounds.radius)});
    // Every sync, O(pairs): a pair come, gone or re-aimed changes every other pair's share.
    apportion_photons();
    share_refinement();
}

void CausticLists::set_siblings(const std::vector<std::optional<CausticEmitter>>& aimed,
                                const AxisBox& path_region) {
    const auto emitter = [&](std::size_t i) -> const CausticEmitter& {
        return aimed[i] ? *aimed[i] : pairs_[i].photons.emitter();
    };
    // The pairs of each light, in pair order: pairs_ is sorted by generator first.
    std::map<ecs::Entity, std::vector<std::size_t>> by_light;
    for (std::size_t i = 0; i < pairs_.size(); ++i) {
        by_light[pairs_[i].light].push_back(i);
    }
    std::vector<BoundingSphere> siblings;
    for (const auto& [light, indices] : by_light) {
        for (const std::size_t i : indices) {
            siblings.clear();
            for (const std::size_t j : indices) {
                if (j != i && emitter(j).reaches_generator()) {
                    siblings.push_back(generators_.at(pairs_[j].generator).world_sphere);
                }
            }
            // A sibling come, gone or moved changes the shares of the rays that cross its old
            // or new sphere: a pair with such rays is re-aimed (and retraced) as if it had
            // changed itself; one without keeps its photons.
            const auto& current = emitter(i).siblings();
            const auto same_sphere = [](const BoundingSphere& a, const BoundingSphere& b) {
                return a.centre == b.centre && a.radius == b.radius;
            };
            if (!aimed[i]) {
                bool shares_change = false;
                const auto check = [&](const std::vector<BoundingSphere>& from,
                                       const std::vector<BoundingSphere>& in) {
                    for (const BoundingSphere& sphere : from) {
                        const bool kept = std::any_of(in.begin(), in.end(), [&](const auto& s) {
                            return same_sphere(s, sphere);
                        });
                        shares_change = shares_change || (!kept && emitter(i).may_sample(sphere));
                    }
                };
                check(siblings, current);
                check(current, siblings);
                if (std::equal(siblings.begin(), siblings.end(), current.begin(), current.end(),
                               same_sphere)) {
                    continue;
                }
                if (!shares_change) {
                    pairs_[i].photons.set_siblings_keeping_photons(siblings);
                    continue;
                }
            }
            CausticEmitter next = emitter(i);
            next.set_siblings(siblings);
            pairs_[i].photons.set_emitter(
                std::move(next), aimed[i] ? path_region : pairs_[i].photons.path_cells().region());
        }
    }
}

bool CausticLists::pending() const {
    return std::any_of(pairs_.begin(), pairs_.end(),
                       [](const CausticPair& pair) { return pair.photons.needs_retrace(); });
}

bool CausticLists::catching_up() const {
    return std::any_of(pairs_.begin(), pairs_.end(),
                       [](const CausticPair& pair) { return pair.photons.catching_up(); });
}

bool CausticLists::refining() const {
    return std::any_of(pairs_.begin(), pairs_.end(), [](const CausticPair& pair) {
        return pair.photons.refinement_slice().has_value();
    });
}

void CausticLists::apportion_photons() {
    const std::uint32_t full = settings_.photons_per_pair;
    // At least a photon per slice (fewer leaves slices empty), unless the pairs hold fewer.
    const std::uint32_t least = std::min(std::max<std::uint32_t>(settings_.slices, 1), full);
    const bool capped = settings_.max_photons > 0 &&
                        static_cast<std::uint64_t>(pairs_.size()) * full > settings_.max_photons;
    double total = 0.0;
    for (const CausticPair& pair : pairs_) {
        total += pair.photons.emitter().nominal_power();
    }
    for (CausticPair& pair : pairs_) {
        std::uint32_t target = full;
        if (capped) {
            const double power = pair.photons.emitter().nominal_power();
            const double share =
                total > 0.0 ? power / total : 1.0 / static_cast<double>(pairs_.size());
            const double photons = std::floor(static_cast<double>(settings_.max_photons) * share);
            target = static_cast<std::uint32_t>(
                std::clamp(photons, static_cast<double>(least), static_cast<double>(full)));
        }
        const std::uint32_t current = pair.photons.photon_count();
        // A quarter's slack, so that a lamp switched on among thousands does not retrace every
        // other pair; back to the full count always, as the budget no longer binds.
        const double ratio = static_cast<double>(target) / static_cast<double>(current);
        if (target == current || (target != full && ratio > 0.8 && ratio < 1.25)) {
            continue;
        }
        CausticPhotonList resized(target, settings_.slices, pair.photons.seed(),
                                  settings_.stand_in);
        resized.set_emitter(pair.photons.emitter(), pair.photons.path_cells().region());
        pair.photons = std::move(resized);
    }
}

void CausticLists::share_refinement() {
    // Each pair's share of the refinement photons follows the power its light sends toward
    // its generator: the brighter caustic shows its noise more.
    double total = 0.0;
    for (const CausticPair& pair : pairs_) {
        total += pair.photons.emitter().nominal_power();
    }
    for (CausticPair& pair : pairs_) {
        std::uint32_t limit = 1;
        const double power = pair.photons.emitter().nominal_power();
        const std::uint32_t generation = pair.photons.photon_count();
        if (total > 0.0 && power > 0.0 && generation > 0) {
            const double photons =
                static_cast<double>(settings_.refinement_photons) * power / total;
            const double extra = std::floor(photons / generation);
            limit = static_cast<std::uint32_t>(std::min<double>(
                1.0 + extra, std::max<std::uint32_t>(settings_.max_generations, 1)));
        }
        pair.photons.set_generation_limit(limit);
    }
}

CausticFrameStats CausticLists::update(std::uint64_t frame, const PhotonGeometry& geometry,
                                       JobSystem& jobs) {
    CausticFrameStats stats;
    std::vector<CausticPhotonList::SliceWork> work;
    for (CausticPair& pair : pairs_) {
        if (const auto slice = pair.photons.slice_for_frame(frame)) {
            work.push_back({&pair.photons, *slice});
            ++stats.slices_retraced;
        } else if (const auto refine = pair.photons.refinement_slice()) {
            work.push_back({&pair.photons, *refine});
            ++stats.slices_refined;
        }
    }
    if (work.empty()) {
        return stats;  // nothing moved and nothing to refine: nothing is traced
    }
    stats.trace = CausticPhotonList::retrace(geometry.scene(), geometry.materials(), work,
                                             settings_.max_specular_interactions, jobs);
    return stats;
}

CausticFrameStats CausticLists::trace_unit(const PhotonGeometry& geometry,
                                           std::uint32_t max_photons, bool refine,
                                           JobSystem& jobs) {
    CausticFrameStats stats;
    const std::size_t count = pairs_.size();
    // A unit takes one list's slice, and the next list's once that slice is complete, until
    // its photons are spent: 10,000 lights' lists of 16 photons each fill units of 256 as
    // one list's slice of 1,250 photons takes five of them.
    std::uint32_t left = std::max<std::uint32_t>(max_photons, 1);
    while (left > 0) {
        // Retraces before refinement: a list that needs one shows the old scene. Then the
        // refinement of lists catching up after a change, whose error a player has just seen
        // jump, before that of still lists, which only lowers noise further.
        std::optional<std::size_t> chosen;
        for (std::size_t n = 0; n < count && !chosen; ++n) {
            const std::size_t i = (unit_cursor_ + n) % count;
            if (pairs_[i].photons.needs_retrace()) {
                chosen = i;
            }
        }
        for (int pass = 0; pass < 2 && !chosen && refine; ++pass) {
            for (std::size_t n = 0; n < count && !chosen; ++n) {
                const std::size_t i = (unit_cursor_ + n) % count;
                const CausticPhotonList& list = pairs_[i].photons;
                if (list.has_work() && (pass == 1 || list.catching_up())) {
                    chosen = i;
                }
            }
        }
        if (!chosen) {
            break;
        }
        CausticPhotonList& list = pairs_[*chosen].photons;
        const bool retrace = list.needs_retrace();
        const std::uint64_t completed = list.parts_completed();
        const CausticTraceCounters part =
            list.trace_part(geometry.scene(), geometry.materials(), left,
                            settings_.max_specular_interactions, jobs);
        stats.trace += part;
        const bool done = list.parts_completed() != completed;
        if (done) {
            (retrace ? stats.slices_retraced : stats.slices_refined) += 1;
        }
        // A list keeps the turn until its slice is complete, so slices land as soon as they can.
        unit_cursor_ = done ? *chosen + 1 : *chosen;
        if (part.photons == 0 || part.photons >= left) {
            break;
        }
        left -= static_cast<std::uint32_t>(part.photons);
    }
    return stats;
}

std::uint64_t CausticLists::photons_left(bool refine) const {
    std::uint64_t left = 0;
    for (const CausticPair& pair : pairs_) {
        if (refine) {
            // A list catching up may take several slices in a frame whose share has room.
            left += std::max<std::uint64_t>(pair.photons.part_photons_left(),
                                            pair.photons.catch_up_photons_left());
        } else if (pair.photons.needs_retrace()) {
            left += pair.photons.part_photons_left();
        }
    }
    return left;
}

CausticTotals CausticLists::totals() const {
    CausticTotals totals;
    totals.lists = pairs_.size();
    totals.bytes = pairs_.capacity() * sizeof(CausticPair);
    for (const CausticPair& pair : pairs_) {
        totals.stored += pair.photons.stored_count();
        totals.bytes += pair.photons.bytes_used() - sizeof(CausticPhotonList);
    }
    return totals;
}

}  // namespace luxel::lighting
