#pragma once

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
/// is not applied (it is the SkyLight's).
[[nodiscard]] std::shared_ptr<const lighting::SkyRadiance> make_sky_radiance(
    const scene::SkySpec& spec, const glm::vec3& towards_sun);

/// The direction towards the sun of `scene` in its rest pose: its brightest enabled
/// directional light (shining down its node's -z), or 45 degrees up when it has none.
[[nodiscard]] glm::vec3 sun_direction(const scene::Scene& scene);

/// An entity named "sky" with the SkyLight `spec` describes (the sun from sun_direction for a
/// daylight sky); null_entity for SkySpec::Kind::None.
ecs::Entity add_sky(ecs::Registry& registry, const scene::Scene& scene, const scene::SkySpec& spec);

}  // namespace luxel::world
