#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

#include "luxel/ecs/registry.hpp"
#include "luxel/lighting/components.hpp"
#include "luxel/lighting/core/light_source.hpp"
#include "luxel/lighting/core/photon_map.hpp"
#include "luxel/lighting/core/photon_world.hpp"
#include "luxel/lighting/core/ray_scene.hpp"

namespace luxel::lighting {

/// PhotonWorld's geometry (docs/METHOD.md §3): MeshInstance entities mirrored into the RayScene
/// (Dynamic ones as instances), their scene materials as TraceMaterials, caustic generators'
/// own optics for their specular materials, and the light-mapped surfaces photons are stored
/// on (each added to the photon map as it is found).
class PhotonGeometry {
  public:
    PhotonGeometry(const ecs::Registry& registry, PhotonMap& map, bool implicit_surfaces);

    /// Mirrors the entity's mesh (with its generator's optics, if it has a CausticGenerator).
    void add_mesh(ecs::Entity entity);
    /// Its photons stay until their groups' probes notice; its surfaces are not reused.
    void remove_mesh(ecs::Entity entity);
    /// A moved entity: a dynamic object's instance transform, a static one rebuilt in place.
    /// Returns whether the entity is an object of the ray scene.
    bool move(ecs::Entity entity);
    /// A mesh entity whose MeshInstance is a new pose of the mesh its object was made from (a
    /// skinned mesh, world::update_skins): the object's vertices moved in place and its BVH
    /// refitted, the change recorded as a move is. False (nothing done) for anything else: the
    /// caller removes and re-adds the mesh then.
    bool deform(ecs::Entity entity);
    /// A generator's edited component: its own materials rewritten in place.
    void set_generator_optics(ecs::Entity entity, const CausticGenerator& optics);
    /// A generator went away: its own materials are no longer used when its mesh is re-added.
    void forget_generator(ecs::Entity entity);
    /// Makes the edits visible to ray queries (RayScene::commit).
    void commit() { scene_.commit(); }
    /// Where geometry changed since the last clear_changes(): each object's box where it was and
    /// where it is now (empty: nothing was added, removed or moved).
    [[nodiscard]] const std::vector<GeometryChange>& changes() const { return changes_; }
    void clear_changes() { changes_.clear(); }

    [[nodiscard]] std::optional<ObjectId> object(ecs::Entity entity) const;
    /// Every mesh entity mirrored, with its object: an object's vertices and triangles are its
    /// MeshInstance's primitives concatenated in order (add_mesh).
    [[nodiscard]] const std::map<ecs::Entity, ObjectId>& objects() const { return objects_; }
    /// The sphere around the whole scene (directional lights' discs, caustic emitters).
    [[nodiscard]] BoundingSphere sphere() const;
    [[nodiscard]] std::size_t dynamic_object_count() const;
    [[nodiscard]] const RayScene& scene() const { return scene_; }
    [[nodiscard]] const std::vector<TraceMaterial>& materials() const { return materials_; }
    [[nodiscard]] const std::vector<SurfaceInfo>& surfaces() const { return surfaces_; }

  private:
    /// The table's entry for a scene material, one per (source, material, closed): `closed`
    /// only matters for a dielectric (TraceMaterial::closed).
    std::uint32_t material_index(const scene::Scene* source, int material, bool closed);
    /// Whether primitive `p` of the entity's mesh is a closed dielectric (is_closed_surface,
    /// asked once per source mesh and primitive; a posed mesh is asked each time).
    bool closed_dielectric(const scene::MeshInstance& instance, std::size_t p);
    std::uint32_t generator_material(ecs::Entity entity, std::uint32_t shared,
                                     const CausticGenerator& optics);

    const ecs::Registry& registry_;
    PhotonMap& map_;
    bool implicit_surfaces_;
    RayScene scene_;
    std::vector<SurfaceInfo> surfaces_;
    std::vector<TraceMaterial> materials_;
    std::map<std::tuple<const scene::Scene*, int, bool>, std::uint32_t> material_ids_;
    /// (source, mesh, primitive) -> whether that primitive closes up.
    std::map<std::tuple<const scene::Scene*, int, std::size_t>, bool> closed_primitives_;
    /// (generator entity, shared material id) -> the generator's own material id.
    std::map<std::pair<ecs::Entity, std::uint32_t>, std::uint32_t> generator_materials_;
    /// An object's box around its own vertices (object space for dynamic objects, world space
    /// for static ones, as RayScene keeps them) and where that box lies as last added or moved:
    /// a move records the latter as where the object was.
    struct ObjectBoxes {
        AxisBox local;
        AxisBox world;
    };

    std::map<ecs::Entity, ObjectId> objects_;
    /// Objects made from a posed mesh (MeshInstance::posed): the scene and mesh it poses, which
    /// a later pose must share to be deformed in place.
    std::map<ecs::Entity, std::pair<const scene::Scene*, int>> posed_from_;
    std::map<ObjectId, ObjectBoxes> object_boxes_;
    std::vector<GeometryChange> changes_;
};

}  // namespace luxel::lighting
