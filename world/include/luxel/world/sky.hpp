#pragma once

#include <cstddef>
#include <memory>

#include <glm/glm.hpp>

#include "luxel/ecs/registry.hpp"
#include "luxel/lighting/core/sky_radiance.hpp"
#include "luxel/scene/scene.hpp"

/// The sky of a level as an entity: a SkySpec (the level's extras or --sky) made into a
/// SkyLight (docs/LEVELS.md, "Sky").
namespace luxel::world {

/// The radiance a spec describes: a uniform sky, a daylight sky for a sun in direction
/// `towards_sun`, or the environment map read from its file (throws luxel::Error naming the
/// file when it cannot be read or is too large). Null for SkySpec::Kind::None. The spec's scale
/// is not applied (it is the SkyLight's). A spec with a ground gets lighting::with_ground, lit
/// by the sky and, for daylight, by `sun_irradiance` (W/m^2 facing the sun) at its elevation.
[[nodiscard]] std::shared_ptr<const lighting::SkyRadiance> make_sky_radiance(
    const scene::SkySpec& spec, const glm::vec3& towards_sun,
    const glm::vec3& sun_irradiance = glm::vec3(0.0f));

/// The sun of `scene`: its brightest enabled directional light's node, or -1 without one.
[[nodiscard]] int sun_node(const scene::Scene& scene);

/// The direction towards the sun of `scene` in its rest pose: sun_node's light (shining down
/// its node's -z), or 45 degrees up when it has none.
[[nodiscard]] glm::vec3 sun_direction(const scene::Scene& scene);

/// A daylight sky that turns with its sun (time of day): update_sky rebuilds the entity's
/// SkyLight radiance for the sun entity's direction whenever that has turned by more than
/// kTurnDegrees since the sky was made.
struct DaylightSun {
    static constexpr float kTurnDegrees = 0.25f;
    ecs::Entity sun = ecs::null_entity;  ///< a DirectionalLight; it shines down its -z
    float turbidity = 3.0f;
    float irradiance = 1.0f;                  ///< W/m^2 the sky alone gives a horizontal face
    glm::vec3 towards_sun{0.0f, 1.0f, 0.0f};  ///< the direction the radiance was made for
    glm::vec3 ground{0.0f};                   ///< the spec's ground albedo (0: none)
    /// The sun's irradiance (0 while off) the ground was lit with: with a ground, a sun that
    /// brightens, dims or switches rebuilds the sky too.
    glm::vec3 sun_irradiance{0.0f};
};

/// An entity named "sky" with the SkyLight `spec` describes (the sun from sun_direction for a
/// daylight sky); null_entity for SkySpec::Kind::None. A daylight sky given the level's `sun`
/// entity (instantiate passes it) gets a DaylightSun, so it follows the sun at run time.
ecs::Entity add_sky(ecs::Registry& registry, const scene::Scene& scene, const scene::SkySpec& spec,
                    ecs::Entity sun = ecs::null_entity);

/// Rebuilds each DaylightSun's sky whose sun turned, or, for a sky with a ground, whose sun's
/// irradiance changed or was switched (patching its SkyLight, so the lighting
/// system re-emits its photons and re-gathers, and the renderer redraws the background); a sky
/// whose sun is gone, or points nowhere, stays as it is. Reads the sun's world transform from
/// its Transform hierarchy, so it may run before or after the TransformSystem; run it after
/// whatever turns the sun (animations, a game's clock) and before the lighting update. Returns
/// how many skies it rebuilt.
std::size_t update_sky(ecs::Registry& registry);

}  // namespace luxel::world
