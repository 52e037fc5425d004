// The Scheduler's rules, one at a time: deduplication, priority order, budget fitting,
// forced units, pause and resume, callbacks that enqueue or cancel, per-kind shares.

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "luxel/lighting/core/scheduler.hpp"
#include "luxel/runtime/clock.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;

/// A callback that costs `ms` on the clock and logs its name.
std::function<void()> costs(ManualClock& clock, double ms, std::vector<std::string>* log = nullptr,
                            std::string label = {}) {
    return [&clock, ms, log, label] {
        clock.advance(from_milliseconds(ms));
        if (log != nullptr) {
            log->push_back(label);
        }
    };
}

/// Settings whose priors are exact for costs() units of size 1 costing `ms`.
SchedulerSettings priors_of(double ms) {
    SchedulerSettings settings;
    settings.cost.prior_ms.fill(ms);
    settings.cost.prior_relative_deviation = 0.0;
    return settings;
}

TEST(Scheduler, EnqueueMergesTheSameKindAndKey) {
    ManualClock clock;
    Scheduler s(clock, priors_of(1.0));
    std::vector<std::string> log;
    s.enqueue({WorkKind::IimGather, 7, 0.9, costs(clock, 1.0, &log, "first")});
    s.enqueue({WorkKind::IimGather, 7, 0.1, costs(clock, 1.0, &log, "second")});
    s.enqueue({WorkKind::AimRebuild, 7, 0.5, costs(clock, 1.0, &log, "aim")});
    EXPECT_EQ(s.pending(WorkKind::IimGather), 1U);
    EXPECT_EQ(s.pending(WorkKind::AimRebuild), 1U);  // same key, other kind: another unit
    EXPECT_EQ(s.pending_total(), 2U);
    const FrameReport r = s.run(100.0);
    // The later callback replaced the first; the priority kept is the max (0.9 * 2 = 1.8 for
    // the gather, 0.5 * 3 = 1.5 for the AIM rebuild), so the gather went first.
    ASSERT_EQ(log.size(), 2U);
    EXPECT_EQ(log[0], "second");
    EXPECT_EQ(log[1], "aim");
    EXPECT_EQ(r.units_done, 2U);
    EXPECT_EQ(s.pending_total(), 0U);
}

TEST(Scheduler, EmptyCallbackIsRejected) {
    ManualClock clock;
    Scheduler s(clock);
    EXPECT_THROW(s.enqueue({WorkKind::IimGather, 0, 1.0, {}}), std::invalid_argument);
    // A kind past the enum's end (a cast from a number) would index past every per-kind array.
    EXPECT_THROW(s.enqueue({static_cast<WorkKind>(kWorkKindCount), 0, 1.0, [] {}}),
                 std::invalid_argument);
    EXPECT_EQ(s.pending_total(), 0U);
}

TEST(Scheduler, HigherEffectivePriorityGoesFirst) {
    ManualClock clock;
    Scheduler s(clock, priors_of(1.0));
    std::vector<std::string> log;
    // Effective priority = priority * weight (6 5 4 3 2 by kind).
    s.enqueue({WorkKind::IimGather, 0, 0.5, costs(clock, 1.0, &log, "gather-mid")});  // 1
    s.enqueue({WorkKind::IimGather, 1, 0.2, costs(clock, 1.0, &log, "gather-lo")});   // 0.4
    s.enqueue({WorkKind::IimGather, 2, 0.9, costs(clock, 1.0, &log, "gather-hi")});   // 1.8
    s.enqueue({WorkKind::AimRebuild, 3, 0.5, costs(clock, 1.0, &log, "aim")});        // 1.5
    s.enqueue({WorkKind::CausticSlice, 4, 0.5, costs(clock, 1.0, &log, "caustic")});  // 2
    s.enqueue({WorkKind::GroupRetrace, 5, 0.5, costs(clock, 1.0, &log, "retrace")});  // 2.5
    s.enqueue({WorkKind::PhotonProbe, 6, 0.5, costs(clock, 1.0, &log, "probe")});     // 3
    s.enqueue({WorkKind::PhotonProbe, 7, 0.5, costs(clock, 1.0, &log, "probe-2")});   // 3, later
    const FrameReport r = s.run(std::numeric_limits<double>::infinity());
    const std::vector<std::string> expected = {"probe",     "probe-2", "retrace",    "caustic",
                                               "gather-hi", "aim",     "gather-mid", "gather-lo"};
    EXPECT_EQ(log, expected);
    EXPECT_EQ(r.units_done, 8U);
    EXPECT_DOUBLE_EQ(r.used_ms, 8.0);
}

