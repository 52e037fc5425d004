#pragma once

// Shared by the stability tests: loading a prepared level (optionally edited first), driving a
// LightingSystem to convergence, and checking every light-map value.

#include <cmath>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "luxel/ecs/transform_system.hpp"
#include "luxel/lighting/core/lighting_system.hpp"
#include "luxel/runtime/clock.hpp"
#include "luxel/scene/gltf.hpp"
#include "luxel/world/animation_system.hpp"
#include "luxel/world/scene_instance.hpp"
#include "test_paths.hpp"
#include "texel_visit.hpp"

namespace luxel::testing {

inline scene::Scene load_prepared(const std::string& name) {
    return scene::load_gltf(luxel::testing::source_dir() / "assets" / "levels" / "prepared" /
                            (name + ".glb"));
}

/// A level in a registry with its LightingSystem.
struct LitLevel {
    ecs::Registry registry;
    world::SceneInstance instance;
    ecs::TransformSystem transforms{registry};
    JobSystem jobs{2};
    std::unique_ptr<lighting::LightingSystem> lighting;
    double time = 0.0;

    /// `clock` times the scheduler's work units: a ManualClock that never advances makes every
    /// unit cost nothing, so each frame does all the work queued (deterministic, whatever the
    /// machine's load).
    LitLevel(scene::Scene scene, lighting::LightingConfig config, bool animate = false,
             const Clock& clock = SteadyClock::instance()) {
        world::InstantiateOptions options;
        options.play_animations = animate;
        instance =
            world::instantiate(registry, std::make_shared<scene::Scene>(std::move(scene)), options);
        transforms.update();
        lighting = std::make_unique<lighting::LightingSystem>(registry, jobs, config, clock);
    }

    const lighting::LightingStats& frame(double budget_ms, double dt = 1.0 / 30.0) {
        time += dt;
        world::update_animations(registry, dt);
        world::update_light_switches(registry, dt);
        transforms.update();
        return lighting->update(budget_ms, time);
    }

    /// What is still pending, for failure messages.
    [[nodiscard]] std::string pending() const {
        const auto& census = lighting->plan().census();
        return "pending groups " + std::to_string(lighting->photons().pending_groups().size()) +
               ", AIM requests " + std::to_string(lighting->maps().aim_requests().size()) +
               ", gather requests " + std::to_string(lighting->maps().gather_requests().size()) +
               ", caustics pending " + std::to_string(lighting->photons().caustics_pending()) +
               ", queued units " + std::to_string(lighting->scheduler().pending_total()) +
               ", moving " + std::to_string(census.moving_objects) + ", geometry changes " +
               std::to_string(census.geometry_changes);
    }

    /// Unlimited budget until converged; returns the frames it took (limit + 1: never).
    int converge(int limit) {
        for (int i = 1; i <= limit; ++i) {
            frame(1e9);
            if (lighting->plan().census().converged) {
                return i;
            }
        }
        return limit + 1;
    }
};

/// Small photon counts so that stiff cases stay fast; the gather is not what these test.
inline lighting::LightingConfig stability_config(std::uint32_t groups, std::uint32_t per_group) {
    lighting::LightingConfig config;
    config.photons.selective.groups = groups;
    config.photons.selective.per_group = per_group;
    config.photons.caustics.photons_per_pair = 2000;
    config.gather.rays_per_texel = 16;
    config.texels_per_gather_unit = 1u << 20;
    config.texels_per_aim_unit = 1u << 20;
    return config;
}

inline bool finite_non_negative(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && v.x >= 0.0f &&
           v.y >= 0.0f && v.z >= 0.0f;
}

}  // namespace luxel::testing
