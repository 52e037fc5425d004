#pragma once

#include <glm/glm.hpp>

#include "luxel/ecs/hierarchy.hpp"
#include "luxel/ecs/registry.hpp"
#include "luxel/ecs/transform.hpp"

// What the parts of PhotonWorld share (photon_geometry.cpp, light_groups.cpp).
namespace luxel::lighting {

namespace photon_world_support {

inline glm::mat4 world_matrix(const ecs::Registry& registry, ecs::Entity entity) {
    if (const auto* world = registry.try_get<ecs::WorldTransform>(entity)) {
        return world->matrix;
    }
    return ecs::compute_world_matrix(registry, entity);
}

}  // namespace photon_world_support

}  // namespace luxel::lighting
