#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/scene/scene.hpp"

/// The generic components of an entity made from a scene node: what it draws, whether it moves,
/// its camera, name and origin. Not lighting: the renderer, the photon tracer and a game all read
/// them. Change them through Registry::patch/replace so systems see the change.
namespace luxel::scene {

/// The geometry an entity draws and traces: one mesh of a loaded scene, which also supplies the
/// materials. Shared, immutable: many entities may instance the same mesh.
struct MeshInstance {
    MeshInstance() = default;
    MeshInstance(std::shared_ptr<const Scene> scene, int index,
                 std::shared_ptr<const Mesh> pose = nullptr,
                 std::shared_ptr<const std::vector<glm::mat4>> joints = nullptr)
        : source(std::move(scene)),
          mesh(index),
          posed(std::move(pose)),
          joint_matrices(std::move(joints)) {}

    std::shared_ptr<const Scene> source;
    int mesh = -1;
    /// The mesh as it stands now, when it is not the scene's own: a skinned mesh in its current
    /// pose (world::update_skins replaces the component with each new pose, so observers see
    /// a changed mesh). Null: the scene's mesh as loaded.
    std::shared_ptr<const Mesh> posed;
    /// When `posed` is the scene's mesh skinned (scene::posed_mesh): the joint matrices it was
    /// posed with, one per joint of the skin. A renderer skins the scene's own mesh with them
    /// in its vertex stage, so a new pose uploads these matrices rather than every vertex;
    /// the CPU's `posed` is what the ray scene traces. Null for every other mesh.
    std::shared_ptr<const std::vector<glm::mat4>> joint_matrices;

    [[nodiscard]] const Mesh& geometry() const {
        return posed ? *posed : source->meshes.at(static_cast<std::size_t>(mesh));
    }
};

/// Tag: the entity moves (animated, or flagged dynamic). Static geometry goes into one BVH
/// built once; dynamic entities are instanced so motion only updates a transform.
struct Dynamic {};

/// A camera from the scene file (looks down its entity's -z).
struct CameraComponent {
    Camera camera;
};

/// A readable name, from the glTF node.
struct Name {
    std::string value;
};

/// Where an entity came from: its node index in the source scene.
struct SceneNode {
    int index = -1;
};

}  // namespace luxel::scene
