// Views over 1 to 4 components, with and without exclusions, and changes during iteration.

#include <gtest/gtest.h>

#include <map>
#include <tuple>
#include <vector>

#include "luxel/ecs/registry.hpp"
#include "test_components.hpp"

namespace luxel::ecs {
namespace {

using test::A;
using test::B;
using test::C;
using test::D;
using test::E;
using test::Position;
using test::sorted;
using test::Velocity;

/// 2,000 entities; entity i has A if i % 2 == 0, B if i % 3 == 0, C if i % 5 == 0, D if
/// i % 7 == 0, E if i % 11 == 0. Each component's value is i times its tag + 1, so a view that
/// hands out the wrong entity's component is caught. Components are added type by type in
/// shuffled-ish orders so that pools do not line up (the slow path of the view is exercised).
class ViewFixture : public ::testing::Test {
  protected:
    static constexpr std::uint32_t count = 2000;

    void SetUp() override {
        for (std::uint32_t i = 0; i < count; ++i) {
            entities.push_back(registry.create());
        }
        add<A>(2, 1, false);
        add<B>(3, 2, true);
        add<C>(5, 3, false);
        add<D>(7, 4, true);
        add<E>(11, 5, false);
    }

    template <class T>
    void add(std::uint32_t modulus, std::uint32_t tag, bool reverse) {
        for (std::uint32_t n = 0; n < count; ++n) {
            const std::uint32_t i = reverse ? count - 1 - n : n;
            if (i % modulus == 0) {
                registry.emplace<T>(entities[i], i * tag + 1);
            }
        }
    }

    /// The entities with all of `with` and none of `without` (by modulus).
    [[nodiscard]] std::vector<Entity> expected(const std::vector<std::uint32_t>& with,
                                               const std::vector<std::uint32_t>& without) const {
        std::vector<Entity> result;
        for (std::uint32_t i = 0; i < count; ++i) {
            bool in = true;
            for (const std::uint32_t m : with) {
                in = in && i % m == 0;
            }
            for (const std::uint32_t m : without) {
                in = in && i % m != 0;
            }
            if (in) {
                result.push_back(entities[i]);
            }
        }
        return result;
    }

    [[nodiscard]] std::uint32_t index_of(Entity entity) const { return entity.index(); }

