#include "photon_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "luxel/runtime/log.hpp"
#include "luxel/scene/image_decode.hpp"
#include "luxel/scene/volume.hpp"
#include "photon_world_support.hpp"

namespace luxel::lighting {
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
        if (scene::absorbs_inside(material)) {
            traced.attenuation_color = material.attenuation_color;
            traced.attenuation_distance = material.attenuation_distance;
        }
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

}  // namespace

using photon_world_support::world_matrix;

PhotonGeometry::PhotonGeometry(const ecs::Registry& registry, PhotonMap& map,
                               bool implicit_surfaces)
    : registry_(registry), map_(map), implicit_surfaces_(implicit_surfaces) {}

std::uint32_t PhotonGeometry::material_index(const scene::Scene* source, int material,
                                             bool closed) {
    const auto key = std::make_tuple(source, material, closed);
    if (const auto found = material_ids_.find(key); found != material_ids_.end()) {
        return found->second;
    }
    const auto index = static_cast<std::uint32_t>(materials_.size());
    TraceMaterial traced =
        material >= 0 && source != nullptr
            ? trace_material_of(*source, source->materials.at(static_cast<std::size_t>(material)))
            : TraceMaterial{};
    traced.closed = closed && traced.scattering == Scattering::Dielectric;
    materials_.push_back(traced);
    material_ids_.emplace(key, index);
    return index;
}

bool PhotonGeometry::closed_dielectric(const scene::MeshInstance& instance, std::size_t p) {
    const scene::Primitive& primitive = instance.geometry().primitives[p];
    const scene::Scene* source = instance.source.get();
    if (source == nullptr || primitive.material < 0 ||
        static_cast<std::size_t>(primitive.material) >= source->materials.size() ||
        !(source->materials[static_cast<std::size_t>(primitive.material)].transmission > 0.0f)) {
        return false;  // only a dielectric has an inside to tell
    }
    if (instance.posed) {
        return scene::is_closed_surface(primitive);  // its own vertices, new each pose
    }
    const auto key = std::make_tuple(source, instance.mesh, p);
    if (const auto found = closed_primitives_.find(key); found != closed_primitives_.end()) {
        return found->second;
    }
    const bool closed = scene::is_closed_surface(primitive);
    closed_primitives_.emplace(key, closed);
    return closed;
}

std::uint32_t PhotonGeometry::generator_material(ecs::Entity entity, std::uint32_t shared,
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

void PhotonGeometry::set_generator_optics(ecs::Entity entity, const CausticGenerator& optics) {
    for (const auto& [key, own] : generator_materials_) {
        if (key.first == entity) {
            materials_[own] = generator_optics(materials_[key.second], optics);
        }
    }
}

void PhotonGeometry::forget_generator(ecs::Entity entity) {
    // The material slots themselves stay (ids are baked into triangles until re-added); they
    // are a few dozen bytes each and generators are rarely removed.
    std::erase_if(generator_materials_,
                  [&](const auto& entry) { return entry.first.first == entity; });
}

void PhotonGeometry::add_mesh(ecs::Entity entity) {
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
        if (layout_id >= 0 || (layout == nullptr && implicit_surfaces_ && !dynamic)) {
            surface = static_cast<std::int32_t>(surfaces_.size());
            surfaces_.push_back({entity, static_cast<int>(p), layout_id});
            map_.add_surfaces(1);
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
        std::uint32_t material = material_index(instance.source.get(), primitive.material,
                                                closed_dielectric(instance, p));
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
    const ObjectId object =
        scene_.add_object(std::move(triangles), world_matrix(registry_, entity), dynamic);
    objects_[entity] = object;
    if (instance.posed) {
        posed_from_[entity] = {instance.source.get(), instance.mesh};
    }
    ObjectBoxes& boxes = object_boxes_[object];
    boxes.local = box_around(scene_.mesh(object).positions);
    boxes.world = transformed(boxes.local, scene_.transform(object));
    changes_.push_back(boxes.world);
}

void PhotonGeometry::remove_mesh(ecs::Entity entity) {
    const auto found = objects_.find(entity);
    if (found == objects_.end()) {
        return;
    }
    // Photons stored on its surfaces stay until their groups' probes notice (they no longer hit
    // it) and retrace: the surfaces are not reused.
    if (const auto boxes = object_boxes_.find(found->second); boxes != object_boxes_.end()) {
        changes_.push_back(boxes->second.world);
        object_boxes_.erase(boxes);
    }
    scene_.remove_object(found->second);
    objects_.erase(found);
    posed_from_.erase(entity);
}

bool PhotonGeometry::deform(ecs::Entity entity) {
    const auto found = objects_.find(entity);
    const auto made = posed_from_.find(entity);
    if (found == objects_.end() || made == posed_from_.end() || !scene_.is_dynamic(found->second)) {
        return false;
    }
    const auto& instance = registry_.get<scene::MeshInstance>(entity);
    if (!instance.posed || made->second != std::make_pair(instance.source.get(), instance.mesh)) {
        return false;
    }
    // The vertices as add_mesh lays them out: every primitive's in order, a zero normal where
    // a primitive has none.
    const ObjectId object = found->second;
    const std::size_t count = scene_.mesh(object).positions.size();
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    positions.reserve(count);
    normals.reserve(count);
    for (const scene::Primitive& primitive : instance.geometry().primitives) {
        positions.insert(positions.end(), primitive.positions.begin(), primitive.positions.end());
        if (primitive.normals.size() == primitive.positions.size()) {
            normals.insert(normals.end(), primitive.normals.begin(), primitive.normals.end());
        } else {
            normals.resize(positions.size(), glm::vec3(0.0f));
        }
    }
    if (positions.size() != count) {
        return false;
    }
    scene_.deform(object, positions, normals);
    ObjectBoxes& boxes = object_boxes_[object];
    changes_.push_back(boxes.world);  // where it was
    boxes.local = box_around(positions);
    boxes.world = transformed(boxes.local, scene_.transform(object));
    changes_.push_back(boxes.world);  // where it is
    return true;
}

bool PhotonGeometry::move(ecs::Entity entity) {
    const auto found = objects_.find(entity);
    if (found == objects_.end()) {
        return false;
    }
    if (scene_.is_dynamic(found->second)) {
        const ObjectId object = found->second;
        scene_.set_transform(object, world_matrix(registry_, entity));
        ObjectBoxes& boxes = object_boxes_[object];
        changes_.push_back(boxes.world);  // where it was
        boxes.world = transformed(boxes.local, scene_.transform(object));
        changes_.push_back(boxes.world);  // where it is
    } else {
        // A static object moved after all: rebuild it in place (rare, and logged).
        log::debug("static mesh moved; rebuilding the static BVH");
        remove_mesh(entity);
        add_mesh(entity);
    }
    return true;
}

std::optional<ObjectId> PhotonGeometry::object(ecs::Entity entity) const {
    const auto found = objects_.find(entity);
    if (found == objects_.end()) {
        return std::nullopt;
    }
    return found->second;
}

std::size_t PhotonGeometry::dynamic_object_count() const {
    std::size_t count = 0;
    for (const auto& entry : objects_) {
        count += scene_.is_dynamic(entry.second) ? 1 : 0;
    }
    return count;
}

BoundingSphere PhotonGeometry::sphere() const {
    const glm::vec3 lo = scene_.bounds_min();
    const glm::vec3 hi = scene_.bounds_max();
    if (lo.x > hi.x) {
        return {};
    }
    return {(lo + hi) * 0.5f, std::max(0.5f * glm::length(hi - lo), 1e-6f)};
}

}  // namespace luxel::lighting
