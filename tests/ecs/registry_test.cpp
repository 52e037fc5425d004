// Entities, handles and the component API of the Registry.

#include <gtest/gtest.h>

#include <string>
#include <unordered_set>
#include <vector>

#include "luxel/ecs/registry.hpp"
#include "test_components.hpp"

namespace luxel::ecs {
namespace {

using test::A;
using test::B;
using test::Frozen;
using test::Mesh;
using test::Name;
using test::Position;
using test::Velocity;

bool message_contains(const std::exception& error, const std::string& text) {
    return std::string(error.what()).find(text) != std::string::npos;
}

TEST(EntityHandle, PacksIndexAndGenerationIntoThirtyTwoBits) {
    const Entity entity(12345, 678);
    EXPECT_EQ(entity.index(), 12345u);
    EXPECT_EQ(entity.generation(), 678u);
    EXPECT_EQ(Entity::from_bits(entity.bits()), entity);
    EXPECT_NE(Entity(12345, 679), entity);
    EXPECT_EQ(to_string(entity), "12345v678");
    EXPECT_EQ(std::hash<Entity>{}(entity), std::hash<std::uint32_t>{}(entity.bits()));
}

TEST(EntityHandle, DefaultIsNull) {
    const Entity entity;
    EXPECT_TRUE(entity.is_null());
    EXPECT_EQ(entity, null_entity);
    EXPECT_EQ(to_string(entity), "null");
    EXPECT_FALSE(Entity(Entity::max_index, 0).is_null());
}

TEST(Registry, CreateHandsOutDistinctLiveEntities) {
    Registry registry;
    std::unordered_set<Entity> seen;
    for (int i = 0; i < 1000; ++i) {
        const Entity entity = registry.create();
        EXPECT_TRUE(registry.valid(entity));
        EXPECT_TRUE(seen.insert(entity).second);
    }
    EXPECT_EQ(registry.alive(), 1000u);
}

TEST(Registry, NullEntityIsNeverValid) {
    Registry registry;
    (void)registry.create();
    EXPECT_FALSE(registry.valid(null_entity));
    EXPECT_THROW((void)registry.get<Position>(null_entity), StaleEntityError);
    EXPECT_THROW(registry.destroy(null_entity), StaleEntityError);
}

TEST(Registry, EveryCallRejectsAStaleHandle) {
    Registry registry;
    const Entity entity = registry.create();
    registry.emplace<Position>(entity, 1.0f, 2.0f, 3.0f);
    registry.destroy(entity);

    EXPECT_FALSE(registry.valid(entity));
    EXPECT_THROW((void)registry.get<Position>(entity), StaleEntityError);
    EXPECT_THROW((void)registry.try_get<Position>(entity), StaleEntityError);
    EXPECT_THROW((void)registry.has<Position>(entity), StaleEntityError);
    EXPECT_THROW((void)registry.has_any<Position>(entity), StaleEntityError);
    EXPECT_THROW(registry.emplace<Velocity>(entity), StaleEntityError);
    EXPECT_THROW(registry.emplace_or_replace<Position>(entity), StaleEntityError);
    EXPECT_THROW(registry.get_or_emplace<Position>(entity), StaleEntityError);
    EXPECT_THROW(registry.remove<Position>(entity), StaleEntityError);
    EXPECT_THROW(registry.patch<Position>(entity, [](Position&) {}), StaleEntityError);
    EXPECT_THROW(registry.replace<Position>(entity), StaleEntityError);
    EXPECT_THROW(registry.mark_updated<Position>(entity), StaleEntityError);
    EXPECT_THROW(registry.destroy(entity), StaleEntityError);
    const Registry& constant = registry;
    EXPECT_THROW((void)constant.get<Position>(entity), StaleEntityError);
    EXPECT_THROW((void)constant.try_get<Position>(entity), StaleEntityError);

    try {
        (void)registry.get<Position>(entity);
        FAIL() << "expected StaleEntityError";
    } catch (const StaleEntityError& error) {
        EXPECT_EQ(error.entity(), entity);
        EXPECT_TRUE(message_contains(error, to_string(entity))) << error.what();
        EXPECT_TRUE(message_contains(error, "stale")) << error.what();
    }
}

TEST(Registry, StaleHandleNeverReachesTheEntityThatReusedItsSlot) {
    Registry registry;
    const Entity old_entity = registry.create();
    registry.emplace<Position>(old_entity, 1.0f, 0.0f, 0.0f);
    registry.destroy(old_entity);

    const Entity new_entity = registry.create();
    ASSERT_EQ(new_entity.index(), old_entity.index()) << "the slot is recycled";
    EXPECT_NE(new_entity.generation(), old_entity.generation());
    registry.emplace<Position>(new_entity, 2.0f, 0.0f, 0.0f);

    EXPECT_TRUE(registry.valid(new_entity));
    EXPECT_FALSE(registry.valid(old_entity));
    EXPECT_THROW((void)registry.get<Position>(old_entity), StaleEntityError);
    EXPECT_THROW(registry.remove<Position>(old_entity), StaleEntityError);
    EXPECT_EQ(registry.get<Position>(new_entity).x, 2.0f);
    EXPECT_FALSE(registry.storage<Position>().contains(old_entity));
    EXPECT_TRUE(registry.storage<Position>().contains(new_entity));
}

TEST(Registry, SlotIsRetiredWhenItsGenerationIsExhausted) {
    Registry registry;
    std::vector<Entity> history;
    Entity entity = registry.create();
    const std::uint32_t first_index = entity.index();
    while (entity.index() == first_index) {
        history.push_back(entity);
        registry.destroy(entity);
        entity = registry.create();
    }
    // Every generation of the slot was used once, then the slot was retired rather than wrapped.
    EXPECT_EQ(history.size(), std::size_t{Entity::max_generation} + 1);
    EXPECT_EQ(history.back().generation(), Entity::max_generation);
    for (const Entity old : history) {
        EXPECT_FALSE(registry.valid(old));
    }
    EXPECT_TRUE(registry.valid(entity));
    EXPECT_EQ(registry.alive(), 1u);
}

TEST(Registry, EmplaceBuildsAggregatesNonAggregatesMoveOnlyAndEmptyTypes) {
    Registry registry;
    const Entity entity = registry.create();
    Position& position = registry.emplace<Position>(entity, 1.0f, 2.0f, 3.0f);
    EXPECT_EQ(position.y, 2.0f);
    EXPECT_EQ(registry.emplace<Name>(entity, "crate").text(), "crate");
    registry.emplace<Mesh>(entity, std::make_unique<std::vector<float>>(9, 0.5f));
    registry.emplace<Frozen>(entity);
    registry.emplace<int>(entity, 42);

    EXPECT_EQ(registry.get<Position>(entity).z, 3.0f);
    EXPECT_EQ(registry.get<Mesh>(entity).vertices->size(), 9u);
    EXPECT_EQ(registry.get<int>(entity), 42);
    EXPECT_TRUE((registry.has<Position, Name, Mesh, Frozen, int>(entity)));
}

TEST(Registry, MissingAndDuplicateComponentsAreCheckedErrors) {
    Registry registry;
    const Entity entity = registry.create();
    try {
        (void)registry.get<Velocity>(entity);
        FAIL() << "expected MissingComponentError";
    } catch (const MissingComponentError& error) {
        EXPECT_TRUE(message_contains(error, "Velocity")) << error.what();
    }
    EXPECT_EQ(registry.try_get<Velocity>(entity), nullptr);
    EXPECT_THROW(registry.patch<Velocity>(entity, [](Velocity&) {}), MissingComponentError);
    EXPECT_THROW(registry.replace<Velocity>(entity), MissingComponentError);
    EXPECT_THROW(registry.mark_updated<Velocity>(entity), MissingComponentError);

    registry.emplace<Velocity>(entity, 1.0f);
    EXPECT_THROW(registry.emplace<Velocity>(entity, 2.0f), DuplicateComponentError);
    EXPECT_EQ(registry.get<Velocity>(entity).x, 1.0f) << "a failed emplace changes nothing";
    EXPECT_EQ(registry.size<Velocity>(), 1u);
}

TEST(Registry, HasRemoveAndSizes) {
    Registry registry;
    const Entity entity = registry.create();
    registry.emplace<A>(entity);
    registry.emplace<B>(entity);
    EXPECT_TRUE((registry.has<A, B>(entity)));
    EXPECT_FALSE((registry.has<A, Position>(entity)));
    EXPECT_TRUE((registry.has_any<Position, B>(entity)));
    EXPECT_FALSE((registry.has_any<Position, Velocity>(entity)));
    EXPECT_TRUE(registry.has<>(entity));

    EXPECT_EQ((registry.remove<A, Position>(entity)), 1u);
    EXPECT_EQ(registry.remove<A>(entity), 0u) << "removing an absent component is a no-op";
    EXPECT_FALSE(registry.has<A>(entity));
    EXPECT_EQ(registry.size<A>(), 0u);
    EXPECT_EQ(registry.size<B>(), 1u);
    EXPECT_EQ(registry.size<Velocity>(), 0u) << "no pool yet";
}

TEST(Registry, PatchReplaceAndEmplaceOrReplaceChangeValues) {
    Registry registry;
    const Entity entity = registry.create();
    registry.emplace<Position>(entity, 1.0f, 1.0f, 1.0f);
    registry.patch<Position>(entity, [](Position& p) { p.x += 10.0f; });
    EXPECT_EQ(registry.get<Position>(entity).x, 11.0f);
    registry.replace<Position>(entity, 5.0f, 6.0f, 7.0f);
    EXPECT_EQ(registry.get<Position>(entity).y, 6.0f);
    registry.emplace_or_replace<Position>(entity, 8.0f);
    EXPECT_EQ(registry.get<Position>(entity).x, 8.0f);
    EXPECT_EQ(registry.get<Position>(entity).y, 0.0f);
    registry.emplace_or_replace<Velocity>(entity, 3.0f);
    EXPECT_EQ(registry.get<Velocity>(entity).x, 3.0f);
    EXPECT_EQ(registry.get_or_emplace<Velocity>(entity, 99.0f).x, 3.0f);
    EXPECT_EQ(registry.get_or_emplace<A>(entity, 7u).value, 7u);
}

TEST(Registry, GetSeveralComponentsAtOnce) {
    Registry registry;
    const Entity entity = registry.create();
    registry.emplace<Position>(entity, 1.0f);
    registry.emplace<Velocity>(entity, 2.0f);
    auto [position, velocity] = registry.get<Position, Velocity>(entity);
    position.x += velocity.x;
    EXPECT_EQ(registry.get<Position>(entity).x, 3.0f);
    const Registry& constant = registry;
    EXPECT_EQ(constant.get<Velocity>(entity).x, 2.0f);
    EXPECT_EQ(constant.try_get<A>(entity), nullptr) << "const access never creates a pool";
}

TEST(Registry, DestroyRemovesEveryComponent) {
    Registry registry;
    const Entity doomed = registry.create();
    const Entity kept = registry.create();
    for (const Entity entity : {doomed, kept}) {
        registry.emplace<Position>(entity);
        registry.emplace<Name>(entity, "x");
        registry.emplace<Mesh>(entity);
    }
    registry.destroy(doomed);
    EXPECT_EQ(registry.size<Position>(), 1u);
    EXPECT_EQ(registry.size<Name>(), 1u);
    EXPECT_EQ(registry.size<Mesh>(), 1u);
    EXPECT_TRUE((registry.has<Position, Name, Mesh>(kept)));
    EXPECT_EQ(registry.alive(), 1u);
}

TEST(Registry, SwapAndPopKeepsEveryOtherEntitysComponent) {
    Registry registry;
    std::vector<Entity> entities;
    for (std::uint32_t i = 0; i < 100; ++i) {
        entities.push_back(registry.create());
        registry.emplace<A>(entities.back(), i);
    }
    for (std::uint32_t i = 0; i < 100; i += 3) {
        registry.remove<A>(entities[i]);
    }
    for (std::uint32_t i = 0; i < 100; ++i) {
        const A* component = registry.try_get<A>(entities[i]);
        if (i % 3 == 0) {
            EXPECT_EQ(component, nullptr);
        } else {
            ASSERT_NE(component, nullptr);
            EXPECT_EQ(component->value, i);
        }
    }
}

TEST(Registry, ClearDestroysEverything) {
    Registry registry;
    std::vector<Entity> entities;
    for (int i = 0; i < 50; ++i) {
        entities.push_back(registry.create());
        registry.emplace<Position>(entities.back());
    }
    registry.clear();
    EXPECT_EQ(registry.alive(), 0u);
    EXPECT_EQ(registry.size<Position>(), 0u);
    for (const Entity entity : entities) {
        EXPECT_FALSE(registry.valid(entity));
    }
}

TEST(Registry, SeveralRegistriesAreIndependent) {
    Registry first;
    Registry second;
    const Entity in_first = first.create();
    const Entity in_second = second.create();
    first.emplace<Position>(in_first, 1.0f);
    EXPECT_EQ(second.size<Position>(), 0u);
    EXPECT_EQ(second.try_get<Position>(in_second), nullptr);
    second.emplace<Position>(in_second, 2.0f);
    EXPECT_EQ(first.get<Position>(in_first).x, 1.0f);
    EXPECT_EQ(second.get<Position>(in_second).x, 2.0f);

    int first_constructs = 0;
    const Connection connection =
        first.on_construct<Velocity>().connect([&](Registry&, Entity) { ++first_constructs; });
    second.emplace<Velocity>(in_second);
    EXPECT_EQ(first_constructs, 0) << "hooks belong to one registry";
    first.emplace<Velocity>(in_first);
    EXPECT_EQ(first_constructs, 1);

    first.ctx().emplace<int>(7);
    EXPECT_FALSE(second.ctx().contains<int>());
}

TEST(Registry, CapacityIsCheckedNotOverflowed) {
    Registry registry;
    for (std::uint32_t i = 0; i <= Entity::max_index; ++i) {
        (void)registry.create();
    }
    EXPECT_EQ(registry.alive(), std::size_t{Entity::max_index} + 1);
    EXPECT_THROW((void)registry.create(), CapacityError);
    registry.destroy(Entity(7, 0));
    EXPECT_EQ(registry.create(), Entity(7, 1)) << "a freed slot is reusable at full capacity";
}

TEST(Registry, HooksMayReadButNotExtendAnEntityBeingDestroyed) {
    Registry registry;
    const Entity entity = registry.create();
    registry.emplace<Position>(entity, 4.0f);
    float seen = 0.0f;
    bool emplace_refused = false;
    const Connection on_entity = registry.on_destroy_entity().connect([&](Registry& r, Entity e) {
        seen = r.get<Position>(e).x;
        try {
            r.emplace<Velocity>(e);
        } catch (const EcsError&) {
            emplace_refused = true;
        }
        r.destroy(e);  // a nested destroy of the same entity is a no-op
    });
    registry.destroy(entity);
    EXPECT_EQ(seen, 4.0f);
    EXPECT_TRUE(emplace_refused);
    EXPECT_FALSE(registry.valid(entity));
    EXPECT_EQ(registry.size<Velocity>(), 0u);
    EXPECT_EQ(registry.alive(), 0u);
    EXPECT_EQ(registry.create().index(), entity.index()) << "freed exactly once";
    EXPECT_EQ(registry.create().index(), entity.index() + 1);
}

TEST(Context, HoldsOnePerTypeSingletons) {
    Registry registry;
    Context& context = registry.ctx();
    EXPECT_EQ(context.find<std::string>(), nullptr);
    context.emplace<std::string>("sun");
    EXPECT_EQ(context.get<std::string>(), "sun");
    EXPECT_THROW(context.emplace<std::string>("moon"), EcsError);
    EXPECT_EQ(context.get_or_emplace<std::string>("moon"), "sun");
    EXPECT_THROW((void)context.get<int>(), EcsError);
    EXPECT_TRUE(context.erase<std::string>());
    EXPECT_FALSE(context.contains<std::string>());
    EXPECT_FALSE(context.erase<std::string>());
}

TEST(TypeName, NamesComponentsReadably) {
    // The compiler decides how much of the namespace to spell; the type itself is always there.
    EXPECT_TRUE(type_name<Position>().ends_with("test::Position")) << type_name<Position>();
    EXPECT_EQ(type_name<int>(), "int");
    EXPECT_NE(type_index<Position>(), type_index<Velocity>());
    EXPECT_EQ(type_index<Position>(), type_index<Position>());
}

}  // namespace
}  // namespace luxel::ecs
