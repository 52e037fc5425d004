#include "frame_lights.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/constants.hpp>

#include "luxel/ecs/hierarchy.hpp"
#include "luxel/ecs/transform.hpp"
#include "luxel/lighting/components.hpp"

namespace luxel::renderer {
namespace {

bool delivers_light(const glm::vec3& value) {
    return glm::any(glm::greaterThan(value, glm::vec3(0.0f)));
}

/// A component's radius as the frame uses it: a negative or non-finite one is a point.
float sphere_radius(float radius) {
    return std::isfinite(radius) && radius > 0.0f ? radius : 0.0f;
}

FrameLight placed(const ecs::Registry& registry, ecs::Entity entity) {
    FrameLight light;
    light.entity = entity;
    const glm::mat4 world = entity_world_matrix(registry, entity);
    light.position = glm::vec3(world[3]);
    const glm::vec3 axis = -glm::vec3(world[2]);
    // The same axis PhotonWorld gives the photon emitter, so photons and pixels agree.
    light.direction = glm::length(axis) > 0.0f ? glm::normalize(axis) : glm::vec3(0, 0, -1);
    return light;
}

}  // namespace

glm::mat4 entity_world_matrix(const ecs::Registry& registry, ecs::Entity entity) {
    if (const auto* world = registry.try_get<ecs::WorldTransform>(entity)) {
        return world->matrix;
    }
    return ecs::compute_world_matrix(registry, entity);
}

std::vector<FrameLight> collect_lights(ecs::Registry& registry) {
    std::vector<FrameLight> lights;
    constexpr float pi = glm::pi<float>();
    for (auto [entity, point] : registry.view<lighting::PointLight>()) {
        if (!point.enabled || !delivers_light(point.power)) {
            continue;
        }
        FrameLight light = placed(registry, entity);
        light.kind = 0;
        light.intensity = point.power / (4.0f * pi);
        light.radius = sphere_radius(point.radius);
        light.shadow = ShadowKind::Cube;
        lights.push_back(light);
    }
    for (auto [entity, spot] : registry.view<lighting::SpotLight>()) {
        if (!spot.enabled || !delivers_light(spot.power)) {
            continue;
        }
        FrameLight light = placed(registry, entity);
        light.kind = 1;
        const float outer = std::clamp(spot.outer_cone, 1e-4f, pi);
        light.outer_cone = outer;
        light.cos_outer = std::cos(outer);
        light.cos_inner = std::cos(std::clamp(spot.inner_cone, 0.0f, outer));
        light.intensity = spot.power / (2.0f * pi * std::max(1.0f - light.cos_outer, 1e-8f));
        light.radius = sphere_radius(spot.radius);
        light.shadow = outer > kWideSpot ? ShadowKind::Cube : ShadowKind::Perspective;
        lights.push_back(light);
    }
    for (auto [entity, sun] : registry.view<lighting::DirectionalLight>()) {
        if (!sun.enabled || !delivers_light(sun.irradiance)) {
            continue;
        }
        FrameLight light = placed(registry, entity);
        light.kind = 2;
        light.intensity = sun.irradiance;
        light.shadow = ShadowKind::Ortho;
        lights.push_back(light);
    }
    return lights;
}

}  // namespace luxel::renderer
