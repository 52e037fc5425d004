#include "luxel/lighting/core/photon_world.hpp"

#include <algorithm>
#include <cmath>

#include "luxel/ecs/hierarchy.hpp"
#include "luxel/ecs/transform.hpp"
#include "luxel/runtime/log.hpp"
#include "luxel/scene/image_decode.hpp"

namespace luxel::lighting {

struct PhotonWorld::LightRecord {
    std::unique_ptr<LightPhotons> photons;
    bool enabled = true;
    bool directional = false;
};

namespace {

/// Where a scene material becomes the material photons (and the CPU gather and the reference,
/// which share this table) see. A textured material bounces with factor x the texture's mean
/// linear colour: scene::mean_diffuse_albedo says why the mean is enough.
TraceMaterial trace_material_of(const scene::Scene& scene, const scene::Material& material) {
    TraceMaterial traced;
    traced.albedo = scene::mean_diffuse_albedo(scene, material);
    traced.ior = material.ior;
    if (material.transmission > 0.0f) {
        traced.scattering = Scattering::Dielectric;
        traced.tint = glm::vec3(material.base_color);
    } else if (material.is_specular()) {
        traced.scattering = Scattering::Mirror;
        traced.tint = glm::vec3(material.base_color);
    }
    return traced;
}

/// A generator's own optics for one of its specular materials: the CausticGenerator component
/// is what a game edits to change a caustic.
TraceMaterial generator_optics(const TraceMaterial& shared, const CausticGenerator& generator) {
    TraceMaterial optics = shared;
    if (generator.transmission > 0.0f) {
        optics.scattering = Scattering::Dielectric;
        optics.ior = generator.ior;
        optics.tint = generator.tint * std::clamp(generator.transmission, 0.0f, 1.0f);
    } else {
        optics.scattering = Scattering::Mirror;
        optics.tint = generator.tint;
    }
    return optics;
}

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

glm::mat4 world_matrix(const ecs::Registry& registry, ecs::Entity entity) {
    if (const auto* world = registry.try_get<ecs::WorldTransform>(entity)) {
        return world->matrix;
    }
    return ecs::compute_world_matrix(registry, entity);
}

}  // namespace

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

std::uint32_t PhotonWorld::material_index(const scene::Scene* source, int material) {
    const auto key = std::make_pair(source, material);
    if (const auto found = material_ids_.find(key); found != material_ids_.end()) {
        return found->second;
    }
    const auto index = static_cast<std::uint32_t>(materials_.size());
    materials_.push_back(
        material >= 0 && source != nullptr
            ? trace_material_of(*source, source->materials.at(static_cast<std::size_t>(material)))
            : TraceMaterial{});
    material_ids_.emplace(key, index);
    return index;
}

std::uint32_t PhotonWorld::generator_material(ecs::Entity entity, std::uint32_t shared,
                                              const CausticGenerator& optics) {
    const auto key = std::make_pair(entity, shared);
    auto found = generator_materials_.find(key);
    if (found == generator_materials_.end()) {
        found =
            generator_materials_.emplace(key, static_cast<std::uint32_t>(materials_.size())).first;
        materials_.emplace_back();
    }
    materials_[found->second] = generator_optics(materials_[shared], optics);
    return found->second;
}

void PhotonWorld::forget_generator_materials(ecs::Entity entity) {
    // The material slots themselves stay (ids are baked into triangles until re-added); they
    // are a few dozen bytes each and generators are rarely removed.
    std::erase_if(generator_materials_,
                  [&](const auto& entry) { return entry.first.first == entity; });
}

void PhotonWorld::add_mesh(ecs::Entity entity) {
    const scene::MeshInstance& instance = registry_.get<scene::MeshInstance>(entity);
    const scene::Mesh& mesh = instance.geometry();
    const bool dynamic = registry_.has<scene::Dynamic>(entity);
    const LightmappedSurface* layout = registry_.try_get<LightmappedSurface>(entity);
    const CausticGenerator* generator = registry_.try_get<CausticGenerator>(entity);

    TriangleMesh triangles;
    for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
        const scene::Primitive& primitive = mesh.primitives[p];
        std::int32_t surface = -1;
        int layout_id = -1;
        if (layout != nullptr) {
            for (const auto& entry : layout->layout.surfaces) {
                if (entry.primitive == static_cast<int>(p)) {
                    layout_id = entry.id;
                }
            }
        }
        if (layout_id >= 0 || (layout == nullptr && settings_.implicit_surfaces && !dynamic)) {
            surface = static_cast<std::int32_t>(surfaces_.size());
            surfaces_.push_back({entity, static_cast<int>(p), layout_id});
            map_->add_surfaces(1);
        }
        const auto base = static_cast<std::uint32_t>(triangles.positions.size());
        triangles.positions.insert(triangles.positions.end(), primitive.positions.begin(),
                                   primitive.positions.end());
        if (!primitive.normals.empty()) {
            triangles.normals.insert(triangles.normals.end(), primitive.normals.begin(),
                                     primitive.normals.end());
        } else {
            // Keep the arrays aligned: a zero normal falls back to the geometric one.
            triangles.normals.resize(triangles.positions.size(), glm::vec3(0.0f));
        }
        if (!primitive.texcoords1.empty()) {
            triangles.lightmap_uvs.resize(base, glm::vec2(0.0f));
            triangles.lightmap_uvs.insert(triangles.lightmap_uvs.end(),
                                          primitive.texcoords1.begin(), primitive.texcoords1.end());
        }
        for (std::uint32_t index : primitive.indices) {
            triangles.indices.push_back(base + index);
        }
        std::uint32_t material = material_index(instance.source.get(), primitive.material);
        if (generator != nullptr && materials_[material].scattering != Scattering::Diffuse) {
            material = generator_material(entity, material, *generator);
        }
        triangles.surface_ids.insert(triangles.surface_ids.end(), primitive.triangle_count(),
                                     surface);
        triangles.material_ids.insert(triangles.material_ids.end(), primitive.triangle_count(),
                                      material);
    }
    if (!triangles.lightmap_uvs.empty()) {
        triangles.lightmap_uvs.resize(triangles.positions.size(), glm::vec2(0.0f));
    }
    if (triangles.indices.empty()) {
        return;
    }
    objects_[entity] =
        scene_.add_object(std::move(triangles), world_matrix(registry_, entity), dynamic);
    scene_changed_ = true;
}

