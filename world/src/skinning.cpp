#include "luxel/world/skinning.hpp"

#include "luxel/ecs/transform.hpp"
#include "luxel/scene/components.hpp"
#include "luxel/scene/skin.hpp"

namespace luxel::world {

std::vector<glm::mat4> current_joint_matrices(const ecs::Registry& registry,
                                              const SkinnedMesh& skinned) {
    const scene::Skin& skin = skinned.source->skins.at(static_cast<std::size_t>(skinned.skin));
    std::vector<glm::mat4> matrices(skin.joints.size(), glm::mat4(1.0f));
    for (std::size_t j = 0; j < skin.joints.size(); ++j) {
        const ecs::Entity joint = j < skinned.joints.size() ? skinned.joints[j] : ecs::null_entity;
        const ecs::WorldTransform* world =
            registry.valid(joint) ? registry.try_get<ecs::WorldTransform>(joint) : nullptr;
        // Without its joint the vertex stays where the bind pose put it: world(joint) is then
        // the inverse of the inverse bind matrix, and their product the identity.
        matrices[j] =
            world != nullptr ? world->matrix * skin.inverse_bind_matrices.at(j) : glm::mat4(1.0f);
    }
    return matrices;
}

std::size_t update_skins(ecs::Registry& registry) {
    std::vector<std::pair<ecs::Entity, std::vector<glm::mat4>>> moved;
    // A game that took the MeshInstance away (to hide the figure) is left alone.
    for (auto [entity, skinned, instance] : registry.view<SkinnedMesh, scene::MeshInstance>()) {
        std::vector<glm::mat4> matrices = current_joint_matrices(registry, skinned);
        if (matrices != skinned.posed_with) {
            moved.emplace_back(entity, std::move(matrices));
        }
    }
    // Replaced after the view: a replace notifies observers, which must not run mid-iteration.
    for (auto& [entity, matrices] : moved) {
        SkinnedMesh& skinned = registry.get<SkinnedMesh>(entity);
        const scene::Mesh& bind = skinned.source->meshes.at(static_cast<std::size_t>(skinned.mesh));
        auto posed = std::make_shared<const scene::Mesh>(scene::posed_mesh(bind, matrices));
        auto joints = std::make_shared<const std::vector<glm::mat4>>(matrices);
        skinned.posed_with = std::move(matrices);
        registry.replace<scene::MeshInstance>(entity, skinned.source, skinned.mesh,
                                              std::move(posed), std::move(joints));
    }
    return moved.size();
}

}  // namespace luxel::world