TEST(Scheduler, ABudgetTakesTheHighestPrioritiesThatFit) {
    ManualClock clock;
    Scheduler s(clock, priors_of(1.0));
    std::vector<std::string> log;
    for (int i = 0; i < 10; ++i) {
        s.enqueue({WorkKind::GroupRetrace, static_cast<std::uint64_t>(i), 0.1 * i,
                   costs(clock, 1.0, &log, std::to_string(i))});
    }
    const FrameReport r = s.run(3.0);
    EXPECT_EQ(log, (std::vector<std::string>{"9", "8", "7"}));
    EXPECT_EQ(r.kinds[index(WorkKind::GroupRetrace)].units_done, 3U);
    EXPECT_EQ(r.kinds[index(WorkKind::GroupRetrace)].pending_after, 7U);
    EXPECT_DOUBLE_EQ(r.kinds[index(WorkKind::GroupRetrace)].ms, 3.0);
    EXPECT_DOUBLE_EQ(r.kinds[index(WorkKind::GroupRetrace)].predicted_ms, 3.0);
    EXPECT_DOUBLE_EQ(r.used_ms, 3.0);
    EXPECT_EQ(r.forced_units, 0U);
}

TEST(Scheduler, SkipsAUnitThatDoesNotFitForSmallerOnes) {
    ManualClock clock;
    SchedulerSettings settings = priors_of(1.0);
    Scheduler s(clock, settings);
    std::vector<std::string> log;
    s.enqueue({WorkKind::AimRebuild, 1, 1.0, costs(clock, 5.0, &log, "big"), 5.0});
    s.enqueue({WorkKind::IimGather, 2, 0.1, costs(clock, 1.0, &log, "small")});
    const FrameReport r = s.run(2.0);
    EXPECT_EQ(log, (std::vector<std::string>{"small"}));
    EXPECT_TRUE(s.queued(WorkKind::AimRebuild, 1));
    EXPECT_LE(r.used_ms, 2.0);
}

TEST(Scheduler, AnOverdueUnitIsForcedOncePerFrame) {
    ManualClock clock;
    SchedulerSettings settings = priors_of(1.0);
    settings.max_wait_frames = 5;
    settings.record_units = true;
    Scheduler s(clock, settings);
    std::vector<std::string> log;
    // Two units predicted at 10 ms never fit a 4 ms budget.
    s.enqueue({WorkKind::AimRebuild, 1, 1.0, costs(clock, 10.0, &log, "a"), 10.0});
    s.enqueue({WorkKind::AimRebuild, 2, 1.0, costs(clock, 10.0, &log, "b"), 10.0});
    for (int f = 0; f < 5; ++f) {
        const FrameReport r = s.run(4.0);
        EXPECT_EQ(r.units_done, 0U) << "frame " << f;
    }
    // Frame 5: both have waited 5 frames; only the first (oldest) is forced.
    FrameReport r = s.run(4.0);
    EXPECT_EQ(log, (std::vector<std::string>{"a"}));
    EXPECT_EQ(r.forced_units, 1U);
    EXPECT_DOUBLE_EQ(r.forced_ms, 10.0);
    EXPECT_DOUBLE_EQ(r.overrun_ms(), 6.0);  // exactly the forced unit's cost minus the budget
    ASSERT_EQ(r.units.size(), 1U);
    EXPECT_TRUE(r.units[0].forced);
    EXPECT_EQ(r.units[0].waited_frames, 5U);
    r = s.run(4.0);
    EXPECT_EQ(log, (std::vector<std::string>{"a", "b"}));
    EXPECT_EQ(r.forced_units, 1U);
    EXPECT_EQ(s.totals().forced_units, 2U);
    EXPECT_EQ(s.pending_total(), 0U);
}

TEST(Scheduler, AForcedUnitThatTurnsOutCheapLeavesRoomForOthers) {
    ManualClock clock;
    SchedulerSettings settings = priors_of(1.0);
    settings.max_wait_frames = 0;  // everything is overdue at once
    Scheduler s(clock, settings);
    std::vector<std::string> log;
    // Predicted 10 ms (size 10) but costs 1 ms.
    s.enqueue({WorkKind::AimRebuild, 1, 1.0, costs(clock, 1.0, &log, "cheap"), 10.0});
    s.enqueue({WorkKind::IimGather, 2, 1.0, costs(clock, 1.0, &log, "gather")});
    const FrameReport r = s.run(4.0);
    EXPECT_EQ(log, (std::vector<std::string>{"cheap", "gather"}));
    EXPECT_EQ(r.forced_units, 1U);
    EXPECT_DOUBLE_EQ(r.used_ms, 2.0);
}

