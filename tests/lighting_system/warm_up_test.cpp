// The loading-screen warm-up ends: a lit, prepared level converges; a level with no light, or
// one luxel-prep never prepared, stops after a few updates and says why, instead of updating
// without effect until its time limit (issue 21: hundreds of thousands of empty updates, 20 s).
// Time is the injected clock's, which ticks on every reading: the limit is far beyond what a
// converging warm-up needs, and a warm-up that reached it failed.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

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

    explicit Level(scene::Scene level, LightingConfig config = small_config()) {
        instance = world::instantiate(registry, std::make_shared<scene::Scene>(std::move(level)));
        ecs::TransformSystem(registry).update();
        lighting = std::make_unique<LightingSystem>(registry, jobs, config, clock);
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

TEST(WarmUp, ProgressRisesToCompletionAndTheTimeIsAccountedByKind) {
    Level level(luxel::testing::prepared_cornell());
    std::vector<WarmUpProgress> seen;
    const WarmUpResult result = level.lighting->warm_up(
        0.0, kLimitMs, [&](const WarmUpProgress& progress) { seen.push_back(progress); }, 50.0);
    ASSERT_EQ(result.end, WarmUpEnd::Converged) << describe(result);
    // Reported every 50 ms of the clock and once at the end, rising to all of the passes.
    ASSERT_GE(seen.size(), 3u);
    for (std::size_t i = 1; i < seen.size(); ++i) {
        EXPECT_GE(seen[i].share, seen[i - 1].share);
        EXPECT_GT(seen[i].elapsed_ms, seen[i - 1].elapsed_ms);
        EXPECT_GE(seen[i].updates, seen[i - 1].updates);
    }
    // Every report but the end's comes at least the interval after the one before it.
    for (std::size_t i = 1; i + 1 < seen.size(); ++i) {
        EXPECT_GE(seen[i].elapsed_ms - seen[i - 1].elapsed_ms, 50.0);
    }
    EXPECT_LT(seen.front().share, 1.0);
    EXPECT_DOUBLE_EQ(seen.back().share, 1.0);
    EXPECT_EQ(seen.back().updates, result.updates);
    EXPECT_DOUBLE_EQ(level.lighting->maps().refined_share(), 1.0);
    // The kinds' times are the scheduler's: gathers and AIM rebuilds ran, and the line names
    // the largest first.
    const auto ms = [&](WorkKind kind) { return result.kind_ms[static_cast<std::size_t>(kind)]; };
    EXPECT_GT(ms(WorkKind::IimGather), 0.0);
    EXPECT_GT(ms(WorkKind::AimRebuild), 0.0);
    const std::string line = describe_time(result);
    EXPECT_NE(line.find("iim_gather "), std::string::npos) << line;
    EXPECT_NE(line.find(" ms"), std::string::npos) << line;
    double largest = 0.0;
    std::string first;
    for (std::size_t kind = 0; kind < kWorkKindCount; ++kind) {
        if (result.kind_ms[kind] > largest) {
            largest = result.kind_ms[kind];
            first = std::string(name(static_cast<WorkKind>(kind)));
        }
    }
    EXPECT_EQ(line.rfind(first + " ", 0), 0u) << line;
}

TEST(WarmUp, AWarmUpThatStopsAtOnceReportsOnce) {
    Level level(luxel::testing::without_light(luxel::testing::prepared_cornell()));
    std::vector<WarmUpProgress> seen;
    const WarmUpResult result = level.lighting->warm_up(
        0.0, kLimitMs, [&](const WarmUpProgress& progress) { seen.push_back(progress); });
    EXPECT_EQ(result.end, WarmUpEnd::NoProgress);
    ASSERT_EQ(seen.size(), 1u);  // the end's report
    EXPECT_EQ(seen.front().updates, result.updates);
    EXPECT_GE(seen.front().share, 0.0);
    EXPECT_LE(seen.front().share, 1.0);
}

TEST(WarmUp, LargerUnitsChangeTheUpdatesItTakesNotTheMaps) {
    // The warm-up's units are warm_up_unit_scale times the frame's: no budget to fit. Fewer
    // updates, the same light maps.
    LightingConfig frame_sized = small_config();
    frame_sized.texels_per_gather_unit = 16;
    frame_sized.warm_up_unit_scale = 1;
    LightingConfig scaled = frame_sized;
    scaled.warm_up_unit_scale = 16;
    scaled.scheduler.record_units = true;
    Level small_units(luxel::testing::prepared_cornell(), frame_sized);
    Level large_units(luxel::testing::prepared_cornell(), scaled);
    const WarmUpResult small_result = small_units.lighting->warm_up(0.0, kLimitMs);
    const WarmUpResult large_result = large_units.lighting->warm_up(0.0, kLimitMs);
    ASSERT_EQ(small_result.end, WarmUpEnd::Converged) << describe(small_result);
    ASSERT_EQ(large_result.end, WarmUpEnd::Converged) << describe(large_result);
    EXPECT_LT(large_result.updates * 2, small_result.updates);
    std::printf("[ figures  ] cornell warm-up: %d updates with frame-sized units, %d at 16x\n",
                small_result.updates, large_result.updates);
    const auto small_pages = small_units.lighting->maps().iim_pages();
    const auto large_pages = large_units.lighting->maps().iim_pages();
    ASSERT_EQ(small_pages.size(), large_pages.size());
    // Passes can start in another order relative to the AIM rebuilds (a pass that read an AIM
    // rebuilt under it gathers again, with the next pass's pattern), so texels hold other
    // samples of the same estimate: the maps agree in their totals and within the gathers'
    // noise per texel, not bit for bit.
    glm::dvec3 small_total(0.0);
    glm::dvec3 large_total(0.0);
    double squared_difference = 0.0;
    double squared_value = 0.0;
    for (std::size_t p = 0; p < small_pages.size(); ++p) {
        const auto& a = small_pages[p].current.texels;
        const auto& b = large_pages[p].current.texels;
        ASSERT_EQ(a.size(), b.size());
        for (std::size_t t = 0; t < a.size(); ++t) {
            small_total += glm::dvec3(a[t]);
            large_total += glm::dvec3(b[t]);
            squared_difference += glm::dot(glm::dvec3(a[t] - b[t]), glm::dvec3(a[t] - b[t]));
            squared_value += glm::dot(glm::dvec3(a[t]), glm::dvec3(a[t]));
        }
    }
    ASSERT_GT(squared_value, 0.0);
    const double total_ratio = (large_total.x + large_total.y + large_total.z) /
                               (small_total.x + small_total.y + small_total.z);
    const double relative_rms = std::sqrt(squared_difference / squared_value);
    std::printf("[ figures  ] IIM at 16x units against frame-sized: total %.5f, relRMS %.4f\n",
                total_ratio, relative_rms);
    EXPECT_NEAR(total_ratio, 1.0, 0.005);
    EXPECT_LT(relative_rms, 0.02);
    // After the warm-up a frame's units are the frame's size again: the light dims, and the
    // gathers it causes come in units of 16 texels.
    large_units.registry.view<PointLight>().each([&](ecs::Entity light, PointLight&) {
        large_units.registry.patch<PointLight>(light,
                                               [](PointLight& point) { point.power *= 0.5f; });
    });
    std::size_t gather_units = 0;
    for (int frame = 0; frame < 200 && gather_units == 0; ++frame) {
        const LightingStats& stats = large_units.lighting->update(1e9, 1.0);
        for (const UnitRecord& unit : stats.schedule.units) {
            if (unit.kind == WorkKind::IimGather) {
                EXPECT_EQ(unit.size, 16.0);
                ++gather_units;
            }
        }
    }
    EXPECT_GT(gather_units, 0u);
}

}  // namespace
