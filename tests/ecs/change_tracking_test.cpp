// Observers ("what changed since I last looked") and the construct/update/destroy signals.

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "luxel/ecs/registry.hpp"
#include "test_components.hpp"

namespace luxel::ecs {
namespace {

using test::Position;
using test::sorted;
using test::Velocity;

std::vector<Entity> list(std::span<const Entity> entities) {
    return std::vector<Entity>(entities.begin(), entities.end());
}

/// One "frame" as an observer sees it: the three lists, then marked seen.
struct Look {
    std::vector<Entity> constructed;
    std::vector<Entity> updated;
    std::vector<Entity> destroyed;
};
template <class T>
Look look(Observer<T>& observer) {
    Look result{sorted(list(observer.constructed())), sorted(list(observer.updated())),
                sorted(list(observer.destroyed()))};
    observer.clear();
    return result;
}

TEST(Observer, ReportsEachKindOfChange) {
    Registry registry;
    Observer<Position> observer = registry.observe<Position>();
    const Entity a = registry.create();
    const Entity b = registry.create();
    const Entity c = registry.create();
    registry.emplace<Position>(a);
    registry.emplace<Position>(b);
    registry.emplace<Position>(c);
    Look first = look(observer);
    EXPECT_EQ(first.constructed, (std::vector<Entity>{a, b, c}));
    EXPECT_TRUE(first.updated.empty());
    EXPECT_TRUE(first.destroyed.empty());
    EXPECT_TRUE(observer.empty());

    registry.patch<Position>(a, [](Position& p) { p.x = 1; });
    registry.replace<Position>(b, 2.0f);
    registry.get<Position>(c).x = 3;  // untracked until marked
    Look second = look(observer);
    EXPECT_EQ(second.updated, (std::vector<Entity>{a, b}));
    registry.mark_updated<Position>(c);
    registry.emplace_or_replace<Position>(a, 4.0f);
    EXPECT_EQ(look(observer).updated, (std::vector<Entity>{a, c}));

    registry.remove<Position>(a);
    registry.destroy(b);
    Look fourth = look(observer);
    EXPECT_EQ(fourth.destroyed, (std::vector<Entity>{a, b}));
    EXPECT_TRUE(fourth.constructed.empty());
    EXPECT_TRUE(fourth.updated.empty());
}

TEST(Observer, ConstructedUpdatedDestroyedInOneFrameIsNoChange) {
    Registry registry;
    Observer<Position> observer = registry.observe<Position>();
    const Entity entity = registry.create();
    registry.emplace<Position>(entity);
    registry.patch<Position>(entity, [](Position& p) { p.y = 5; });
    registry.destroy(entity);
    EXPECT_TRUE(observer.empty()) << "never seen, so nothing to report";
}

TEST(Observer, ConstructedUpdatedDestroyedAcrossFrames) {
    Registry registry;
    Observer<Position> observer = registry.observe<Position>();
    const Entity entity = registry.create();

    registry.emplace<Position>(entity);  // frame 1
    Look frame1 = look(observer);
    EXPECT_EQ(frame1.constructed, std::vector<Entity>{entity});
    EXPECT_TRUE(frame1.updated.empty());

    registry.patch<Position>(entity, [](Position& p) { p.y = 5; });  // frame 2
    Look frame2 = look(observer);
    EXPECT_TRUE(frame2.constructed.empty());
    EXPECT_EQ(frame2.updated, std::vector<Entity>{entity});

    Look frame3 = look(observer);  // nothing happened
    EXPECT_TRUE(frame3.constructed.empty() && frame3.updated.empty() && frame3.destroyed.empty());

    registry.destroy(entity);  // frame 4
    Look frame4 = look(observer);
    EXPECT_EQ(frame4.destroyed, std::vector<Entity>{entity});
    EXPECT_TRUE(frame4.updated.empty());
}

TEST(Observer, FoldsChangesWithinAFrame) {
    Registry registry;
    const Entity existing = registry.create();
    registry.emplace<Position>(existing);
    Observer<Position> observer = registry.observe<Position>();

    // Constructed then updated: Constructed only.
    const Entity fresh = registry.create();
    registry.emplace<Position>(fresh);
    registry.patch<Position>(fresh, [](Position&) {});
    // Updated many times: once.
    for (int i = 0; i < 10; ++i) {
        registry.patch<Position>(existing, [](Position& p) { p.x += 1; });
    }
    Look frame = look(observer);
    EXPECT_EQ(frame.constructed, std::vector<Entity>{fresh});
    EXPECT_EQ(frame.updated, std::vector<Entity>{existing});

    // Updated then destroyed: Destroyed only.
    registry.patch<Position>(existing, [](Position&) {});
    registry.remove<Position>(existing);
    frame = look(observer);
    EXPECT_TRUE(frame.updated.empty());
    EXPECT_EQ(frame.destroyed, std::vector<Entity>{existing});
}

TEST(Observer, RemovedAndReaddedIsDestroyedPlusConstructed) {
    Registry registry;
    const Entity entity = registry.create();
    registry.emplace<Position>(entity, 1.0f);
    Observer<Position> observer = registry.observe<Position>();
    registry.remove<Position>(entity);
    registry.emplace<Position>(entity, 2.0f);
    Look frame = look(observer);
    EXPECT_EQ(frame.destroyed, std::vector<Entity>{entity});
    EXPECT_EQ(frame.constructed, std::vector<Entity>{entity});
}

TEST(Observer, RecycledSlotReportsOldHandleDestroyedAndNewConstructed) {
    Registry registry;
    const Entity old_entity = registry.create();
    registry.emplace<Position>(old_entity);
    Observer<Position> observer = registry.observe<Position>();
    registry.destroy(old_entity);
    const Entity new_entity = registry.create();
    ASSERT_EQ(new_entity.index(), old_entity.index());
    registry.emplace<Position>(new_entity);
    Look frame = look(observer);
    EXPECT_EQ(frame.destroyed, std::vector<Entity>{old_entity});
    EXPECT_EQ(frame.constructed, std::vector<Entity>{new_entity});
}

TEST(Observer, IndependentObserversEachSeeSinceTheirOwnLastLook) {
    Registry registry;
    Observer<Position> every_frame = registry.observe<Position>();
    Observer<Position> every_other_frame = registry.observe<Position>();
    const Entity a = registry.create();
    const Entity b = registry.create();

    registry.emplace<Position>(a);  // frame 1
    EXPECT_EQ(look(every_frame).constructed, std::vector<Entity>{a});

    registry.patch<Position>(a, [](Position&) {});  // frame 2
    registry.emplace<Position>(b);
    Look fast = look(every_frame);
    EXPECT_EQ(fast.updated, std::vector<Entity>{a});
    EXPECT_EQ(fast.constructed, std::vector<Entity>{b});
    Look slow = look(every_other_frame);
    EXPECT_EQ(slow.constructed, (std::vector<Entity>{a, b})) << "a's update folds into it";
    EXPECT_TRUE(slow.updated.empty());

    registry.patch<Position>(b, [](Position&) {});  // frame 3
    EXPECT_EQ(look(every_frame).updated, std::vector<Entity>{b});

    registry.destroy(a);  // frame 4
    EXPECT_EQ(look(every_frame).destroyed, std::vector<Entity>{a});
    Look slow2 = look(every_other_frame);
    EXPECT_EQ(slow2.updated, std::vector<Entity>{b});
    EXPECT_EQ(slow2.destroyed, std::vector<Entity>{a});
}

TEST(Observer, WithExistingStartsWithThePoolAsConstructed) {
    Registry registry;
    std::vector<Entity> entities;
    for (int i = 0; i < 5; ++i) {
        entities.push_back(registry.create());
        registry.emplace<Position>(entities.back());
    }
    Observer<Position> empty_start = registry.observe<Position>();
    Observer<Position> full_start = registry.observe<Position>(ObserverStart::WithExisting);
    EXPECT_TRUE(empty_start.empty());
    EXPECT_EQ(sorted(list(full_start.constructed())), entities);
}

TEST(Observer, ConsumeOrdersKindsAndKeepsChangesMadeMeanwhileForNextTime) {
    Registry registry;
    const Entity old_one = registry.create();
    const Entity updated = registry.create();
    registry.emplace<Position>(old_one);
    registry.emplace<Position>(updated);
    Observer<Position> observer = registry.observe<Position>();
    registry.destroy(old_one);
    registry.patch<Position>(updated, [](Position&) {});
    const Entity fresh = registry.create();
    registry.emplace<Position>(fresh);

    std::vector<std::pair<Entity, ChangeKind>> seen;
    observer.consume([&](Entity entity, ChangeKind kind) {
        seen.emplace_back(entity, kind);
        if (kind != ChangeKind::Destroyed) {
            registry.patch<Position>(entity, [](Position& p) { p.z = 1; });  // a change of T
        }
    });
    const std::vector<std::pair<Entity, ChangeKind>> want{{old_one, ChangeKind::Destroyed},
                                                          {fresh, ChangeKind::Constructed},
                                                          {updated, ChangeKind::Updated}};
    EXPECT_EQ(seen, want);
    EXPECT_EQ(sorted(list(observer.updated())), sorted({updated, fresh}))
        << "changes made while consuming wait for the next look";
    EXPECT_THROW(observer.consume([&](Entity, ChangeKind) { observer.consume([](auto...) {}); }),
                 EcsError);
}

TEST(Observer, WorkIsProportionalToChangesAndMemoryToThePool) {
    Registry registry;
    std::vector<Entity> entities;
    for (int i = 0; i < 10000; ++i) {
        entities.push_back(registry.create());
        registry.emplace<Position>(entities.back());
    }
    Observer<Position> reader = registry.observe<Position>();
    Observer<Position> forgotten = registry.observe<Position>();  // never looks
    for (int frame = 0; frame < 100; ++frame) {
        for (int i = 0; i < 10; ++i) {
            registry.patch<Position>(entities[static_cast<std::size_t>(frame * 10 + i)],
                                     [](Position& p) { p.x += 1; });
        }
        // The same entity every frame: the forgotten observer does not grow for repeats.
        registry.patch<Position>(entities[0], [](Position&) {});
        EXPECT_EQ(reader.size(), frame == 0 ? 10u : 11u)
            << "a look sees exactly the changes, not the pool";
        reader.clear();
    }
    EXPECT_EQ(forgotten.size(), 1000u) << "at most one entry per changed entity";
    EXPECT_LE(forgotten.size(), registry.size<Position>());
}

TEST(Observer, DetachesOnDestructionAndMayOutliveItsRegistry) {
    Observer<Position> survivor;
    {
        Registry registry;
        {
            Observer<Position> scoped = registry.observe<Position>();
            EXPECT_EQ(registry.storage<Position>().observer_count(), 1u);
        }
        EXPECT_EQ(registry.storage<Position>().observer_count(), 0u);
        survivor = registry.observe<Position>();
        Observer<Position> moved = std::move(survivor);
        survivor = std::move(moved);
        EXPECT_EQ(registry.storage<Position>().observer_count(), 1u);
        registry.emplace<Position>(registry.create());
        EXPECT_TRUE(survivor.attached());
    }
    EXPECT_FALSE(survivor.attached());
    EXPECT_EQ(survivor.constructed().size(), 1u) << "what it had is still readable";
    survivor.clear();
    EXPECT_TRUE(survivor.empty());
}

TEST(Observer, TracksOnlyItsOwnComponentType) {
    Registry registry;
    Observer<Position> positions = registry.observe<Position>();
    const Entity entity = registry.create();
    registry.emplace<Velocity>(entity);
    registry.patch<Velocity>(entity, [](Velocity&) {});
    EXPECT_TRUE(positions.empty());
}

// ---- Signals ------------------------------------------------------------------------------

TEST(Signals, FireOnConstructUpdateAndDestroyWithTheComponentReadable) {
    Registry registry;
    std::vector<std::string> events;
    Connection construct = registry.on_construct<Position>().connect([&](Registry& r, Entity e) {
        events.push_back("construct " + std::to_string(r.get<Position>(e).x));
    });
    Connection update = registry.on_update<Position>().connect([&](Registry& r, Entity e) {
        events.push_back("update " + std::to_string(r.get<Position>(e).x));
    });
    Connection destroy = registry.on_destroy<Position>().connect([&](Registry& r, Entity e) {
        events.push_back("destroy " + std::to_string(r.get<Position>(e).x));
    });
    const Entity entity = registry.create();
    registry.emplace<Position>(entity, 1.0f);
    registry.patch<Position>(entity, [](Position& p) { p.x = 2.0f; });
    registry.replace<Position>(entity, 3.0f);
    registry.mark_updated<Position>(entity);
    registry.destroy(entity);
    const std::vector<std::string> want{"construct 1.000000", "update 2.000000", "update 3.000000",
                                        "update 3.000000", "destroy 3.000000"};
    EXPECT_EQ(events, want);
    EXPECT_TRUE(construct.connected());
}

TEST(Signals, ConnectionsDisconnectOnDestructionOrRequest) {
    Registry registry;
    int calls = 0;
    const Entity entity = registry.create();
    {
        Connection scoped =
            registry.on_construct<Position>().connect([&](Registry&, Entity) { ++calls; });
        EXPECT_EQ(registry.on_construct<Position>().size(), 1u);
    }
    registry.emplace<Position>(entity);
    EXPECT_EQ(calls, 0);
    EXPECT_TRUE(registry.on_construct<Position>().empty());

    Connection explicit_one =
        registry.on_update<Position>().connect([&](Registry&, Entity) { ++calls; });
    registry.mark_updated<Position>(entity);
    explicit_one.disconnect();
    EXPECT_FALSE(explicit_one.connected());
    registry.mark_updated<Position>(entity);
    EXPECT_EQ(calls, 1);

    {
        Connection released =
            registry.on_update<Position>().connect([&](Registry&, Entity) { ++calls; });
        released.release();
    }
    registry.mark_updated<Position>(entity);
    EXPECT_EQ(calls, 2) << "a released connection stays connected";
}

TEST(Signals, ConnectionOutlivingTheRegistryIsHarmless) {
    Connection connection;
    {
        Registry registry;
        connection = registry.on_construct<Position>().connect([](Registry&, Entity) {});
        EXPECT_TRUE(connection.connected());
    }
    EXPECT_FALSE(connection.connected());
    connection.disconnect();
}

TEST(Signals, ConnectAndDisconnectDuringEmission) {
    Signal<int> signal;
    std::vector<std::string> calls;
    Connection late;
    Connection second;
    Connection first = signal.connect([&](int value) {
        calls.push_back("first " + std::to_string(value));
        if (value == 1) {
            late = signal.connect([&](int v) { calls.push_back("late " + std::to_string(v)); });
            second.disconnect();
        }
    });
    second = signal.connect([&](int value) { calls.push_back("second " + std::to_string(value)); });
    signal.emit(1);
    signal.emit(2);
    const std::vector<std::string> want{"first 1", "first 2", "late 2"};
    EXPECT_EQ(calls, want);
    EXPECT_EQ(signal.size(), 2u);
}

TEST(Signals, HandlerMayChangeOtherComponentsAndEntities) {
    Registry registry;
    Connection spawn_velocity = registry.on_construct<Position>().connect(
        [](Registry& r, Entity e) { r.emplace<Velocity>(e, 1.0f); });
    Connection cascade = registry.on_destroy<Velocity>().connect([](Registry& r, Entity) {
        const Entity debris = r.create();
        r.emplace<Velocity>(debris, -1.0f);
    });
    const Entity entity = registry.create();
    Position& position = registry.emplace<Position>(entity, 5.0f);
    EXPECT_EQ(position.x, 5.0f) << "the returned reference is valid after the hooks ran";
    EXPECT_EQ(registry.get<Velocity>(entity).x, 1.0f);
    registry.destroy(entity);
    EXPECT_EQ(registry.size<Velocity>(), 1u);
    EXPECT_EQ(registry.alive(), 1u);
}

}  // namespace
}  // namespace luxel::ecs