    Registry registry;
    std::vector<Entity> entities;
};

TEST_F(ViewFixture, OneComponent) {
    std::vector<Entity> visited;
    registry.view<A>().each([&](Entity entity, A& a) {
        EXPECT_EQ(a.value, index_of(entity) * 1 + 1);
        visited.push_back(entity);
    });
    EXPECT_EQ(sorted(visited), expected({2}, {}));
}

TEST_F(ViewFixture, TwoComponents) {
    std::vector<Entity> visited;
    registry.view<A, B>().each([&](Entity entity, A& a, B& b) {
        EXPECT_EQ(a.value, index_of(entity) * 1 + 1);
        EXPECT_EQ(b.value, index_of(entity) * 2 + 1);
        visited.push_back(entity);
    });
    EXPECT_EQ(sorted(visited), expected({2, 3}, {}));
}

TEST_F(ViewFixture, ThreeComponents) {
    std::vector<Entity> visited;
    registry.view<C, A, B>().each([&](Entity entity, C& c, A& a, B& b) {
        EXPECT_EQ(a.value, index_of(entity) * 1 + 1);
        EXPECT_EQ(b.value, index_of(entity) * 2 + 1);
        EXPECT_EQ(c.value, index_of(entity) * 3 + 1);
        visited.push_back(entity);
    });
    EXPECT_EQ(sorted(visited), expected({2, 3, 5}, {}));
}

TEST_F(ViewFixture, FourComponents) {
    std::vector<Entity> visited;
    registry.view<A, B, C, D>().each([&](Entity entity, A&, B& b, C&, D& d) {
        EXPECT_EQ(b.value, index_of(entity) * 2 + 1);
        EXPECT_EQ(d.value, index_of(entity) * 4 + 1);
        visited.push_back(entity);
    });
    const std::vector<Entity> want = expected({2, 3, 5, 7}, {});
    ASSERT_FALSE(want.empty());
    EXPECT_EQ(sorted(visited), want);
}

TEST_F(ViewFixture, OneComponentExcludingOne) {
    std::vector<Entity> visited;
    registry.view<A>(exclude<B>).each([&](Entity entity, A&) { visited.push_back(entity); });
    EXPECT_EQ(sorted(visited), expected({2}, {3}));
}

TEST_F(ViewFixture, TwoComponentsExcludingTwo) {
    std::vector<Entity> visited;
    registry.view<A, B>(exclude<C, D>).each([&](Entity entity, A&, B&) {
        visited.push_back(entity);
    });
    EXPECT_EQ(sorted(visited), expected({2, 3}, {5, 7}));
}

TEST_F(ViewFixture, ThreeComponentsExcludingOne) {
    std::vector<Entity> visited;
    registry.view<A, B, C>(exclude<E>).each([&](Entity entity, A&, B&, C&) {
        visited.push_back(entity);
    });
    EXPECT_EQ(sorted(visited), expected({2, 3, 5}, {11}));
}

TEST_F(ViewFixture, FourComponentsExcludingOne) {
    std::vector<Entity> visited;
    registry.view<A, B, C, D>(exclude<E>).each([&](Entity entity, A&, B&, C&, D&) {
        visited.push_back(entity);
    });
    EXPECT_EQ(sorted(visited), expected({2, 3, 5, 7}, {11}));
}

TEST_F(ViewFixture, ExcludingAComponentNobodyHasExcludesNothing) {
    std::vector<Entity> visited;
    registry.view<D>(exclude<Position>).each([&](Entity entity, D&) { visited.push_back(entity); });
    EXPECT_EQ(sorted(visited), expected({7}, {}));
}

TEST_F(ViewFixture, ComponentsOnlyCallableAndWritesThrough) {
    registry.view<A, C>().each([](A& a, C& c) { a.value = c.value; });
    for (const Entity entity : expected({2, 5}, {})) {
        EXPECT_EQ(registry.get<A>(entity).value, registry.get<C>(entity).value);
    }
    // Generic lambdas are accepted too.
    int calls = 0;
    registry.view<B, D>().each([&](auto&, auto&) { ++calls; });
    EXPECT_EQ(static_cast<std::size_t>(calls), expected({3, 7}, {}).size());
}

TEST_F(ViewFixture, RangeForMatchesEach) {
    std::vector<Entity> from_each;
    registry.view<A, B>(exclude<C>).each([&](Entity entity, A&, B&) {
        from_each.push_back(entity);
    });
    std::vector<Entity> from_range;
    for (auto [entity, a, b] : registry.view<A, B>(exclude<C>)) {
        EXPECT_EQ(a.value, index_of(entity) + 1);
        b.value = 0;  // references into the pool
        from_range.push_back(entity);
    }
    EXPECT_EQ(from_range, from_each) << "same order, same members";
    for (const Entity entity : from_range) {
        EXPECT_EQ(registry.get<B>(entity).value, 0u);
    }
}

TEST_F(ViewFixture, LeadsWithTheSmallestPool) {
    auto view = registry.view<A, E>();
    EXPECT_EQ(view.size_hint(), registry.size<E>());
    std::size_t visited = 0;
    view.each([&](A&, E&) { ++visited; });
    EXPECT_EQ(visited, expected({2, 11}, {}).size());
}

TEST_F(ViewFixture, ContainsAndGet) {
    auto view = registry.view<A, B>(exclude<C>);
    EXPECT_TRUE(view.contains(entities[6]));
    EXPECT_FALSE(view.contains(entities[30])) << "has C";
    EXPECT_FALSE(view.contains(entities[4])) << "lacks B";
    EXPECT_EQ(view.get<B>(entities[6]).value, 6u * 2 + 1);
}

TEST(View, EmptyPoolsAndAnEmptyRegistryVisitNothing) {
    Registry registry;
    int calls = 0;
    registry.view<A, B>().each([&](A&, B&) { ++calls; });
    for ([[maybe_unused]] auto row : registry.view<A>()) {
        ++calls;
    }
    EXPECT_EQ(calls, 0);
}

TEST(View, AKeptViewStaysCorrectAcrossStructuralChanges) {
    // A view remembers which blocks of its pools line up; every kind of change to a pool must
    // make it look again. Several blocks' worth of entities, changed between passes.
    Registry registry;
    std::vector<Entity> entities;
    for (std::uint32_t i = 0; i < 5000; ++i) {
        entities.push_back(registry.create());
        registry.emplace<A>(entities.back(), i);
        registry.emplace<B>(entities.back(), i);
    }
    auto view = registry.view<A, B>();
    const auto check = [&](const char* step) {
        std::size_t visited = 0;
        bool consistent = true;
        view.each([&](Entity entity, A& a, B& b) {
            consistent = consistent && a.value == entity.index() && b.value == entity.index();
            ++visited;
        });
        std::size_t expected = 0;
        for (const Entity entity : entities) {
            expected += registry.valid(entity) && registry.has<A, B>(entity);
        }
        EXPECT_TRUE(consistent) << step;
        EXPECT_EQ(visited, expected) << step;
    };
    check("lined up");
    check("lined up, remembered");
    registry.remove<B>(entities[10]);  // B's last entity moves to position 10: misaligned there
    check("one removal");
    registry.emplace<B>(entities[10], 10u);
    check("re-added at the end");
    registry.destroy(entities[2500]);
    registry.destroy(entities[4999]);
    check("destroyed");
    const Entity fresh = registry.create();
    registry.emplace<B>(fresh, fresh.index());
    registry.emplace<A>(fresh, fresh.index());
    entities.push_back(fresh);
    check("added in the other order");
    registry.clear();
    check("cleared");
    for (std::uint32_t i = 0; i < 3000; ++i) {
        const Entity entity = registry.create();
        registry.emplace<A>(entity, entity.index());
        registry.emplace<B>(entity, entity.index());
        entities.push_back(entity);
    }
    check("refilled");
}

// ---- Changes during iteration -------------------------------------------------------------

class IterationMutation : public ::testing::Test {
  protected:
    void SetUp() override {
        for (std::uint32_t i = 0; i < 500; ++i) {
            const Entity entity = registry.create();
            registry.emplace<A>(entity, i);
            if (i % 2 == 0) {
                registry.emplace<B>(entity, i);
            }
            all.push_back(entity);
        }
    }
    Registry registry;
    std::vector<Entity> all;
};

TEST_F(IterationMutation, RemovingTheCurrentLeadingComponentVisitsEachOnce) {
    std::map<Entity, int> visits;
    registry.view<A>().each([&](Entity entity, A&) {
        ++visits[entity];
        registry.remove<A>(entity);
    });
    EXPECT_EQ(visits.size(), all.size());
    for (const auto& [entity, count] : visits) {
        EXPECT_EQ(count, 1) << to_string(entity);
    }
    EXPECT_EQ(registry.size<A>(), 0u);
}

TEST_F(IterationMutation, RemovingTheCurrentNonLeadingComponentVisitsEachOnce) {
    std::map<Entity, int> visits;
    // A (500) is larger than B (250), so B leads; removing A is the non-leading case.
    registry.view<A, B>().each([&](Entity entity, A&, B&) {
        ++visits[entity];
        registry.remove<A>(entity);
    });
    EXPECT_EQ(visits.size(), 250u);
    for (const auto& [entity, count] : visits) {
        EXPECT_EQ(count, 1);
    }
    EXPECT_EQ(registry.size<A>(), 250u);
}

TEST_F(IterationMutation, DestroyingTheCurrentEntityVisitsEachOnce) {
    std::map<Entity, int> visits;
    registry.view<A, B>().each([&](Entity entity, A&, B&) {
        ++visits[entity];
        registry.destroy(entity);
    });
    EXPECT_EQ(visits.size(), 250u);
    for (const auto& [entity, count] : visits) {
        EXPECT_EQ(count, 1);
        EXPECT_FALSE(registry.valid(entity));
    }
    EXPECT_EQ(registry.alive(), 250u);
    EXPECT_EQ(registry.size<B>(), 0u);
}

TEST_F(IterationMutation, DestroyingTheCurrentEntityInRangeFor) {
    std::map<Entity, int> visits;
    for (auto [entity, a] : registry.view<A>()) {
        ++visits[entity];
        EXPECT_EQ(a.value, entity.index());
        registry.destroy(entity);
    }
    EXPECT_EQ(visits.size(), all.size());
    EXPECT_EQ(registry.alive(), 0u);
}

TEST_F(IterationMutation, EntitiesThatJoinTheLeadingPoolAreNotVisitedThisPass) {
    std::size_t visited = 0;
    registry.view<A>().each([&](Entity, A&) {
        ++visited;
        const Entity spawned = registry.create();
        registry.emplace<A>(spawned, 9999u);
    });
    EXPECT_EQ(visited, all.size());
    EXPECT_EQ(registry.size<A>(), 2 * all.size());
}

TEST_F(IterationMutation, AddingComponentsToTheCurrentEntityIsSafe) {
    std::size_t visited = 0;
    registry.view<A>(exclude<C>).each([&](Entity entity, A& a) {
        ++visited;
        const std::uint32_t value = a.value;  // read before the pool of C grows
        registry.emplace<C>(entity, value);
    });
    EXPECT_EQ(visited, all.size());
    EXPECT_EQ(registry.size<C>(), all.size());
    std::size_t second_pass = 0;
    registry.view<A>(exclude<C>).each([&](A&) { ++second_pass; });
    EXPECT_EQ(second_pass, 0u);
}

TEST_F(IterationMutation, AnEntityExcludedBeforeItIsReachedIsSkipped) {
    // The walk goes backwards, so the first position of the leading pool is reached last.
    const Entity reached_last = registry.storage<A>().entities().front();
    std::vector<Entity> visited;
    registry.view<A>(exclude<C>).each([&](Entity entity, A&) {
        if (visited.empty()) {
            registry.emplace<C>(reached_last);
        }
        visited.push_back(entity);
    });
    EXPECT_EQ(visited.size(), all.size() - 1);
    EXPECT_EQ(std::count(visited.begin(), visited.end(), reached_last), 0);
}

TEST_F(IterationMutation, RemovingAnotherEntitysComponentNeverSkipsAMember) {
    // Remove A from an entity not reached yet: it is not visited, every remaining member is
    // (possibly twice, as documented), and nothing reads freed memory (ASan checks that).
    const Entity victim = registry.storage<A>().entities().front();
    std::map<Entity, int> visits;
    registry.view<A>().each([&](Entity entity, A& a) {
        EXPECT_EQ(a.value, entity.index());
        if (visits.empty()) {
            registry.remove<A>(victim);
        }
        ++visits[entity];
    });
    EXPECT_EQ(visits.count(victim), 0u);
    for (const Entity entity : all) {
        if (entity != victim) {
            EXPECT_GE(visits[entity], 1) << to_string(entity);
            EXPECT_LE(visits[entity], 2) << to_string(entity);
        }
    }
}

TEST_F(IterationMutation, DestroyingManyEntitiesFromOneCallbackIsSafe) {
    // The callback destroys the current entity and the next nine the walk would reach; the pool
    // shrinks under the walk, which resumes at its end.
    std::map<Entity, int> visits;
    registry.view<A>().each([&](Entity entity, A&) {
        ++visits[entity];
        const auto members = registry.storage<A>().entities();
        std::vector<Entity> doomed(members.begin(),
                                   members.begin() + std::min<std::size_t>(10, members.size()));
        doomed.push_back(entity);
        for (const Entity other : doomed) {
            if (registry.valid(other)) {
                registry.destroy(other);
            }
        }
    });
    EXPECT_EQ(registry.size<A>(), 0u);
    for (const auto& [entity, count] : visits) {
        EXPECT_LE(count, 1) << "destroyed entities are not visited again";
    }
}

}  // namespace
}  // namespace luxel::ecs