void PhotonWorld::remove_mesh(ecs::Entity entity) {
    const auto found = objects_.find(entity);
    if (found == objects_.end()) {
        return;
    }
    // Photons stored on its surfaces stay until their groups' probes notice (they no longer hit
    // it) and retrace: the surfaces are not reused.
    scene_.remove_object(found->second);
    objects_.erase(found);
    scene_changed_ = true;
}

BoundingSphere PhotonWorld::scene_sphere() const {
    const glm::vec3 lo = scene_.bounds_min();
    const glm::vec3 hi = scene_.bounds_max();
    if (lo.x > hi.x) {
        return {};
    }
    return {(lo + hi) * 0.5f, std::max(0.5f * glm::length(hi - lo), 1e-6f)};
}

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

void PhotonWorld::sync() {
    last_sync_ = {};
    std::vector<ecs::Entity> light_touched;
    std::vector<ecs::Entity> meshes_added;
    mesh_changes_.consume([&](ecs::Entity entity, ecs::ChangeKind kind) {
        ++last_sync_.meshes_changed;
        switch (kind) {
            case ecs::ChangeKind::Destroyed:
                remove_mesh(entity);
                break;
            case ecs::ChangeKind::Constructed:
                add_mesh(entity);
                meshes_added.push_back(entity);
                break;
            case ecs::ChangeKind::Updated:
                remove_mesh(entity);
                add_mesh(entity);
                meshes_added.push_back(entity);
                break;
        }
        light_touched.push_back(entity);  // an area light's geometry may have changed
    });
    // Caustic generators: a mesh added above already took its optics from the component; one
    // added earlier is re-added so that its triangles use (or stop using) the generator's own
    // materials. An edited component rewrites those materials in place.
    std::sort(meshes_added.begin(), meshes_added.end());
    std::vector<ecs::Entity> generators_touched;
    generator_changes_.consume([&](ecs::Entity entity, ecs::ChangeKind kind) {
        generators_touched.push_back(entity);
        const bool mesh_is_current =
            std::binary_search(meshes_added.begin(), meshes_added.end(), entity);
        const bool has_object = objects_.contains(entity);
        switch (kind) {
            case ecs::ChangeKind::Destroyed:
                generators_.erase(entity);
                forget_generator_materials(entity);
                if (has_object && registry_.valid(entity) &&
                    registry_.has<scene::MeshInstance>(entity)) {
                    remove_mesh(entity);
                    add_mesh(entity);
                }
                break;
            case ecs::ChangeKind::Constructed:
                generators_[entity] = GeneratorRecord{};
                if (has_object && !mesh_is_current) {
                    remove_mesh(entity);
                    add_mesh(entity);
                }
                break;
            case ecs::ChangeKind::Updated: {
                const CausticGenerator& optics = registry_.get<CausticGenerator>(entity);
                for (const auto& [key, own] : generator_materials_) {
                    if (key.first == entity) {
                        materials_[own] = generator_optics(materials_[key.second], optics);
                    }
                }
                break;
            }
        }
    });
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
    auto collect = [&](auto& observer) {
        observer.consume(
            [&](ecs::Entity entity, ecs::ChangeKind) { light_touched.push_back(entity); });
    };
    collect(point_changes_);
    collect(spot_changes_);
    collect(directional_changes_);
    collect(area_changes_);
    scene_.commit();

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

std::size_t PhotonWorld::dynamic_object_count() const {
    std::size_t count = 0;
    for (const auto& entry : objects_) {
        count += scene_.is_dynamic(entry.second) ? 1 : 0;
    }
    return count;
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
