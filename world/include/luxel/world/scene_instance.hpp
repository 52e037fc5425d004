#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "luxel/ecs/registry.hpp"
#include "luxel/scene/scene.hpp"

namespace luxel::world {

/// What instantiate() created: one entity per scene node (same order as scene.nodes) and one
/// entity per animation (holding its AnimationPlayer).
struct SceneInstance {
    std::shared_ptr<const scene::Scene> source;
    std::vector<ecs::Entity> nodes;
    std::vector<ecs::Entity> animations;
    /// One per node with a skin: the entity that holds its mesh in the current pose
    /// (world/skinning.hpp), in the order of the nodes.
    std::vector<ecs::Entity> skinned;
    ecs::Entity sky = ecs::null_entity;  ///< the level's sky (world/sky.hpp), if it has one

    /// The entity of the first node with this name, or null_entity.
    [[nodiscard]] ecs::Entity find(const std::string& node_name) const;
};

struct InstantiateOptions {
    bool play_animations = true;  ///< start every animation playing, looped
    /// The sky instead of the level's own (--sky; Kind::None removes it), when set.
    std::optional<scene::SkySpec> sky;
};

/// Turns a loaded scene into entities and components:
/// - every node: Transform (its local TRS), Name, SceneNode, and the hierarchy (set_parent);
/// - a mesh: MeshInstance; with an emissive material: AreaLight; with a specular material
///   (Material::is_specular): CausticGenerator from the first such material; with a light-map
///   layout in the node's extras.luxel (luxel-prep's output): LightmappedSurface;
/// - a glTF light: PointLight / SpotLight / DirectionalLight in watts (light.hpp converts),
///   enabled unless extras.luxel.enabled is false; a `switch` object adds a LightSwitch;
/// - a camera: CameraComponent;
/// - a mesh with extras.luxel.wave: VertexWave, and its MeshInstance shaped by the wave at
///   time 0 (world/vertex_wave.hpp; update_waves moves it);
/// - Dynamic when scene.is_dynamic(node) (a waved mesh is);
/// - a mesh with a skin: not on the node's entity but on an entity of its own, with an identity
///   Transform and no parent (glTF places a skinned mesh by its joints alone): SkinnedMesh,
///   MeshInstance in the rest pose, Dynamic, Name and SceneNode as the node's; AreaLight when
///   emissive; no CausticGenerator and no light map (it deforms);
/// - each animation: an entity with an AnimationPlayer whose channels target the node entities;
/// - the level's sky (or options.sky): an entity with a SkyLight (world/sky.hpp).
/// The scene is shared, not copied: MeshInstance and AnimationPlayer keep it alive. Throws
/// luxel::Error naming the node when its light-map layout is malformed or names a primitive
/// without TEXCOORD_1.
SceneInstance instantiate(ecs::Registry& registry, std::shared_ptr<const scene::Scene> scene,
                          const InstantiateOptions& options = {});

}  // namespace luxel::world
