#include "light_groups.hpp"

#include <algorithm>
#include <cmath>

#include "photon_world_support.hpp"

namespace luxel::lighting {

using photon_world_support::world_matrix;

namespace {

/// A light's radius as the direct light uses it: a negative or non-finite one is a point.
float sphere_radius(float radius) {
    return std::isfinite(radius) && radius > 0.0f ? radius : 0.0f;
}

}  // namespace

LightGroups::LightGroups(const ecs::Registry& registry, PhotonMap& map,
                         const SelectiveSettings& settings)
    : registry_(registry), map_(map), settings_(settings) {}

LightGroups::~LightGroups() = default;

void LightGroups::refresh(ecs::Entity entity, const BoundingSphere& scene) {
    if (!registry_.valid(entity)) {
        remove(entity);
        return;
    }
    const glm::mat4 world = world_matrix(registry_, entity);
    LightSource source;
    source.position = glm::vec3(world[3]);
    const glm::vec3 axis = -glm::vec3(world[2]);
    source.direction = glm::length(axis) > 0.0f ? glm::normalize(axis) : glm::vec3(0, 0, -1);
    bool enabled = false;
    bool directional = false;
    if (const auto* point = registry_.try_get<PointLight>(entity)) {
        source.kind = LightKind::Point;
        source.power = point->power;
        source.radius = sphere_radius(point->radius);
        enabled = point->enabled;
    } else if (const auto* spot = registry_.try_get<SpotLight>(entity)) {
        source.kind = LightKind::Spot;
        source.power = spot->power;
        source.inner_cone = spot->inner_cone;
        source.outer_cone = spot->outer_cone;
        source.radius = sphere_radius(spot->radius);
        enabled = spot->enabled;
    } else if (const auto* sun = registry_.try_get<DirectionalLight>(entity)) {
        source.kind = LightKind::Directional;
        source.power = sun->irradiance;
        source.portals = portals_;
        enabled = sun->enabled;
        directional = true;
    } else if (const auto* sky = registry_.try_get<SkyLight>(entity)) {
        // Emitted from the disc of the scene's sphere, as a directional light is.
        source.kind = LightKind::Sky;
        source.sky = sky->radiance;
        source.sky_scale = sky->effective_scale();
        // Its integral over the sphere (W/m^2): what "has power" means for a sky.
        source.power = sky->radiance != nullptr
                           ? glm::vec3(sky->radiance->integral()) * source.sky_scale
                           : glm::vec3(0.0f);
        enabled = sky->enabled && sky->radiance != nullptr && !sky->radiance->black();
        directional = true;
        source.portals = portals_;
    } else if (const auto* area = registry_.try_get<AreaLight>(entity);
               area != nullptr && registry_.has<scene::MeshInstance>(entity)) {
        source.kind = LightKind::Area;
        enabled = area->enabled;
        const scene::MeshInstance& instance = registry_.get<scene::MeshInstance>(entity);
        for (const auto& primitive : instance.geometry().primitives) {
            if (primitive.material < 0 ||
                !instance.source->materials.at(static_cast<std::size_t>(primitive.material))
                     .is_emissive()) {
                continue;
            }
            for (std::uint32_t index : primitive.indices) {
                source.triangles.push_back(
                    glm::vec3(world * glm::vec4(primitive.positions[index], 1.0f)));
            }
        }
        const PiecesCache& pieces = emission_pieces(entity, instance);
        source.pieces = pieces.pieces;
        source.piece_scale = area->scale;
        source.power =
            source.pieces != nullptr ? mean_radiance(source) : pieces.uniform * area->scale;
    } else {
        remove(entity);
        return;
    }

    Record& record = lights_[entity];
    if (!record.photons) {
        const std::uint32_t first = map_.add_groups(settings_.groups);
        record.photons = std::make_unique<LightPhotons>(PhotonEmitter(source, scene), first,
                                                        next_seed_++, settings_);
    } else {
        record.photons->set_emitter(PhotonEmitter(source, scene));
    }
    record.directional = directional;
    record.enabled = enabled;
    record.scene = scene;
    const LightPhotons& photons = *record.photons;
    // A moved, changed or switched light invalidates all its groups.
    if (enabled) {
        for (std::uint32_t g = 0; g < photons.group_count(); ++g) {
            add_pending(photons.first_group() + g);
        }
    } else {
        clear_photons(photons);
    }
}

void LightGroups::clear_photons(const LightPhotons& photons) {
    std::vector<std::uint32_t> groups(photons.group_count());
    for (std::uint32_t g = 0; g < photons.group_count(); ++g) {
        groups[g] = photons.first_group() + g;
        paths_.clear_group(groups[g]);
    }
    map_.clear_groups(groups);
    drop_pending(photons);
}

const LightGroups::PiecesCache& LightGroups::emission_pieces(ecs::Entity entity,
                                                             const scene::MeshInstance& instance) {
    // The pieces depend on the mesh and its materials only, so a moving emitter keeps its
    // own; the scene held in the key keeps its address from being reused while cached.
    PiecesCache& cached = pieces_[entity];
    if (cached.source == nullptr || cached.source != instance.source ||
        cached.mesh != instance.mesh) {
        cached.source = instance.source;
        cached.mesh = instance.mesh;
        EmissionPieces pieces = EmissionPieces::of_mesh(*instance.source, instance.geometry());
        // One radiance everywhere (an untextured emitter): no pieces, and photons of exactly
        // equal power, as before pieces existed.
        cached.uniform = pieces.piece_count() > 0 ? pieces.radiance(0, 0) : glm::vec3(0.0f);
        cached.pieces =
            pieces.uniform() ? nullptr : std::make_shared<const EmissionPieces>(std::move(pieces));
    }
    return cached;
}

glm::vec3 LightGroups::mean_radiance(const LightSource& light) {
    // Area-weighted over the world-space triangles: pi x this x area is the light's flux.
    const AreaRadiance integral = integrate_area_radiance(light);
    return integral.area > 0.0 ? glm::vec3(integral.radiance_times_area / integral.area)
                               : glm::vec3(0.0f);
}

void LightGroups::remove(ecs::Entity entity) {
    pieces_.erase(entity);
    const auto found = lights_.find(entity);
    if (found == lights_.end()) {
        return;
    }
    clear_photons(*found->second.photons);
    lights_.erase(found);
}

void LightGroups::refresh_directional(std::span<const ecs::Entity> skip,
                                      const BoundingSphere& scene) {
    std::vector<ecs::Entity> directional;
    for (const auto& [entity, record] : lights_) {
        const bool moved =
            record.scene.centre != scene.centre || record.scene.radius != scene.radius;
        if (record.directional && moved && !std::binary_search(skip.begin(), skip.end(), entity)) {
            directional.push_back(entity);
        }
    }
    for (ecs::Entity entity : directional) {
        refresh(entity, scene);  // may remove it: not while iterating lights_
    }
}

void LightGroups::add_pending(std::uint32_t group) {
    if (std::find(pending_.begin(), pending_.end(), group) == pending_.end()) {
        pending_.push_back(group);
    }
}

std::size_t LightGroups::invalidate_crossing(std::span<const AxisBox> boxes) {
    // Groups an earlier frame's crossing already queued are still at the front of the queue,
    // waiting for their retrace: the query skips them (in the sandbox level, where several
    // objects move every frame, most of what it would find).
    const std::vector<std::uint32_t> crossing = paths_.groups_meeting(boxes, crossing_pending_);
    if (crossing.empty()) {
        return 0;
    }
    // First in the queue, in group order (the retrace takes the oldest first); a group already
    // pending for another reason moves to the front with them. One pass over the queue
    // (crossing is sorted), not a search of it per crossing group.
    const std::size_t before = pending_.size();
    std::erase_if(pending_, [&](std::uint32_t group) {
        return std::binary_search(crossing.begin(), crossing.end(), group);
    });
    const std::size_t moved = before - pending_.size();
    pending_.insert(pending_.begin(), crossing.begin(), crossing.end());
    if (crossing_pending_.size() <= crossing.back()) {
        crossing_pending_.resize(static_cast<std::size_t>(crossing.back()) + 1, 0);
    }
    for (const std::uint32_t group : crossing) {
        crossing_pending_[group] = 1;
    }
    return crossing.size() - moved;
}

void LightGroups::drop_pending(const LightPhotons& photons) {
    std::erase_if(pending_, [&](std::uint32_t g) {
        return g >= photons.first_group() && g < photons.first_group() + photons.group_count();
    });
    for (std::uint32_t g = photons.first_group();
         g < photons.first_group() + photons.group_count() && g < crossing_pending_.size(); ++g) {
        crossing_pending_[g] = 0;
    }
}

std::vector<ecs::Entity> LightGroups::enabled_entities() const {
    std::vector<ecs::Entity> enabled;
    for (const auto& [entity, record] : lights_) {
        if (record.enabled) {
            enabled.push_back(entity);
        }
    }
    return enabled;
}

const LightSource& LightGroups::source(ecs::Entity entity) const {
    return lights_.at(entity).photons->emitter().light();
}

std::vector<const LightPhotons*> LightGroups::active() const {
    std::vector<const LightPhotons*> active;
    for (const auto& [entity, record] : lights_) {
        if (record.enabled) {
            active.push_back(record.photons.get());
        }
    }
    return active;
}

ecs::Entity LightGroups::light_of_group(std::uint32_t group) const {
    for (const auto& [entity, record] : lights_) {
        const LightPhotons& photons = *record.photons;
        if (group >= photons.first_group() &&
            group < photons.first_group() + photons.group_count()) {
            return entity;
        }
    }
    return ecs::null_entity;
}

EmissionStats LightGroups::probe(std::uint64_t frame, const RayScene& scene,
                                 std::span<const TraceMaterial> materials, JobSystem& jobs) {
    const auto lights = active();
    std::vector<std::uint32_t> invalid;
    // Groups already waiting need no probe verdict; probing them anyway keeps this simple and
    // costs one photon each.
    EmissionStats stats = run_probes(scene, materials, lights, map_, frame, jobs, invalid);
    for (std::uint32_t group : invalid) {
        add_pending(group);
    }
    return stats;
}

EmissionStats LightGroups::retrace_pending(const RayScene& scene,
                                           std::span<const TraceMaterial> materials,
                                           JobSystem& jobs, std::size_t max_groups) {
    const std::size_t count =
        max_groups == 0 ? pending_.size() : std::min(max_groups, pending_.size());
    const std::vector<std::uint32_t> batch(pending_.begin(),
                                           pending_.begin() + static_cast<std::ptrdiff_t>(count));
    pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(count));
    for (const std::uint32_t group : batch) {
        if (group < crossing_pending_.size()) {
            crossing_pending_[group] = 0;
        }
    }
    const auto lights = active();
    // Without exact invalidation no index is kept: it is never asked.
    return retrace_groups(scene, materials, lights, map_, batch, jobs,
                          settings_.exact_invalidation ? &paths_ : nullptr);
}

}  // namespace luxel::lighting
