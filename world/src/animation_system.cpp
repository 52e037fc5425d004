#include "luxel/world/animation_system.hpp"

#include <cmath>

#include "luxel/ecs/transform.hpp"
#include "luxel/lighting/components.hpp"
#include "luxel/scene/animation.hpp"

namespace luxel::world {
namespace {

/// Wraps t into [0, period). fmod keeps the phase exact enough over any run length: the stored
/// time never grows beyond one period, so float sampling loses no precision.
double wrap(double t, double period) {
    if (!(period > 0.0)) {
        return 0.0;
    }
    double wrapped = std::fmod(t, period);
    if (wrapped < 0.0) {
        wrapped += period;
    }
    return wrapped;
}

template <class Light>
void set_enabled_if_present(ecs::Registry& registry, ecs::Entity entity, bool on) {
    if (auto* light = registry.try_get<Light>(entity); light != nullptr && light->enabled != on) {
        registry.patch<Light>(entity, [on](Light& l) { l.enabled = on; });
    }
}

/// A sampled value the node can take: finite (keys near the float maximum can overflow in
/// between, and a cubic spline can overshoot them), with no scale component closer to 0 than
/// scene::kMinAnimatedScale. False means the pose is skipped: the node keeps its last value.
bool usable_value(glm::vec4& value, scene::AnimatedProperty property) {
    if (!std::isfinite(value.x) || !std::isfinite(value.y) || !std::isfinite(value.z) ||
        !std::isfinite(value.w)) {
        return false;
    }
    if (property == scene::AnimatedProperty::Scale) {
        for (int axis = 0; axis < 3; ++axis) {
            if (std::abs(value[axis]) < scene::kMinAnimatedScale) {
                value[axis] = std::copysign(scene::kMinAnimatedScale, value[axis]);
            }
        }
    }
    return true;
}

}  // namespace

void update_animations(ecs::Registry& registry, double dt_seconds) {
    registry.view<AnimationPlayer>().each([&](AnimationPlayer& player) {
        if (!player.playing || !player.source || player.animation < 0) {
            return;
        }
        const scene::Animation& animation =
            player.source->animations.at(static_cast<std::size_t>(player.animation));
        const double duration = animation.duration();
        player.time += dt_seconds * player.speed;
        if (player.loop) {
            player.time = wrap(player.time, duration);
        } else if (player.time >= duration) {
            player.time = duration;
            player.playing = false;  // the last pose below is still applied
        }
        const auto t = static_cast<float>(player.time);
        for (std::size_t c = 0; c < animation.channels.size() && c < player.targets.size(); ++c) {
            const ecs::Entity target = player.targets[c];
            if (!registry.valid(target) || !registry.has<ecs::Transform>(target)) {
                continue;
            }
            const scene::AnimationChannel& channel = animation.channels[c];
            if (channel.sampler < 0 ||
                static_cast<std::size_t>(channel.sampler) >= animation.samplers.size()) {
                continue;
            }
            glm::vec4 value = animation.samplers[static_cast<std::size_t>(channel.sampler)].sample(
                t, channel.property);
            if (!usable_value(value, channel.property)) {
                continue;
            }
            registry.patch<ecs::Transform>(target, [&](ecs::Transform& transform) {
                switch (channel.property) {
                    case scene::AnimatedProperty::Translation:
                        transform.translation = scene::as_vec3(value);
                        break;
                    case scene::AnimatedProperty::Rotation:
                        transform.rotation = scene::as_quat(value);
                        break;
                    case scene::AnimatedProperty::Scale:
                        transform.scale = scene::as_vec3(value);
                        break;
                }
            });
        }
    });
}

bool switch_is_on(const LightSwitch& light_switch, double time) {
    const double phase_time = wrap(time - light_switch.phase, light_switch.period);
    return phase_time < light_switch.on;
}

void update_light_switches(ecs::Registry& registry, double dt_seconds) {
    registry.view<LightSwitch>().each([&](ecs::Entity entity, LightSwitch& light_switch) {
        light_switch.time = wrap(light_switch.time + dt_seconds, light_switch.period);
        const bool on = switch_is_on(light_switch, light_switch.time);
        set_enabled_if_present<lighting::PointLight>(registry, entity, on);
        set_enabled_if_present<lighting::SpotLight>(registry, entity, on);
        set_enabled_if_present<lighting::DirectionalLight>(registry, entity, on);
        set_enabled_if_present<lighting::AreaLight>(registry, entity, on);
    });
}

}  // namespace luxel::world
