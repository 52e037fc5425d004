// The ordered system pipeline.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "luxel/ecs/pipeline.hpp"
#include "luxel/ecs/transform_system.hpp"
#include "test_components.hpp"

namespace luxel::ecs {
namespace {

TEST(Pipeline, RunsPhasesInOrderAndSystemsInInsertionOrder) {
    Pipeline pipeline;
    std::vector<std::string> calls;
    const auto record = [&calls](std::string name) {
        return [&calls, name](Registry&, double) { calls.push_back(name); };
    };
    pipeline.add(Phase::Render, "draw", record("draw"));
    pipeline.add(Phase::Simulation, "physics", record("physics"));
    pipeline.add(Phase::Input, "keyboard", record("keyboard"));
    pipeline.add(Phase::Simulation, "animation", record("animation"));
    pipeline.add(Phase::Lighting, "gi", record("gi"));
    pipeline.add(Phase::Transforms, "transforms", record("transforms"));

    Registry registry;
    pipeline.run(registry, 0.016);
    const std::vector<std::string> want{"keyboard",   "physics", "animation",
                                        "transforms", "gi",      "draw"};
    EXPECT_EQ(calls, want);
    const std::vector<std::string> described{"input/keyboard",       "simulation/physics",
                                             "simulation/animation", "transforms/transforms",
                                             "lighting/gi",          "render/draw"};
    EXPECT_EQ(pipeline.describe(), described);
    EXPECT_EQ(pipeline.frames_run(), 1u);
}

TEST(Pipeline, PassesRegistryAndTimeStepAndAcceptsRegistryOnlySystems) {
    Pipeline pipeline;
    double seen_dt = 0.0;
    Registry* seen_registry = nullptr;
    int registry_only_calls = 0;
    pipeline.add(Phase::Simulation, "timed", [&](Registry& registry, double dt) {
        seen_dt = dt;
        seen_registry = &registry;
    });
    pipeline.add(Phase::Render, "untimed", [&](Registry&) { ++registry_only_calls; });
    Registry registry;
    pipeline.run(registry, 0.25);
    EXPECT_EQ(seen_dt, 0.25);
    EXPECT_EQ(seen_registry, &registry);
    EXPECT_EQ(registry_only_calls, 1);
}

TEST(Pipeline, RemoveDisableAndNameChecks) {
    Pipeline pipeline;
    int a_calls = 0;
    int b_calls = 0;
    pipeline.add(Phase::Simulation, "a", [&](Registry&) { ++a_calls; });
    pipeline.add(Phase::Simulation, "b", [&](Registry&) { ++b_calls; });
    EXPECT_THROW(pipeline.add(Phase::Render, "a", [](Registry&) {}), EcsError);
    EXPECT_THROW(pipeline.add(Phase::Render, "", [](Registry&) {}), EcsError);
    EXPECT_THROW(pipeline.set_enabled("missing", false), EcsError);

    Registry registry;
    pipeline.set_enabled("a", false);
    pipeline.run(registry, 0.0);
    EXPECT_EQ(a_calls, 0);
    EXPECT_EQ(b_calls, 1);
    EXPECT_EQ(pipeline.describe().front(), "simulation/a (disabled)");
    pipeline.set_enabled("a", true);
    EXPECT_TRUE(pipeline.remove("b"));
    EXPECT_FALSE(pipeline.remove("b"));
    EXPECT_FALSE(pipeline.contains("b"));
    pipeline.run(registry, 0.0);
    EXPECT_EQ(a_calls, 1);
    EXPECT_EQ(b_calls, 1);
}

TEST(Pipeline, CannotBeChangedWhileRunningAndRecoversFromAThrowingSystem) {
    Pipeline pipeline;
    bool refused = false;
    pipeline.add(Phase::Input, "editor", [&](Registry&) {
        try {
            pipeline.add(Phase::Render, "late", [](Registry&) {});
        } catch (const EcsError&) {
            refused = true;
        }
    });
    pipeline.add(Phase::Simulation, "faulty", [](Registry&) { throw std::runtime_error("boom"); });
    Registry registry;
    EXPECT_THROW(pipeline.run(registry, 0.0), std::runtime_error);
    EXPECT_TRUE(refused);
    EXPECT_EQ(pipeline.frames_run(), 0u);
    EXPECT_TRUE(pipeline.remove("faulty")) << "usable again after the exception";
    pipeline.run(registry, 0.0);
    EXPECT_EQ(pipeline.frames_run(), 1u);
}

TEST(Pipeline, OnePipelineDrivesSeveralIndependentRegistries) {
    Pipeline pipeline;
    pipeline.add(Phase::Simulation, "spawn",
                 [](Registry& registry) { registry.emplace<test::Position>(registry.create()); });
    Registry first;
    Registry second;
    pipeline.run(first, 0.0);
    pipeline.run(first, 0.0);
    pipeline.run(second, 0.0);
    EXPECT_EQ(first.size<test::Position>(), 2u);
    EXPECT_EQ(second.size<test::Position>(), 1u);
}

TEST(Pipeline, PhaseNames) {
    EXPECT_EQ(to_string(Phase::Input), "input");
    EXPECT_EQ(to_string(Phase::Simulation), "simulation");
    EXPECT_EQ(to_string(Phase::Transforms), "transforms");
    EXPECT_EQ(to_string(Phase::Lighting), "lighting");
    EXPECT_EQ(to_string(Phase::Render), "render");
}

TEST(Pipeline, AFrameFromSimulationThroughTransformsToLighting) {
    // The shape of a luxel frame: simulation moves a parent, the transform phase propagates it,
    // and the lighting phase learns exactly which world transforms changed.
    Registry registry;
    const Entity lamp_post = registry.create();
    registry.emplace<Transform>(lamp_post);
    const Entity lamp = registry.create();
    registry.emplace<Transform>(lamp, glm::vec3(0, 3, 0));
    set_parent(registry, lamp, lamp_post);
    const Entity statue = registry.create();
    registry.emplace<Transform>(statue, glm::vec3(10, 0, 0));

    TransformSystem transforms(registry);
    Observer<WorldTransform> moved = registry.observe<WorldTransform>();
    std::vector<Entity> lighting_saw;
    Pipeline pipeline;
    pipeline.add(Phase::Simulation, "push", [lamp_post](Registry& r, double dt) {
        r.patch<Transform>(lamp_post,
                           [dt](Transform& t) { t.translation.x += static_cast<float>(dt); });
    });
    pipeline.add(Phase::Transforms, "transforms",
                 [&transforms](Registry& r, double) { transforms.update(r); });
    pipeline.add(Phase::Lighting, "gi", [&](Registry&) {
        lighting_saw.clear();
        moved.consume([&](Entity e, ChangeKind kind) {
            if (kind != ChangeKind::Destroyed) {
                lighting_saw.push_back(e);
            }
        });
    });

    pipeline.run(registry, 1.0);  // first frame: everything appears
    EXPECT_EQ(test::sorted(lighting_saw), test::sorted({lamp_post, lamp, statue}));
    pipeline.run(registry, 1.0);
    EXPECT_EQ(test::sorted(lighting_saw), test::sorted({lamp_post, lamp})) << "the statue is still";
    EXPECT_EQ(registry.get<WorldTransform>(lamp).position(), glm::vec3(2, 3, 0));
}

}  // namespace
}  // namespace luxel::ecs