TEST(Scheduler, BudgetZeroPausesEverythingAndResumingDrainsTheBacklog) {
    ManualClock clock;
    SchedulerSettings settings = priors_of(1.0);
    settings.max_wait_frames = 2;  // would be overdue at once if paused frames counted
    Scheduler s(clock, settings);
    int ran = 0;
    std::vector<int> runs(40, 0);
    for (int i = 0; i < 40; ++i) {
        s.enqueue({static_cast<WorkKind>(i % static_cast<int>(kWorkKindCount)),
                   static_cast<std::uint64_t>(i), 0.5, [&clock, &ran, &runs, i] {
                       clock.advance(from_milliseconds(1.0));
                       ++ran;
                       ++runs[static_cast<std::size_t>(i)];
                   }});
    }
    for (double budget : {0.0, -1.0, std::nan(""), -std::numeric_limits<double>::infinity()}) {
        for (int f = 0; f < 50; ++f) {
            const FrameReport r = s.run(budget);
            ASSERT_TRUE(r.paused);
            ASSERT_EQ(r.units_done, 0U);
            ASSERT_EQ(r.forced_units, 0U);
            ASSERT_EQ(r.pending_after(), 40U);
        }
    }
    EXPECT_EQ(ran, 0);
    EXPECT_EQ(clock.now(), Nanoseconds{0});
    EXPECT_EQ(s.frame(), 0U);  // paused frames do not age the queues
    EXPECT_EQ(s.pending_total(), 40U);
    // Resume at 5 ms a frame: 40 units of 1 ms drain in 8 frames, none forced, none twice.
    int frames = 0;
    while (s.pending_total() > 0 && frames < 100) {
        const FrameReport r = s.run(5.0);
        EXPECT_LE(r.used_ms, 5.0);
        EXPECT_EQ(r.forced_units, 0U);
        ++frames;
    }
    EXPECT_EQ(frames, 8);
    EXPECT_EQ(ran, 40);
    for (int count : runs) {
        EXPECT_EQ(count, 1);
    }
}

TEST(Scheduler, CallbacksMayEnqueueAndCancel) {
    ManualClock clock;
    Scheduler s(clock, priors_of(1.0));
    std::vector<std::string> log;
    // The probe finds a divergent group: it enqueues a retrace (next frame) and cancels a
    // stale gather that was queued behind it.
    s.enqueue({WorkKind::PhotonProbe, 1, 1.0, [&] {
                   clock.advance(from_milliseconds(1.0));
                   log.push_back("probe");
                   s.enqueue({WorkKind::GroupRetrace, 9, 1.0, costs(clock, 1.0, &log, "retrace")});
                   EXPECT_TRUE(s.cancel(WorkKind::IimGather, 3));
                   EXPECT_THROW(s.run(1.0), std::logic_error);
               }});
    s.enqueue({WorkKind::IimGather, 3, 0.1, costs(clock, 1.0, &log, "stale")});
    FrameReport r = s.run(10.0);
    EXPECT_EQ(log, (std::vector<std::string>{"probe"}));
    EXPECT_EQ(r.units_done, 1U);
    EXPECT_EQ(s.pending(WorkKind::GroupRetrace), 1U);
    EXPECT_FALSE(s.cancel(WorkKind::IimGather, 3));
    r = s.run(10.0);
    EXPECT_EQ(log, (std::vector<std::string>{"probe", "retrace"}));
}

TEST(Scheduler, ACallbackThatThrowsDropsItsUnitOnly) {
    ManualClock clock;
    Scheduler s(clock, priors_of(1.0));
    s.enqueue({WorkKind::PhotonProbe, 1, 1.0, [] { throw std::runtime_error("boom"); }});
    s.enqueue({WorkKind::IimGather, 2, 1.0, costs(clock, 1.0)});
    EXPECT_THROW(s.run(10.0), std::runtime_error);
    EXPECT_FALSE(s.queued(WorkKind::PhotonProbe, 1));
    EXPECT_TRUE(s.queued(WorkKind::IimGather, 2));
    const FrameReport r = s.run(10.0);  // still usable: not stuck "running"
    EXPECT_EQ(r.units_done, 1U);
}

