#pragma once

#include <memory>

#include <glm/glm.hpp>

#include "luxel/ecs/hierarchy.hpp"
#include "luxel/ecs/transform.hpp"
#include "luxel/lighting/core/photon_world.hpp"
#include "luxel/lighting/core/selective_emitter.hpp"

// What the parts of PhotonWorld share (photon_world.cpp: construction and sync();
// photon_world_geometry.cpp: meshes and materials into the ray scene; photon_world_lights.cpp:
// lights, their photon groups, probes and retraces; photon_world_caustics.cpp: the caustic
// lists).
namespace luxel::lighting {

struct PhotonWorld::LightRecord {
    std::unique_ptr<LightPhotons> photons;
    bool enabled = true;
    bool directional = false;
};

namespace photon_world_support {

inline glm::mat4 world_matrix(const ecs::Registry& registry, ecs::Entity entity) {
    if (const auto* world = registry.try_get<ecs::WorldTransform>(entity)) {
        return world->matrix;
    }
    return ecs::compute_world_matrix(registry, entity);
}

}  // namespace photon_world_support

}  // namespace luxel::lighting
