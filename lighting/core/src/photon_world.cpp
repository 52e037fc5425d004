#include "luxel/lighting/core/photon_world.hpp"

#include <algorithm>
#include <cmath>

#include "luxel/runtime/log.hpp"
#include "luxel/scene/image_decode.hpp"
#include "photon_world_support.hpp"

// PhotonWorld, part 1 of 4: construction and sync(), which reads the ECS change lists in order.
namespace luxel::lighting {

using photon_world_support::world_matrix;

PhotonWorld::PhotonWorld(ecs::Registry& registry, PhotonWorldSettings settings)
    : registry_(registry),
      settings_(settings),
      map_(std::make_unique<PhotonMap>(0, 0)),
      mesh_changes_(registry.observe<scene::MeshInstance>(ecs::ObserverStart::WithExisting)),
      moves_(registry.observe<ecs::WorldTransform>()),
      point_changes_(registry.observe<PointLight>(ecs::ObserverStart::WithExisting)),
      spot_changes_(registry.observe<SpotLight>(ecs::ObserverStart::WithExisting)),
      directional_changes_(registry.observe<DirectionalLight>(ecs::ObserverStart::WithExisting)),
      area_changes_(registry.observe<AreaLight>(ecs::ObserverStart::WithExisting)),
      generator_changes_(registry.observe<CausticGenerator>(ecs::ObserverStart::WithExisting)) {}

PhotonWorld::~PhotonWorld() = default;

void PhotonWorld::sync() {
    last_sync_ = {};
    std::vector<ecs::Entity> light_touched;
    std::vector<ecs::Entity> meshes_added;
    sync_meshes(light_touched, meshes_added);
    std::sort(meshes_added.begin(), meshes_added.end());
    std::vector<ecs::Entity> generators_touched;
    sync_generators(meshes_added, generators_touched);
    sync_moves(light_touched);
    auto collect = [&](auto& observer) {
        observer.consume(
            [&](ecs::Entity entity, ecs::ChangeKind) { light_touched.push_back(entity); });
    };
    collect(point_changes_);
    collect(spot_changes_);
    collect(directional_changes_);
    collect(area_changes_);
    scene_.commit();

    sync_lights(light_touched);
    const bool objects_changed = scene_changed_;
    // The scene disc of directional lights follows the scene's bounds.
    if (scene_changed_) {
        for (auto& [entity, record] : lights_) {
            if (record->directional &&
                !std::binary_search(light_touched.begin(), light_touched.end(), entity)) {
                refresh_light(entity);
            }
        }
        scene_changed_ = false;
    }
    std::sort(generators_touched.begin(), generators_touched.end());
    sync_caustics(light_touched, generators_touched, objects_changed);
}

/// Moved objects: a dynamic one's instance transform, a static one rebuilt in place.
void PhotonWorld::sync_moves(std::vector<ecs::Entity>& light_touched) {
    moves_.consume([&](ecs::Entity entity, ecs::ChangeKind kind) {
        if (kind == ecs::ChangeKind::Destroyed) {
            return;
        }
        if (const auto found = objects_.find(entity); found != objects_.end()) {
            ++last_sync_.objects_moved;
            if (scene_.is_dynamic(found->second)) {
                scene_.set_transform(found->second, world_matrix(registry_, entity));
            } else {
                // A static object moved after all: rebuild it in place (rare, and logged).
                log::debug("static mesh moved; rebuilding the static BVH");
                remove_mesh(entity);
                add_mesh(entity);
            }
            scene_changed_ = true;
        }
        light_touched.push_back(entity);
    });
}

/// Every entity touched this sync whose light may have changed: refreshed (its groups
/// invalidated) if it is a light, forgotten if it no longer is. Leaves `light_touched` sorted
/// and without repeats.
void PhotonWorld::sync_lights(std::vector<ecs::Entity>& light_touched) {
    std::sort(light_touched.begin(), light_touched.end());
    light_touched.erase(std::unique(light_touched.begin(), light_touched.end()),
                        light_touched.end());
    for (ecs::Entity entity : light_touched) {
        if (lights_.contains(entity) ||
            (registry_.valid(entity) &&
             registry_.has_any<PointLight, SpotLight, DirectionalLight, AreaLight>(entity))) {
            ++last_sync_.lights_refreshed;
        }
        const bool is_light =
            registry_.valid(entity) &&
            (registry_.has_any<PointLight, SpotLight, DirectionalLight>(entity) ||
             (registry_.has<AreaLight>(entity) && registry_.has<scene::MeshInstance>(entity)));
        if (is_light) {
            refresh_light(entity);
        } else {
            remove_light(entity);
        }
    }
}

std::size_t PhotonWorld::dynamic_object_count() const {
    std::size_t count = 0;
    for (const auto& entry : objects_) {
        count += scene_.is_dynamic(entry.second) ? 1 : 0;
    }
    return count;
}

}  // namespace luxel::lighting