TEST(Scheduler, AShareCapsAKind) {
    ManualClock clock;
    SchedulerSettings settings = priors_of(1.0);
    settings.max_share[index(WorkKind::GroupRetrace)] = 0.5;
    Scheduler s(clock, settings);
    for (std::uint64_t i = 0; i < 10; ++i) {
        s.enqueue({WorkKind::GroupRetrace, i, 1.0, costs(clock, 1.0)});
        s.enqueue({WorkKind::IimGather, i, 0.1, costs(clock, 1.0)});
    }
    const FrameReport r = s.run(8.0);
    // Retraces outrank gathers, but may take only half of the 8 ms.
    EXPECT_EQ(r.kinds[index(WorkKind::GroupRetrace)].units_done, 4U);
    EXPECT_EQ(r.kinds[index(WorkKind::IimGather)].units_done, 4U);
}

TEST(Scheduler, AShareChangedBetweenFramesAppliesFromTheNextRun) {
    ManualClock clock;
    SchedulerSettings settings = priors_of(1.0);
    settings.max_share[index(WorkKind::CausticSlice)] = 0.25;
    Scheduler s(clock, settings);
    const auto fill = [&] {
        for (std::uint64_t i = 0; i < 10; ++i) {
            s.enqueue({WorkKind::CausticSlice, i, 1.0, costs(clock, 1.0)});
            s.enqueue({WorkKind::IimGather, i, 0.1, costs(clock, 1.0)});
        }
    };
    fill();
    EXPECT_EQ(s.run(8.0).kinds[index(WorkKind::CausticSlice)].units_done, 2U);
    s.set_max_share(WorkKind::CausticSlice, 0.5);  // catching up after a change
    EXPECT_DOUBLE_EQ(s.max_share(WorkKind::CausticSlice), 0.5);
    fill();
    EXPECT_EQ(s.run(8.0).kinds[index(WorkKind::CausticSlice)].units_done, 4U);
    // Outside (0, 1), and not finite: no cap.
    for (const double none : {0.0, 1.0, -1.0, std::numeric_limits<double>::quiet_NaN()}) {
        s.set_max_share(WorkKind::CausticSlice, none);
        EXPECT_EQ(s.max_share(WorkKind::CausticSlice), 0.0);
    }
    s.clear();
    fill();
    EXPECT_EQ(s.run(8.0).kinds[index(WorkKind::CausticSlice)].units_done, 8U);
}

TEST(Scheduler, AgingLiftsOldLowPriorityUnits) {
    ManualClock clock;
    SchedulerSettings settings = priors_of(1.0);
    settings.aging_per_frame = 0.45;
    Scheduler s(clock, settings);
    std::vector<std::string> log;
    s.enqueue({WorkKind::IimGather, 0, 0.0, costs(clock, 1.0, &log, "old-gather")});
    // Each frame one fresh retrace of priority 0.4 (effective 2) competes for a 1 ms budget.
    // The gather (effective 0.45 per frame waited) wins once it has waited 5 frames (2.25 > 2).
    for (int f = 0; f < 10 && log.size() < 6; ++f) {
        s.enqueue({WorkKind::GroupRetrace, static_cast<std::uint64_t>(f), 0.4,
                   costs(clock, 1.0, &log, "retrace")});
        s.run(1.0);
    }
    ASSERT_EQ(log.size(), 6U);
    EXPECT_EQ(log[4], "retrace");
    EXPECT_EQ(log[5], "old-gather");
}

TEST(Scheduler, ReportsPredictionsAgainstActualCosts) {
    ManualClock clock;
    SchedulerSettings settings;
    settings.record_units = true;
    settings.cost.prior_ms[index(WorkKind::CausticSlice)] = 0.5;
    Scheduler s(clock, settings);
    s.enqueue({WorkKind::CausticSlice, 0, 1.0, costs(clock, 0.8), 1.0});
    const FrameReport r = s.run(4.0);
    const KindFrameReport& k = r.kinds[index(WorkKind::CausticSlice)];
    EXPECT_DOUBLE_EQ(k.predicted_ms, 0.5);
    EXPECT_NEAR(k.ms, 0.8, 1e-6);
    EXPECT_NEAR(r.max_error_ms, 0.3, 1e-6);
    EXPECT_GT(r.max_error_bound_ms, 0.0);
    EXPECT_NEAR(r.predicted_ms(), 0.5, 1e-12);
    ASSERT_EQ(r.units.size(), 1U);
    EXPECT_EQ(r.units[0].kind, WorkKind::CausticSlice);
    EXPECT_EQ(s.cost_model().cost(WorkKind::CausticSlice).samples, 1U);
    EXPECT_NEAR(s.totals().kinds[index(WorkKind::CausticSlice)].actual_ms, 0.8, 1e-6);
    // The first measurement replaced the prior (prior_weight 0).
    EXPECT_NEAR(s.cost_model().predict(WorkKind::CausticSlice, 1.0), 0.8, 1e-6);
}

}  // namespace
