// ECS micro-benchmarks, each next to a plain std::vector<struct> loop doing the same work in the
// same run, so docs/PERFORMANCE.md can report ratios rather than machine-dependent times:
//   Create     1,000,000 entities with Position and Velocity     vs push_back of 1,000,000 structs
//   Iterate    p += v * dt over a two-component view              vs the same over the vector
//              (a view kept across passes, one made afresh each pass, and range-for)
//   Changes    patch k entities, then read what changed (k = 0.1%, 1%, 10% of 1,000,000)
//                                                                 vs dirty flags + a dirty list
//   ChangesRead  only the reading half of Changes (timed by hand around the read)
//   ChangesScan  the naive alternative: scan all 1,000,000 dirty flags (flat in k)
// Run: build/bin/luxel_ecs_bench (see docs/PERFORMANCE.md for the exact flags).

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <memory>
#include <numeric>
#include <random>
#include <vector>

#include "luxel/ecs/registry.hpp"

namespace {

using luxel::ecs::ChangeKind;
using luxel::ecs::Entity;
using luxel::ecs::Observer;
using luxel::ecs::Registry;

constexpr std::size_t entity_count = 1000000;
constexpr float dt = 1.0f / 60.0f;

struct Position {
    float x = 0.0f;
    float y = 0.0f;
    float z = 0.0f;
};
struct Velocity {
    float x = 0.0f;
    float y = 0.0f;
    float z = 0.0f;
};

/// The plain-loop baseline's element: what one entity holds, side by side.
struct Body {
    Position position;
    Velocity velocity;
};

Position initial_position(std::size_t i) {
    return Position{static_cast<float>(i), 0.0f, 1.0f};
}
Velocity initial_velocity(std::size_t i) {
    return Velocity{1.0f, static_cast<float>(i % 7), -1.0f};
}

void fill(Registry& registry, std::vector<Entity>* entities = nullptr) {
    for (std::size_t i = 0; i < entity_count; ++i) {
        const Entity entity = registry.create();
        registry.emplace<Position>(entity, initial_position(i));
        registry.emplace<Velocity>(entity, initial_velocity(i));
        if (entities != nullptr) {
            entities->push_back(entity);
        }
    }
}

std::vector<Body> make_bodies() {
    std::vector<Body> bodies;
    for (std::size_t i = 0; i < entity_count; ++i) {
        bodies.push_back(Body{initial_position(i), initial_velocity(i)});
    }
    return bodies;
}

/// k distinct indices in [0, entity_count), in random order (fixed seed: both sides of a pair
/// touch the same entities in the same order).
std::vector<std::uint32_t> random_subset(std::size_t k) {
    std::vector<std::uint32_t> all(entity_count);
    std::iota(all.begin(), all.end(), 0u);
    std::mt19937 generator(12345);
    std::shuffle(all.begin(), all.end(), generator);
    all.resize(k);
    return all;
}

void set_items(benchmark::State& state, std::size_t items_per_iteration) {
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                            static_cast<std::int64_t>(items_per_iteration));
}

// ---- Create -------------------------------------------------------------------------------

void BM_Create_Ecs(benchmark::State& state) {
    for (auto _ : state) {
        auto registry = std::make_unique<Registry>();
        fill(*registry);
        benchmark::DoNotOptimize(registry->size<Velocity>());
        state.PauseTiming();
        registry.reset();
        state.ResumeTiming();
    }
    set_items(state, entity_count);
}

void BM_Create_Vector(benchmark::State& state) {
    for (auto _ : state) {
        auto bodies = std::make_unique<std::vector<Body>>(make_bodies());
        benchmark::DoNotOptimize(bodies->data());
        state.PauseTiming();
        bodies.reset();
        state.ResumeTiming();
    }
    set_items(state, entity_count);
}

// ---- Iterate ------------------------------------------------------------------------------

void BM_Iterate_Ecs(benchmark::State& state) {
    Registry registry;
    fill(registry);
    auto view = registry.view<Position, Velocity>();
    for (auto _ : state) {
        view.each([](Position& p, const Velocity& v) {
            p.x += v.x * dt;
            p.y += v.y * dt;
            p.z += v.z * dt;
        });
        benchmark::ClobberMemory();
    }
    set_items(state, entity_count);
}

// The same with a view made afresh every pass (registry.view<...>().each(...) in a system): each
// pass re-checks that the pools line up, reading both entity arrays once.
void BM_Iterate_EcsFreshView(benchmark::State& state) {
    Registry registry;
    fill(registry);
    for (auto _ : state) {
        registry.view<Position, Velocity>().each([](Position& p, const Velocity& v) {
            p.x += v.x * dt;
            p.y += v.y * dt;
            p.z += v.z * dt;
        });
        benchmark::ClobberMemory();
    }
    set_items(state, entity_count);
}

void BM_Iterate_EcsRangeFor(benchmark::State& state) {
    Registry registry;
    fill(registry);
    for (auto _ : state) {
        for (auto [entity, p, v] : registry.view<Position, Velocity>()) {
            p.x += v.x * dt;
            p.y += v.y * dt;
            p.z += v.z * dt;
        }
        benchmark::ClobberMemory();
    }
    set_items(state, entity_count);
}

void BM_Iterate_Vector(benchmark::State& state) {
    std::vector<Body> bodies = make_bodies();
    for (auto _ : state) {
        for (Body& body : bodies) {
            body.position.x += body.velocity.x * dt;
            body.position.y += body.velocity.y * dt;
            body.position.z += body.velocity.z * dt;
        }
        benchmark::ClobberMemory();
    }
    set_items(state, entity_count);
}

