// One million entities: pools, views, change tracking and handles at the scale of a big level.
// Asserts results only, never speed (speed lives in tests/bench/ecs_bench.cpp).

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "luxel/ecs/registry.hpp"
#include "luxel/ecs/transform_system.hpp"
#include "test_components.hpp"

namespace luxel::ecs {
namespace {

using test::Position;
using test::Velocity;

constexpr std::uint32_t million = 1000000;

TEST(Scale, OneMillionEntities) {
    Registry registry;
    std::vector<Entity> entities;
    entities.reserve(million);
    registry.storage<Position>().reserve(million);
    registry.storage<Velocity>().reserve(million);
    for (std::uint32_t i = 0; i < million; ++i) {
        const Entity entity = registry.create();
        registry.emplace<Position>(entity, static_cast<float>(i));
        if (i % 2 == 0) {
            registry.emplace<Velocity>(entity, 1.0f);
        }
        entities.push_back(entity);
    }
    EXPECT_EQ(registry.alive(), million);

    // A two-component view: exactly the half with a Velocity, each component the right one.
    std::uint64_t visited = 0;
    bool values_match = true;
    registry.view<Position, Velocity>().each([&](Entity entity, Position& p, Velocity& v) {
        values_match = values_match && p.x == static_cast<float>(entity.index());
        p.x += v.x;
        ++visited;
    });
    EXPECT_EQ(visited, million / 2);
    EXPECT_TRUE(values_match);
    EXPECT_EQ(registry.get<Position>(entities[10]).x, 11.0f);
    EXPECT_EQ(registry.get<Position>(entities[11]).x, 11.0f);

    // 1% changed: an observer reports exactly those.
    Observer<Position> observer = registry.observe<Position>();
    for (std::uint32_t i = 0; i < million; i += 100) {
        registry.patch<Position>(entities[i], [](Position& p) { p.y = 1.0f; });
    }
    EXPECT_EQ(observer.updated().size(), million / 100);
    std::uint64_t changed = 0;
    observer.consume([&](Entity entity, ChangeKind kind) {
        changed += kind == ChangeKind::Updated && registry.get<Position>(entity).y == 1.0f;
    });
    EXPECT_EQ(changed, million / 100);

    // Destroy every third entity and refill: old handles stay stale, new ones are live.
    for (std::uint32_t i = 0; i < million; i += 3) {
        registry.destroy(entities[i]);
    }
    EXPECT_EQ(observer.destroyed().size(), (million + 2) / 3);
    std::vector<Entity> refilled;
    for (std::uint32_t i = 0; i < million; i += 3) {
        refilled.push_back(registry.create());
    }
    EXPECT_EQ(registry.alive(), million);
    for (std::uint32_t i = 0; i < million; i += 3) {
        ASSERT_FALSE(registry.valid(entities[i]));
    }
    for (const Entity entity : refilled) {
        ASSERT_TRUE(registry.valid(entity));
        ASSERT_FALSE(registry.has<Position>(entity));
    }
    EXPECT_EQ(registry.size<Position>(), million - (million + 2) / 3);
}

TEST(Scale, OneMillionTransformsInAThousandTrees) {
    Registry registry;
    std::vector<Entity> roots;
    for (std::uint32_t tree = 0; tree < 1000; ++tree) {
        const Entity root = registry.create();
        registry.emplace<Transform>(root, glm::vec3(static_cast<float>(tree), 0, 0));
        roots.push_back(root);
        for (std::uint32_t leaf = 1; leaf < 1000; ++leaf) {
            const Entity child = registry.create();
            registry.emplace<Transform>(child, glm::vec3(0, static_cast<float>(leaf), 0));
            set_parent(registry, child, root);
        }
    }
    TransformSystem system(registry);
    system.update();
    EXPECT_EQ(system.last_visit_count(), million);
    EXPECT_EQ(registry.size<WorldTransform>(), million);
    const Entity some_leaf = registry.get<Children>(roots[321]).last();
    EXPECT_EQ(registry.get<WorldTransform>(some_leaf).position(), glm::vec3(321, 999, 0));

    registry.patch<Transform>(roots[5], [](Transform& t) { t.translation.z = 1; });
    system.update();
    EXPECT_EQ(system.last_visit_count(), 1000u) << "one tree of a thousand";
}

}  // namespace
}  // namespace luxel::ecs
