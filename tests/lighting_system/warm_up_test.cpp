// The loading-screen warm-up ends: a lit, prepared level converges; a level with no light, or
// one luxel-prep never prepared, stops after a few updates and says why, instead of updating
// without effect until its time limit (issue 21: hundreds of thousands of empty updates, 20 s).
// Time is the injected clock's, which ticks on every reading: the limit is far beyond what a
// converging warm-up needs, and a warm-up that reached it failed.

#include <chrono>
#include <cstdio>
#include <memory>

#include <gtest/gtest.h>

#include "lacking_levels.hpp"
#include "luxel/ecs/transform_system.hpp"
#include "luxel/lighting/core/lighting_system.hpp"
#include "luxel/runtime/clock.hpp"
#include "luxel/world/scene_instance.hpp"
#include "ticking_clock.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;

using luxel::testing::TickingClock;

constexpr double kLimitMs = 1e6;  // a thousand seconds of ticks: never reached by a sound warm-up

LightingConfig small_config() {
    LightingConfig config;
    config.photons.selective.groups = 16;
    config.photons.selective.per_group = 8;
    config.gather.rays_per_texel = 8;
    config.texels_per_gather_unit = 4096;
    return config;
}

struct Level {
    ecs::Registry registry;
    world::SceneInstance instance;
    JobSystem jobs{2};
    TickingClock clock;
    std::unique_ptr<LightingSystem> lighting;

    explicit Level(scene::Scene level) {
        instance = world::instantiate(registry, std::make_shared<scene::Scene>(std::move(level)));
        ecs::TransformSystem(registry).update();
        lighting = std::make_unique<LightingSystem>(registry, jobs, small_config(), clock);
    }
};

TEST(WarmUp, ALitPreparedLevelConverges) {
    Level level(luxel::testing::prepared_cornell());
    const WarmUpResult result = level.lighting->warm_up(0.0, kLimitMs);
    EXPECT_EQ(result.end, WarmUpEnd::Converged) << describe(result);
    EXPECT_TRUE(result.why.empty());
    EXPECT_GT(level.lighting->maps().counters().texels_gathered, 0u);
    EXPECT_EQ(describe(result), "converged");
}

TEST(WarmUp, ALevelWithoutLightStopsAtOnceAndSaysWhy) {
    Level level(luxel::testing::without_light(luxel::testing::prepared_cornell()));
    const WarmUpResult result = level.lighting->warm_up(0.0, kLimitMs);
    EXPECT_EQ(result.end, WarmUpEnd::NoProgress) << describe(result);
    EXPECT_LE(result.updates, 2);
    EXPECT_EQ(result.why, "no light in the scene: no lighting work");
    EXPECT_EQ(describe(result), "no progress possible (no light in the scene: no lighting work)");
}

TEST(WarmUp, AnUnpreparedLevelStopsInBoundedUpdatesAndSaysWhy) {
    Level level(luxel::testing::unprepared(luxel::testing::prepared_cornell()));
    const WarmUpResult result = level.lighting->warm_up(0.0, kLimitMs);
    EXPECT_EQ(result.end, WarmUpEnd::NoProgress) << describe(result);
    EXPECT_LE(result.updates, 10);
    std::printf("[ figures  ] unprepared cornell: the warm-up stopped after %d updates\n",
                result.updates);
    EXPECT_EQ(result.why,
              "no light-mapped surface: global photons would have nowhere to be stored");
}

TEST(WarmUp, ATimeLimitStillEndsAWarmUpThatCouldGoOn) {
    Level level(luxel::testing::prepared_cornell());
    const WarmUpResult result = level.lighting->warm_up(0.0, 3.0);
    EXPECT_EQ(result.end, WarmUpEnd::TimeLimit);
    EXPECT_GE(result.updates, 1);
    EXPECT_EQ(describe(result), "time limit reached, not converged");
}

}  // namespace
