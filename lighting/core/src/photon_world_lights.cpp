#include "luxel/lighting/core/photon_world.hpp"

#include <algorithm>
#include <cmath>

#include "luxel/runtime/log.hpp"
#include "luxel/scene/image_decode.hpp"
#include "photon_world_support.hpp"

// PhotonWorld, part 3 of 4: lights, their photon groups, probes and retraces (docs/METHOD.md §4).
namespace luxel::lighting {

using photon_world_support::world_matrix;

void PhotonWorld::refresh_light(ecs::Entity entity) {
    if (!registry_.valid(entity)) {
        remove_light(entity);
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
        enabled = point->enabled;
    } else if (const auto* spot = registry_.try_get<SpotLight>(entity)) {
        source.kind = LightKind::Spot;
        source.power = spot->power;
        source.inner_cone = spot->inner_cone;
        source.outer_cone = spot->outer_cone;
        enabled = spot->enabled;
    } else if (const auto* sun = registry_.try_get<DirectionalLight>(entity)) {
        source.kind = LightKind::Directional;
        source.power = sun->irradiance;
        enabled = sun->enabled;
        directional = true;
    } else if (const auto* area = registry_.try_get<AreaLight>(entity);
               area != nullptr && registry_.has<scene::MeshInstance>(entity)) {
        source.kind = LightKind::Area;
        enabled = area->enabled;
        const scene::MeshInstance& instance = registry_.get<scene::MeshInstance>(entity);
        for (const auto& primitive : instance.geometry().primitives) {
            if (primitive.material < 0) {
                continue;
            }
            const scene::Material& material =
                instance.source->materials.at(static_cast<std::size_t>(primitive.material));
            if (!material.is_emissive()) {
                continue;
            }
            // One radiance per light: the first emissive material's (documented limitation).
            if (source.triangles.empty()) {
                source.power = material.emitted_radiance() * area->scale;
            }
            for (std::uint32_t index : primitive.indices) {
                source.triangles.push_back(
                    glm::vec3(world * glm::vec4(primitive.positions[index], 1.0f)));
            }
        }
    } else {
        remove_light(entity);
        return;
    }

    auto& record = lights_[entity];
    if (!record) {
        record = std::make_unique<LightRecord>();
        const std::uint32_t first = map_->add_groups(settings_.selective.groups);
        record->photons = std::make_unique<LightPhotons>(PhotonEmitter(source, scene_sphere()),
                                                         first, next_seed_++, settings_.selective);
        next_group_ = first + settings_.selective.groups;
    } else {
        record->photons->set_emitter(PhotonEmitter(source, scene_sphere()));
    }
    record->directional = directional;
    record->enabled = enabled;
    const LightPhotons& photons = *record->photons;
    // A moved, changed or switched light invalidates all its groups.
    for (std::uint32_t g = 0; g < photons.group_count(); ++g) {
        const std::uint32_t global = photons.first_group() + g;
        if (enabled) {
            if (std::find(pending_.begin(), pending_.end(), global) == pending_.end()) {
                pending_.push_back(global);
            }
        } else {
            map_->clear_group(global);
        }
    }
    if (!enabled) {
        std::erase_if(pending_, [&](std::uint32_t g) {
            return g >= photons.first_group() && g < photons.first_group() + photons.group_count();
        });
    }
}

void PhotonWorld::remove_light(ecs::Entity entity) {
    const auto found = lights_.find(entity);
    if (found == lights_.end()) {
        return;
    }
    const LightPhotons& photons = *found->second->photons;
    for (std::uint32_t g = 0; g < photons.group_count(); ++g) {
        map_->clear_group(photons.first_group() + g);
    }
    std::erase_if(pending_, [&](std::uint32_t g) {
        return g >= photons.first_group() && g < photons.first_group() + photons.group_count();
    });
    lights_.erase(found);
}

std::vector<const LightPhotons*> PhotonWorld::active_lights() const {
    std::vector<const LightPhotons*> active;
    for (const auto& [entity, record] : lights_) {
        if (record->enabled) {
            active.push_back(record->photons.get());
        }
    }
    return active;
}

ecs::Entity PhotonWorld::light_of_group(std::uint32_t group) const {
    for (const auto& [entity, record] : lights_) {
        const LightPhotons& photons = *record->photons;
        if (group >= photons.first_group() &&
            group < photons.first_group() + photons.group_count()) {
            return entity;
        }
    }
    return ecs::null_entity;
}

EmissionStats PhotonWorld::probe(std::uint64_t frame, JobSystem& jobs) {
    const auto lights = active_lights();
    std::vector<std::uint32_t> invalid;
    // Groups already waiting need no probe verdict; probing them anyway keeps this simple and
    // costs one photon each.
    EmissionStats stats = run_probes(scene_, materials_, lights, *map_, frame,
                                     settings_.selective.tolerance, jobs, invalid);
    for (std::uint32_t group : invalid) {
        if (std::find(pending_.begin(), pending_.end(), group) == pending_.end()) {
            pending_.push_back(group);
        }
    }
    return stats;
}

EmissionStats PhotonWorld::retrace_pending(JobSystem& jobs, std::size_t max_groups) {
    const std::size_t count =
        max_groups == 0 ? pending_.size() : std::min(max_groups, pending_.size());
    const std::vector<std::uint32_t> batch(pending_.begin(),
                                           pending_.begin() + static_cast<std::ptrdiff_t>(count));
    pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(count));
    const auto lights = active_lights();
    return retrace_groups(scene_, materials_, lights, *map_, batch, jobs);
}

}  // namespace luxel::lighting
