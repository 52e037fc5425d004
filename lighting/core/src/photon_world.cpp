#include "luxel/lighting/core/photon_world.hpp"

#include <algorithm>

#include "caustic_lists.hpp"
#include "light_groups.hpp"
#include "photon_geometry.hpp"
#include "photon_world_support.hpp"

// PhotonWorld: construction, the observers and sync(), which reads the ECS change lists in order
// and hands each change to the part that owns it (PhotonGeometry, LightGroups, CausticLists).
namespace luxel::lighting {

PhotonWorld::PhotonWorld(ecs::Registry& registry, PhotonWorldSettings settings)
    : registry_(registry),
      settings_(settings),
      map_(std::make_unique<PhotonMap>(0, 0, settings.selective.tolerance)),
      geometry_(std::make_unique<PhotonGeometry>(registry, *map_, settings.implicit_surfaces)),
      lights_(std::make_unique<LightGroups>(registry, *map_, settings.selective)),
      caustics_(std::make_unique<CausticLists>(settings.caustics)),
      mesh_changes_(registry.observe<scene::MeshInstance>(ecs::ObserverStart::WithExisting)),
      moves_(registry.observe<ecs::WorldTransform>()),
      point_changes_(registry.observe<PointLight>(ecs::ObserverStart::WithExisting)),
      spot_changes_(registry.observe<SpotLight>(ecs::ObserverStart::WithExisting)),
      directional_changes_(registry.observe<DirectionalLight>(ecs::ObserverStart::WithExisting)),
      area_changes_(registry.observe<AreaLight>(ecs::ObserverStart::WithExisting)),
      sky_changes_(registry.observe<SkyLight>(ecs::ObserverStart::WithExisting)),
      portal_changes_(registry.observe<SkyPortal>(ecs::ObserverStart::WithExisting)),
      generator_changes_(registry.observe<CausticGenerator>(ecs::ObserverStart::WithExisting)) {}

PhotonWorld::~PhotonWorld() = default;

void PhotonWorld::sync() {
    last_sync_ = {};
    geometry_->clear_changes();
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
    collect(sky_changes_);
    touch_lights_if_portals_changed(light_touched);
    geometry_->commit();

    sync_lights(light_touched);
    const bool objects_changed = !geometry_->changes().empty();
    if (objects_changed && settings_.selective.exact_invalidation) {
        last_sync_.groups_invalidated =
            static_cast<std::uint32_t>(lights_->invalidate_crossing(geometry_->changes()));
    }
    // The scene disc of directional lights follows the scene's bounds.
    if (objects_changed) {
        lights_->refresh_directional(light_touched, geometry_->sphere());
    }
    std::sort(generators_touched.begin(), generators_touched.end());
    caustics_->sync(*geometry_, *lights_, light_touched, generators_touched, geometry_->changes());
}

/// Meshes added, removed or replaced, mirrored into the ray scene; every such entity may be an
/// area light whose geometry changed.
void PhotonWorld::sync_meshes(std::vector<ecs::Entity>& light_touched,
                              std::vector<ecs::Entity>& meshes_added) {
    mesh_changes_.consume([&](ecs::Entity entity, ecs::ChangeKind kind) {
        ++last_sync_.meshes_changed;
        switch (kind) {
            case ecs::ChangeKind::Destroyed:
                geometry_->remove_mesh(entity);
                break;
            case ecs::ChangeKind::Constructed:
                geometry_->add_mesh(entity);
                meshes_added.push_back(entity);
                break;
            case ecs::ChangeKind::Updated:
                // A skinned mesh's new pose moves its vertices in place; any other new mesh
                // replaces the object.
                if (!geometry_->deform(entity)) {
                    geometry_->remove_mesh(entity);
                    geometry_->add_mesh(entity);
                    meshes_added.push_back(entity);
                }
                break;
        }
        light_touched.push_back(entity);  // an area light's geometry may have changed
    });
}

void PhotonWorld::sync_generators(const std::vector<ecs::Entity>& meshes_added,
                                  std::vector<ecs::Entity>& generators_touched) {
    // Caustic generators: a mesh added above already took its optics from the component; one
    // added earlier is re-added so that its triangles use (or stop using) the generator's own
    // materials. An edited component rewrites those materials in place.
    generator_changes_.consume([&](ecs::Entity entity, ecs::ChangeKind kind) {
        generators_touched.push_back(entity);
        const bool mesh_is_current =
            std::binary_search(meshes_added.begin(), meshes_added.end(), entity);
        const bool has_object = geometry_->object(entity).has_value();
        switch (kind) {
            case ecs::ChangeKind::Destroyed:
                caustics_->remove_generator(entity);
                geometry_->forget_generator(entity);
                if (has_object && registry_.valid(entity) &&
                    registry_.has<scene::MeshInstance>(entity)) {
                    geometry_->remove_mesh(entity);
                    geometry_->add_mesh(entity);
                }
                break;
            case ecs::ChangeKind::Constructed:
                caustics_->add_generator(entity);
                if (has_object && !mesh_is_current) {
                    geometry_->remove_mesh(entity);
                    geometry_->add_mesh(entity);
                }
                break;
            case ecs::ChangeKind::Updated:
                geometry_->set_generator_optics(entity, registry_.get<CausticGenerator>(entity));
                break;
        }
    });
}

/// Moved objects: a dynamic one's instance transform, a static one rebuilt in place.
void PhotonWorld::sync_moves(std::vector<ecs::Entity>& light_touched) {
    moves_.consume([&](ecs::Entity entity, ecs::ChangeKind kind) {
        if (kind == ecs::ChangeKind::Destroyed) {
            return;
        }
        if (geometry_->move(entity)) {
            ++last_sync_.objects_moved;
        }
        light_touched.push_back(entity);
    });
}

/// The photons of skies and suns start on the portals: a portal added, removed, edited or moved
/// re-emits every sky's and sun's.
void PhotonWorld::touch_lights_if_portals_changed(std::vector<ecs::Entity>& light_touched) {
    bool changed = false;
    portal_changes_.consume([&](ecs::Entity, ecs::ChangeKind) { changed = true; });
    for (ecs::Entity entity : light_touched) {
        changed = changed || (registry_.valid(entity) && registry_.has<SkyPortal>(entity));
    }
    if (!changed) {
        return;
    }
    std::vector<glm::vec3> triangles;
    for (auto [entity, portal] : registry_.view<SkyPortal>()) {
        if (!portal.enabled) {
            continue;
        }
        const glm::mat4 to_world = photon_world_support::world_matrix(registry_, entity);
        const std::size_t whole = portal.triangles.size() / 3 * 3;
        for (std::size_t v = 0; v < whole; ++v) {
            triangles.push_back(glm::vec3(to_world * glm::vec4(portal.triangles[v], 1.0f)));
        }
    }
    lights_->set_portals(std::move(triangles));
    for (auto [entity, sky] : registry_.view<SkyLight>()) {
        light_touched.push_back(entity);
    }
    for (auto [entity, sun] : registry_.view<DirectionalLight>()) {
        light_touched.push_back(entity);
    }
}

/// Every entity touched this sync whose light may have changed: refreshed (its groups
/// invalidated) if it is a light, forgotten if it no longer is. Leaves `light_touched` sorted
/// and without repeats.
void PhotonWorld::sync_lights(std::vector<ecs::Entity>& light_touched) {
    std::sort(light_touched.begin(), light_touched.end());
    light_touched.erase(std::unique(light_touched.begin(), light_touched.end()),
                        light_touched.end());
    const BoundingSphere scene = geometry_->sphere();
    for (ecs::Entity entity : light_touched) {
        if (lights_->contains(entity) ||
            (registry_.valid(entity) &&
             registry_.has_any<PointLight, SpotLight, DirectionalLight, AreaLight, SkyLight>(
                 entity))) {
            ++last_sync_.lights_refreshed;
        }
        const bool is_light =
            registry_.valid(entity) &&
            (registry_.has_any<PointLight, SpotLight, DirectionalLight, SkyLight>(entity) ||
             (registry_.has<AreaLight>(entity) && registry_.has<scene::MeshInstance>(entity)));
        if (is_light) {
            lights_->refresh(entity, scene);
        } else {
            lights_->remove(entity);
        }
    }
}

CausticFrameStats PhotonWorld::update_caustics(std::uint64_t frame, JobSystem& jobs) {
    return caustics_->update(frame, *geometry_, jobs);
}

const PathSegmentIndex& PhotonWorld::paths() const {
    return lights_->paths();
}

const std::vector<GeometryChange>& PhotonWorld::geometry_changes() const {
    return geometry_->changes();
}

std::span<const CausticPair> PhotonWorld::caustics() const {
    return caustics_->pairs();
}

CausticTotals PhotonWorld::caustic_totals() const {
    return caustics_->totals();
}

bool PhotonWorld::caustics_pending() const {
    return caustics_->pending();
}

bool PhotonWorld::caustics_catching_up() const {
    return caustics_->catching_up();
}

bool PhotonWorld::caustics_refining() const {
    return caustics_->refining();
}

CausticFrameStats PhotonWorld::trace_caustic_unit(std::uint32_t max_photons, bool refine,
                                                  JobSystem& jobs) {
    return caustics_->trace_unit(*geometry_, max_photons, refine, jobs);
}

std::uint64_t PhotonWorld::caustic_photons_left(bool refine) const {
    return caustics_->photons_left(refine);
}

std::size_t PhotonWorld::light_count() const {
    return lights_->size();
}

std::size_t PhotonWorld::generator_count() const {
    return caustics_->generator_count();
}

std::size_t PhotonWorld::dynamic_object_count() const {
    return geometry_->dynamic_object_count();
}

const std::vector<std::uint32_t>& PhotonWorld::pending_groups() const {
    return lights_->pending();
}

EmissionStats PhotonWorld::probe(std::uint64_t frame, JobSystem& jobs) {
    return lights_->probe(frame, geometry_->scene(), geometry_->materials(), jobs);
}

EmissionStats PhotonWorld::retrace_pending(JobSystem& jobs, std::size_t max_groups) {
    return lights_->retrace_pending(geometry_->scene(), geometry_->materials(), jobs, max_groups);
}

const RayScene& PhotonWorld::ray_scene() const {
    return geometry_->scene();
}

const std::vector<SurfaceInfo>& PhotonWorld::surfaces() const {
    return geometry_->surfaces();
}

const std::map<ecs::Entity, ObjectId>& PhotonWorld::mesh_objects() const {
    return geometry_->objects();
}

const std::vector<TraceMaterial>& PhotonWorld::materials() const {
    return geometry_->materials();
}

ecs::Entity PhotonWorld::light_of_group(std::uint32_t group) const {
    return lights_->light_of_group(group);
}

std::vector<const LightPhotons*> PhotonWorld::active_lights() const {
    return lights_->active();
}

}  // namespace luxel::lighting