// ---- Changes ------------------------------------------------------------------------------
// Work per iteration: move k entities (a tracked write), then visit each changed entity once and
// read its position. The vector side keeps the cheapest honest equivalent: a dirty flag per body
// (to visit each once) and a list of dirty indices (to avoid scanning everything).

struct TrackedBodies {
    std::vector<Body> bodies = make_bodies();
    std::vector<std::uint8_t> dirty = std::vector<std::uint8_t>(entity_count, 0);
    std::vector<std::uint32_t> dirty_list;

    void move(std::uint32_t index) {
        bodies[index].position.y += 1.0f;
        if (dirty[index] == 0) {
            dirty[index] = 1;
            dirty_list.push_back(index);
        }
    }
    float read_changes() {
        float sum = 0.0f;
        for (const std::uint32_t index : dirty_list) {
            sum += bodies[index].position.y;
            dirty[index] = 0;
        }
        dirty_list.clear();
        return sum;
    }
};

void move_ecs(Registry& registry, const std::vector<Entity>& entities,
              const std::vector<std::uint32_t>& subset) {
    for (const std::uint32_t index : subset) {
        registry.patch<Position>(entities[index], [](Position& p) { p.y += 1.0f; });
    }
}

float read_ecs(Observer<Position>& observer) {
    float sum = 0.0f;
    observer.consume([&sum](Entity, ChangeKind, const Position* p) { sum += p->y; });
    return sum;
}

void BM_Changes_Ecs(benchmark::State& state) {
    const auto k = static_cast<std::size_t>(state.range(0));
    Registry registry;
    std::vector<Entity> entities;
    fill(registry, &entities);
    Observer<Position> observer = registry.observe<Position>();
    const std::vector<std::uint32_t> subset = random_subset(k);
    for (auto _ : state) {
        move_ecs(registry, entities, subset);
        benchmark::DoNotOptimize(read_ecs(observer));
    }
    set_items(state, k);
}

void BM_Changes_Vector(benchmark::State& state) {
    const auto k = static_cast<std::size_t>(state.range(0));
    TrackedBodies tracked;
    const std::vector<std::uint32_t> subset = random_subset(k);
    for (auto _ : state) {
        for (const std::uint32_t index : subset) {
            tracked.move(index);
        }
        benchmark::DoNotOptimize(tracked.read_changes());
    }
    set_items(state, k);
}

// The reading half alone, timed by hand around the read (PauseTiming costs about a
// microsecond, as much as a whole 0.1% read).
using Clock = std::chrono::steady_clock;

void set_manual_time(benchmark::State& state, Clock::time_point start) {
    state.SetIterationTime(std::chrono::duration<double>(Clock::now() - start).count());
}

void BM_ChangesRead_Ecs(benchmark::State& state) {
    const auto k = static_cast<std::size_t>(state.range(0));
    Registry registry;
    std::vector<Entity> entities;
    fill(registry, &entities);
    Observer<Position> observer = registry.observe<Position>();
    const std::vector<std::uint32_t> subset = random_subset(k);
    for (auto _ : state) {
        move_ecs(registry, entities, subset);
        const Clock::time_point start = Clock::now();
        benchmark::DoNotOptimize(read_ecs(observer));
        set_manual_time(state, start);
    }
    set_items(state, k);
}

void BM_ChangesRead_Vector(benchmark::State& state) {
    const auto k = static_cast<std::size_t>(state.range(0));
    TrackedBodies tracked;
    const std::vector<std::uint32_t> subset = random_subset(k);
    for (auto _ : state) {
        for (const std::uint32_t index : subset) {
            tracked.move(index);
        }
        const Clock::time_point start = Clock::now();
        benchmark::DoNotOptimize(tracked.read_changes());
        set_manual_time(state, start);
    }
    set_items(state, k);
}

void BM_ChangesScan_Vector(benchmark::State& state) {
    const auto k = static_cast<std::size_t>(state.range(0));
    TrackedBodies tracked;
    const std::vector<std::uint32_t> subset = random_subset(k);
    for (auto _ : state) {
        for (const std::uint32_t index : subset) {
            tracked.bodies[index].position.y += 1.0f;
            tracked.dirty[index] = 1;
        }
        float sum = 0.0f;
        for (std::size_t i = 0; i < entity_count; ++i) {
            if (tracked.dirty[i] != 0) {
                sum += tracked.bodies[i].position.y;
                tracked.dirty[i] = 0;
            }
        }
        benchmark::DoNotOptimize(sum);
    }
    set_items(state, k);
}

/// k = 0.1%, 1% and 10% of the entities.
void change_fractions(benchmark::internal::Benchmark* benchmark) {
    for (const std::int64_t per_mille : {1, 10, 100}) {
        benchmark->Arg(static_cast<std::int64_t>(entity_count) * per_mille / 1000);
    }
    benchmark->Unit(benchmark::kMicrosecond);
}

}  // namespace

BENCHMARK(BM_Create_Ecs)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Create_Vector)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Iterate_Ecs)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Iterate_EcsFreshView)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Iterate_EcsRangeFor)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Iterate_Vector)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Changes_Ecs)->Apply(change_fractions);
BENCHMARK(BM_Changes_Vector)->Apply(change_fractions);
BENCHMARK(BM_ChangesRead_Ecs)->Apply(change_fractions)->UseManualTime();
BENCHMARK(BM_ChangesRead_Vector)->Apply(change_fractions)->UseManualTime();
BENCHMARK(BM_ChangesScan_Vector)->Apply(change_fractions);

BENCHMARK_MAIN();
