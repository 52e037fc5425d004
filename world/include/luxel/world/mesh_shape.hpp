#pragma once

#include <memory>

#include "luxel/ecs/registry.hpp"
#include "luxel/scene/scene.hpp"

namespace luxel::world {

/// Gives `entity`'s mesh a new shape: the general per-frame vertex update for meshes that
/// deform (water, a flag, cloth, a soft body). A game computes the new positions and normals
/// of the entity's mesh each frame and hands them over here; `shape` keeps the mesh's topology
/// (the same primitives, vertex counts and indices) and may change nothing else.
///
/// The entity's MeshInstance is replaced by one that poses the scene's mesh as `shape`
/// (MeshInstance::posed), so every observer sees the change: the ray scene moves the object's
/// vertices in place and refits its BVH (PhotonGeometry::deform; the first call of an entity
/// instantiated without a posed shape rebuilds it once), the photon paths and caustics through
/// its old and new bounds are retraced, and the renderer uploads the new vertices. The entity
/// becomes Dynamic if it was not: a static object would rebuild the static BVH every frame.
///
/// A light-mapped surface keeps its texels where its shape was when the lighting first saw it
/// (light maps are laid out once): right for small deformations (waves of a few centimetres),
/// wrong for large ones, which should not carry a light map (as skinned meshes do not).
///
/// Throws luxel::Error naming the entity's Name when it has no MeshInstance, when `shape`'s
/// primitives or vertex counts differ from its mesh's, or when a position or normal is not
/// finite: nothing is changed then.
void set_mesh_shape(ecs::Registry& registry, ecs::Entity entity,
                    std::shared_ptr<const scene::Mesh> shape);

}  // namespace luxel::world
