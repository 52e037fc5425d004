#pragma once

#include <memory>
#include <vector>

#include "luxel/ecs/registry.hpp"
#include "luxel/scene/scene.hpp"

namespace luxel::world {

/// Plays one glTF animation of a scene onto entities: channel i drives targets[i]'s Transform.
struct AnimationPlayer {
    std::shared_ptr<const scene::Scene> source;
    int animation = -1;
    std::vector<ecs::Entity> targets;  ///< one per channel; null_entity skips the channel
    /// Seconds into the animation, kept within [0, duration) when looping, so precision does
    /// not decay however long the game runs.
    double time = 0.0;
    double speed = 1.0;
    bool loop = true;
    bool playing = true;
};

/// Switches a light component on for `on` seconds of every `period`, starting at `phase`
/// (extras.luxel.switch in a level file).
struct LightSwitch {
    double period = 4.0;
    double on = 2.0;
    double phase = 0.0;
    double time = 0.0;  ///< seconds since the switch started, wrapped to one period
};

/// Advances every playing AnimationPlayer by dt seconds and writes the sampled translation,
/// rotation and scale into the targets' Transforms with Registry::patch, so moved entities
/// appear in the Transform change list. Stale or missing targets are skipped. Run it in
/// Phase::Simulation, before the TransformSystem.
void update_animations(ecs::Registry& registry, double dt_seconds);

/// Advances every LightSwitch and sets the `enabled` flag of the entity's PointLight, SpotLight,
/// DirectionalLight or AreaLight, patching only when the state flips.
void update_light_switches(ecs::Registry& registry, double dt_seconds);

/// Whether a switch is on at `time` seconds after it started.
[[nodiscard]] bool switch_is_on(const LightSwitch& light_switch, double time);

}  // namespace luxel::world
