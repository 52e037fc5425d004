#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/ecs/registry.hpp"

namespace luxel::renderer {

/// How a light's shadow map is laid out.
enum class ShadowKind : std::uint8_t {
    Cube,         ///< six faces around the light: point lights and spots wider than kWideSpot
    Perspective,  ///< one perspective map down the spot's axis
    Ortho,        ///< one orthographic map over the scene: directional lights
};

/// Spots with an outer half angle above this (radians) get a cube map: a single perspective
/// map would need a field of view near 180 degrees and waste its texels at the rim.
inline constexpr float kWideSpot = 1.2f;

/// An enabled punctual light as the direct pass needs it, in world space and radiometric
/// units (docs/UNITS.md).
struct FrameLight {
    ecs::Entity entity;
    int kind = 0;  ///< 0 point, 1 spot, 2 directional (shaders/render/lights.glsl)
    glm::vec3 position{0.0f};
    glm::vec3 direction{0.0f, 0.0f, -1.0f};  ///< spot axis / direction light travels (-z)
    /// Point: I = P / (4 pi) W/sr. Spot: I = P / (2 pi (1 - cos outer)) W/sr (the photon
    /// emitter's convention: the power fills the outer cone). Directional: E W/m^2.
    glm::vec3 intensity{0.0f};
    float cos_inner = 1.0f;
    float cos_outer = 0.0f;
    float outer_cone = 0.0f;
    /// Point and spot: the emitting sphere's radius, m; > 0 draws the light with soft shadows
    /// (SoftShadows). 0 for directional lights and for points.
    float radius = 0.0f;
    ShadowKind shadow = ShadowKind::Cube;
};

/// The enabled PointLight, SpotLight and DirectionalLight entities, placed by their
/// WorldTransform (or, without one, their Transform chain). Lights that deliver nothing (zero
/// power) are left out.
[[nodiscard]] std::vector<FrameLight> collect_lights(ecs::Registry& registry);

/// The world matrix of an entity: its WorldTransform, or the Transform chain computed now.
[[nodiscard]] glm::mat4 entity_world_matrix(const ecs::Registry& registry, ecs::Entity entity);

/// std140 mirror of `Light` in shaders/render/lights.glsl.
struct GpuLight {
    glm::vec4 position_kind{0.0f};
    glm::vec4 direction_far{0.0f};
    glm::vec4 intensity_shadow{0.0f};
    glm::vec4 params{0.0f};
    glm::mat4 shadow_matrix{1.0f};
    glm::mat4 shadow_inverse{1.0f};
};
static_assert(sizeof(GpuLight) == 192);

}  // namespace luxel::renderer
