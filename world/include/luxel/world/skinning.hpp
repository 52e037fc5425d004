#pragma once

#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/ecs/registry.hpp"
#include "luxel/scene/scene.hpp"

namespace luxel::world {

/// A skinned mesh (glTF skin): its entity holds the MeshInstance in the current pose, in world
/// space (the entity has an identity Transform and no parent: glTF places a skinned mesh by its
/// joints alone). The joints are ordinary entities, moved by animations or by the game.
///
/// A new pose replaces the MeshInstance with the mesh skinned on the CPU (scene::posed_mesh)
/// and the joint matrices it was skinned with: the ray scene moves the object's vertices in
/// place and refits its BVH (PhotonGeometry::deform), the photon paths through its old and new
/// bounds retraced (0.47 ms a pose for 10,000 vertices on two cores, docs/PERFORMANCE.md); the
/// renderer skins the bind mesh it uploaded once with the joint matrices in its vertex stage.
struct SkinnedMesh {
    std::shared_ptr<const scene::Scene> source;
    int skin = -1;
    int mesh = -1;
    /// One per joint of the skin: the entity whose WorldTransform poses it.
    std::vector<ecs::Entity> joints;
    /// The joint matrices the MeshInstance was posed with; a frame whose joints give the same
    /// ones poses nothing.
    std::vector<glm::mat4> posed_with;
};

/// The skinned mesh's joint matrices in the joints' current WorldTransforms (a joint entity
/// that is gone keeps its bind pose).
[[nodiscard]] std::vector<glm::mat4> current_joint_matrices(const ecs::Registry& registry,
                                                            const SkinnedMesh& skinned);

/// Poses every SkinnedMesh whose joints moved since its last pose: replaces its MeshInstance
/// with the mesh skinned to the joints' WorldTransforms. Run after the TransformSystem and
/// before the lighting and the renderer read the frame. Returns how many meshes it posed.
std::size_t update_skins(ecs::Registry& registry);

}  // namespace luxel::world
