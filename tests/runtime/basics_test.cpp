// Clocks, the job system and logging.

#include <atomic>
#include <chrono>
#include <mutex>
#include <numeric>
#include <set>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "luxel/runtime/clock.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/runtime/jobs.hpp"
#include "luxel/runtime/log.hpp"

namespace {

using namespace std::chrono_literals;

TEST(Clock, ManualClockDrivesStopwatchAndFrameClock) {
    luxel::ManualClock clock(5ms);
    luxel::Stopwatch stopwatch(clock);
    clock.advance(1500us);
    EXPECT_DOUBLE_EQ(stopwatch.elapsed_ms(), 1.5);
    stopwatch.restart();
    EXPECT_EQ(stopwatch.elapsed(), 0ns);

    luxel::FrameClock frames(clock);
    const auto first = frames.tick();
    EXPECT_EQ(first.index, 0u);
    EXPECT_EQ(first.delta_seconds, 0.0);
    clock.advance(16ms);
    const auto second = frames.tick();
    EXPECT_EQ(second.index, 1u);
    EXPECT_DOUBLE_EQ(second.delta_seconds, 0.016);
    clock.advance(20ms);
    const auto third = frames.tick();
    EXPECT_EQ(third.index, 2u);
    EXPECT_DOUBLE_EQ(third.delta_seconds, 0.020);
    EXPECT_DOUBLE_EQ(third.total_seconds, 0.036);
}

TEST(Clock, SteadyClockIsMonotonic) {
    const auto& clock = luxel::SteadyClock::instance();
    auto previous = clock.now();
    for (int i = 0; i < 1000; ++i) {
        const auto now = clock.now();
        ASSERT_GE(now, previous);
        previous = now;
    }
    EXPECT_NEAR(luxel::to_milliseconds(luxel::from_milliseconds(2.5)), 2.5, 1e-9);
}

TEST(JobSystem, ParallelForVisitsEveryIndexOnce) {
    luxel::JobSystem jobs(2);
    EXPECT_EQ(jobs.thread_count(), 2);
    std::vector<std::atomic<int>> visits(10'000);
    jobs.parallel_for(
        0, visits.size(), [&](std::size_t i) { visits[i].fetch_add(1); }, 64);
    for (const auto& v : visits) {
        ASSERT_EQ(v.load(), 1);
    }
}

TEST(JobSystem, ThreadCountBoundsConcurrency) {
    luxel::JobSystem jobs(1);
    std::mutex mutex;
    std::set<std::thread::id> threads;
    jobs.parallel_for(0, 2000, [&](std::size_t) {
        const std::lock_guard lock(mutex);
        threads.insert(std::this_thread::get_id());
    });
    EXPECT_EQ(threads.size(), 1u);
    EXPECT_EQ(luxel::JobSystem(0).thread_count(), luxel::JobSystem::hardware_threads());
    const int sum = jobs.run([] { return 40 + 2; });
    EXPECT_EQ(sum, 42);
}

TEST(Log, LevelsParseAndFilter) {
    EXPECT_EQ(luxel::log::parse_level("debug"), luxel::log::Level::Debug);
    EXPECT_THROW((void)luxel::log::parse_level("loud"), luxel::Error);
    const auto saved = luxel::log::level();
    luxel::log::set_level(luxel::log::Level::Warn);
    EXPECT_FALSE(luxel::log::enabled(luxel::log::Level::Info));
    EXPECT_TRUE(luxel::log::enabled(luxel::log::Level::Error));
    luxel::log::set_level(luxel::log::Level::Off);
    EXPECT_FALSE(luxel::log::enabled(luxel::log::Level::Error));
    luxel::log::set_level(saved);
}

}  // namespace