namespace luxel::ecs {
namespace {

using test::A;
using test::B;
using test::C;

/// Pools that line up (components added together), several blocks long: each() takes its
/// lookup-free path, which must honour the same rules when the callback changes the pools.
class AlignedIterationMutation : public ::testing::Test {
  protected:
    void SetUp() override {
        for (std::uint32_t i = 0; i < 3000; ++i) {
            const Entity entity = registry.create();
            registry.emplace<A>(entity, entity.index());
            registry.emplace<B>(entity, entity.index());
            all.push_back(entity);
        }
    }
    Registry registry;
    std::vector<Entity> all;
};

TEST_F(AlignedIterationMutation, DestroyingTheCurrentEntityVisitsEachOnce) {
    std::map<Entity, int> visits;
    registry.view<A, B>().each([&](Entity entity, A& a, B& b) {
        EXPECT_EQ(a.value, entity.index());
        EXPECT_EQ(b.value, entity.index());
        ++visits[entity];
        registry.destroy(entity);
    });
    EXPECT_EQ(visits.size(), all.size());
    for (const auto& [entity, count] : visits) {
        EXPECT_EQ(count, 1);
    }
    EXPECT_EQ(registry.alive(), 0u);
}

TEST_F(AlignedIterationMutation, RemovingTheCurrentNonLeadingComponentVisitsEachOnce) {
    std::map<Entity, int> visits;
    registry.view<A, B>().each([&](Entity entity, A&, B&) {
        ++visits[entity];
        registry.remove<B>(entity);
    });
    EXPECT_EQ(visits.size(), all.size());
    for (const auto& [entity, count] : visits) {
        EXPECT_EQ(count, 1);
    }
    EXPECT_EQ(registry.size<B>(), 0u);
    EXPECT_EQ(registry.size<A>(), all.size());
}

TEST_F(AlignedIterationMutation, ChangingOtherEntitiesNeverHandsOutTheWrongComponent) {
    // Removing B from entities not reached yet breaks the line-up in the middle of a block; the
    // walk must notice and never pair one entity's A with another's B.
    std::map<Entity, int> visits;
    std::size_t step = 0;
    registry.view<A, B>().each([&](Entity entity, A& a, B& b) {
        EXPECT_EQ(a.value, entity.index());
        EXPECT_EQ(b.value, entity.index()) << "components of two different entities";
        ++visits[entity];
        if (++step % 5 == 0) {
            const Entity victim = registry.storage<B>().entities().front();
            if (victim != entity) {
                registry.remove<B>(victim);
            }
        }
        if (step % 7 == 0) {
            const Entity spawned = registry.create();  // joins behind the walk
            registry.emplace<A>(spawned, spawned.index());
            registry.emplace<B>(spawned, spawned.index());
        }
    });
    for (const Entity entity : all) {
        if (registry.has<B>(entity)) {
            EXPECT_GE(visits[entity], 1) << to_string(entity);
            EXPECT_LE(visits[entity], 2) << to_string(entity);
        }
    }
    for (const auto& [entity, count] : visits) {
        EXPECT_LT(entity.index(), all.size()) << "spawned entities are not visited this pass";
    }
}

TEST_F(AlignedIterationMutation, AddingComponentsToTheCurrentEntityIsSafe) {
    std::size_t visited = 0;
    registry.view<A, B>(exclude<C>).each([&](Entity entity, A&, B& b) {
        const std::uint32_t value = b.value;
        registry.emplace<C>(entity, value);
        ++visited;
    });
    EXPECT_EQ(visited, all.size());
    EXPECT_EQ(registry.size<C>(), all.size());
}

}  // namespace
}  // namespace luxel::ecs
