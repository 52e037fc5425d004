// Frame-budget tests (issue 8): thousands of frames of a scripted scene whose moving objects
// keep enqueuing work, with randomized unit costs on an injected ManualClock. Every number here
// is deterministic: the same seed replays the same frames.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "luxel/lighting/core/scheduler.hpp"
#include "luxel/runtime/clock.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;

constexpr double kBudgetMs = 4.0;
constexpr std::uint64_t kFrames = 3000;
/// Frames during which the cost model is still learning from its priors (some of which are
/// 10x off): the overrun bound is asserted from this frame on.
constexpr std::uint64_t kWarmupFrames = 20;
/// Comparisons of clock times tolerate the nanosecond rounding of from_milliseconds.
constexpr double kClockSlackMs = 1e-5;

/// A level with six moving objects, as the LightingSystem would feed the scheduler:
/// - photon probes: 4 a frame, round robin over 256 groups (0.03 ms each);
/// - group retraces: each moving object invalidates one random group of 300 a frame (0.2 ms);
/// - caustic slices: one of 8 every other frame (0.6 ms);
/// - AIM rebuilds: one random surface of 40 every 10 frames, size (area) 0.3..3, 2.5 ms per
///   unit of size, so up to 7.5 ms: the big ones never fit a 4 ms budget and need forcing;
/// - IIM gathers: 2 batches a frame of 16..64 texels among 500 batches (0.004 ms per texel);
/// - irradiance probe passes: a unit of 4 probes every third frame among 64 (0.02 ms a probe);
/// - every 500 frames a light is switched: all 300 groups invalidated at once (60 ms of work).
/// Each unit's actual cost is its mean times U(0.7, 1.3). The mean load is about 2.4 ms a
/// frame, 60 % of the 4 ms budget, plus the bursts.
class ScriptedScene {
  public:
    explicit ScriptedScene(std::uint32_t seed, SchedulerSettings settings = default_settings())
        : scheduler_(clock_, settings), script_rng_(seed), cost_rng_(seed * 7919U + 1U) {}

    static SchedulerSettings default_settings() {
        SchedulerSettings settings;
        settings.record_units = true;
        return settings;
    }

    /// One frame: the script's enqueues, then the scheduler with `budget_ms`.
    FrameReport frame(double budget_ms, bool moving = true) {
        if (moving) {
            script();
        }
        FrameReport report = scheduler_.run(budget_ms);
        ++frame_;
        return report;
    }

    Scheduler& scheduler() { return scheduler_; }
    /// Multiplies every unit's cost from now on (a heavier scene).
    void set_cost_scale(double scale) { cost_scale_ = scale; }
    /// The mean cost per unit of size of `kind`, as the script draws it now.
    double true_cost(WorkKind kind) const { return kMeanMs[index(kind)] * cost_scale_; }

    /// Largest number of frames a unit took from its first enqueue to its run, counting both
    /// (1 = run in the frame it was enqueued).
    std::uint64_t max_frames_to_done() const { return max_frames_to_done_; }
    std::uint64_t units_done() const { return units_done_; }
    PerKind<std::uint64_t> units_done_per_kind() const { return done_per_kind_; }
    std::size_t outstanding() const { return enqueued_at_.size(); }

  private:
    static constexpr PerKind<double> kMeanMs = {0.03, 0.2, 0.6, 2.5, 0.004, 0.02};

    void script() {
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        const std::uint64_t f = frame_;
        for (std::uint64_t i = 0; i < 4; ++i) {
            enqueue(WorkKind::PhotonProbe, (4 * f + i) % 256, 0.5, 1.0);
        }
        std::uniform_int_distribution<std::uint64_t> group(0, 299);
        for (int object = 0; object < 6; ++object) {
            enqueue(WorkKind::GroupRetrace, group(script_rng_), 0.2 + 0.8 * unit(script_rng_), 1.0);
        }
        if (f % 2 == 0) {
            enqueue(WorkKind::CausticSlice, (f / 2) % 8, 0.5, 1.0);
        }
        if (f % 10 == 0) {
            std::uniform_int_distribution<std::uint64_t> surface(0, 39);
            const std::uint64_t key = surface(script_rng_);
            const double priority = unit(script_rng_);
            enqueue(WorkKind::AimRebuild, key, priority, 0.3 + 2.7 * unit(script_rng_));
        }
        std::uniform_int_distribution<std::uint64_t> batch(0, 499);
        for (int b = 0; b < 2; ++b) {
            const std::uint64_t key = batch(script_rng_);
            const double priority = unit(script_rng_);
            enqueue(WorkKind::IimGather, key, priority, 16.0 + 48.0 * unit(script_rng_));
        }
        if (f % 3 == 0) {
            enqueue(WorkKind::ProbeGather, (f / 3) % 64, unit(script_rng_), 4.0);
        }
        if (f % 500 == 250) {
            for (std::uint64_t g = 0; g < 300; ++g) {
                enqueue(WorkKind::GroupRetrace, g, 1.0, 1.0);
            }
        }
    }

    void enqueue(WorkKind kind, std::uint64_t key, double priority, double size) {
        const std::pair<std::size_t, std::uint64_t> id{index(kind), key};
        if (!scheduler_.queued(kind, key)) {
            enqueued_at_[id] = frame_;
        }
        scheduler_.enqueue({kind, key, priority,
                            [this, id, kind, size] {
                                std::uniform_real_distribution<double> noise(0.7, 1.3);
                                const double ms = true_cost(kind) * size * noise(cost_rng_);
                                clock_.advance(from_milliseconds(ms));
                                const auto it = enqueued_at_.find(id);
                                ASSERT_NE(it, enqueued_at_.end());
                                const std::uint64_t waited = frame_ - it->second;
                                enqueued_at_.erase(it);
                                max_frames_to_done_ = std::max(max_frames_to_done_, waited + 1);
                                ++units_done_;
                                ++done_per_kind_[id.first];
                            },
                            size});
    }

    ManualClock clock_;
    Scheduler scheduler_;
    std::mt19937 script_rng_;
    std::mt19937 cost_rng_;
    double cost_scale_ = 1.0;
    std::uint64_t frame_ = 0;
    std::map<std::pair<std::size_t, std::uint64_t>, std::uint64_t> enqueued_at_;
    std::uint64_t max_frames_to_done_ = 0;
    std::uint64_t units_done_ = 0;
    PerKind<std::uint64_t> done_per_kind_{};
};

TEST(FrameBudget, NoFrameOverrunsByMoreThanOneUnitsPredictionError) {
    ScriptedScene scene(1234);
    std::uint64_t forced_frames = 0;
    std::uint64_t overrun_frames = 0;
    std::uint64_t backlog_frames = 0;  // frames that ended with retraces still queued
    std::uint64_t warmup_violations = 0;
    double worst_overrun = 0.0;
    for (std::uint64_t f = 0; f < kFrames; ++f) {
        const FrameReport r = scene.frame(kBudgetMs);
        ASSERT_FALSE(r.paused);
        ASSERT_LE(r.forced_units, 1U);
        if (r.forced_units == 1) {
            ++forced_frames;
            ASSERT_FALSE(r.units.empty());
            EXPECT_TRUE(r.units.front().forced) << "a forced unit runs first, frame " << f;
        }
        if (r.kinds[index(WorkKind::GroupRetrace)].pending_after > 0 && r.forced_units == 0) {
            // The budget is used, not hoarded: with small units (retraces, ~0.2 ms) left, the
            // frame stopped only when the next one could not fit.
            ++backlog_frames;
            const CostModel& model = scene.scheduler().cost_model();
            const double retrace = model.predict(WorkKind::GroupRetrace, 1.0) +
                                   model.prediction_error(WorkKind::GroupRetrace, 1.0);
            ASSERT_GE(r.used_ms, kBudgetMs - retrace) << "frame " << f;
        }
        if (r.overrun_ms() > 0.0) {
            ++overrun_frames;
            worst_overrun = std::max(worst_overrun, r.overrun_ms());
        }
        if (r.units.empty()) {
            continue;
        }
        // Units start only when their prediction fits, so only the last one can overrun, and
        // by no more than its own prediction error. A forced unit runs first on the whole
        // budget: then the frame overruns by at most that unit's own cost (or, if it turned
        // out to fit, the last unit's error).
        const double last_bound = r.units.back().error_bound_ms;
        const double allowed =
            (r.forced_units == 0 ? last_bound : std::max(r.forced_ms, last_bound)) + kClockSlackMs;
        if (f < kWarmupFrames) {
            warmup_violations += r.overrun_ms() > allowed ? 1U : 0U;
        } else {
            ASSERT_LE(r.overrun_ms(), allowed) << "frame " << f;
        }
    }
    // While the priors are being replaced (the AIM prior is 1 ms, the script's 2.5 ms per
    // unit), the first frames may overrun more.
    EXPECT_LE(warmup_violations, 3U);
    // The AIM rebuilds above 1.6 units of size (predicted over 4 ms: 52 % of the 300 enqueued,
    // fewer after merging by surface) can only run forced: measured 141 forced frames of 3000.
    EXPECT_GE(forced_frames, kFrames / 40);
    EXPECT_LE(forced_frames, kFrames / 15);
    // Overruns are rare (forced frames and the odd unlucky last unit) and small.
    EXPECT_LE(overrun_frames, kFrames / 10);
    // The bursts (and the random retraces that keep arriving) did leave backlogs to check.
    EXPECT_GE(backlog_frames, 100U);
    const SchedulerTotals& totals = scene.scheduler().totals();
    EXPECT_EQ(totals.frames, kFrames);
    EXPECT_EQ(totals.forced_units, forced_frames);
    RecordProperty("warmup_violations", static_cast<int>(warmup_violations));
    RecordProperty("forced_frames", static_cast<int>(forced_frames));
    RecordProperty("overrun_frames", static_cast<int>(overrun_frames));
    RecordProperty("worst_overrun_us", static_cast<int>(worst_overrun * 1000.0));
}

TEST(FrameBudget, EveryUnitIsDoneWithinABoundedNumberOfFrames) {
    ScriptedScene scene(99);
    const std::uint32_t max_wait = scene.scheduler().settings().max_wait_frames;
    for (std::uint64_t f = 0; f < kFrames; ++f) {
        scene.frame(kBudgetMs);
    }
    // The scene stops; what is queued drains.
    for (int f = 0; f < 100 && scene.scheduler().pending_total() > 0; ++f) {
        scene.frame(kBudgetMs, false);
    }
    EXPECT_EQ(scene.scheduler().pending_total(), 0U);
    EXPECT_EQ(scene.outstanding(), 0U);
    // The bound: overdue after max_wait_frames (30), then forced or fitted within a few frames
    // (at most one overdue unit has to be forced per frame; the light-switch bursts make a
    // handful overdue at once). Measured 31 with this seed; stated with margin.
    EXPECT_LE(scene.max_frames_to_done(), max_wait + 10U);
    for (std::size_t k = 0; k < kWorkKindCount; ++k) {
        EXPECT_GT(scene.units_done_per_kind()[k], 0U) << name(static_cast<WorkKind>(k));
    }
    RecordProperty("max_frames_to_done", static_cast<int>(scene.max_frames_to_done()));
}

TEST(FrameBudget, NoStarvationEvenWhenTheLoadSaturatesTheBudget) {
    // A 2.5 ms budget for a 2.4 ms mean load: the queues are nearly always non-empty and the
    // bursts take long to drain. Low-priority gathers and AIM rebuilds must still get through.
    ScriptedScene scene(5);
    const std::uint32_t max_wait = scene.scheduler().settings().max_wait_frames;
    for (std::uint64_t f = 0; f < kFrames; ++f) {
        scene.frame(2.5);
    }
    for (int f = 0; f < 1000 && scene.scheduler().pending_total() > 0; ++f) {
        scene.frame(2.5, false);
    }
    EXPECT_EQ(scene.outstanding(), 0U);
    // Measured 32 with this seed.
    EXPECT_LE(scene.max_frames_to_done(), max_wait + 10U);
    RecordProperty("max_frames_to_done", static_cast<int>(scene.max_frames_to_done()));
}

TEST(FrameBudget, HigherPriorityKindsGoFirstUnderLoad) {
    // Units run in priority order, and in the 10 frames after a light switch retraces
    // (weight 5) take the budget while gathers (weight 2) wait: far fewer gathers are done
    // than in calm frames.
    ScriptedScene scene(42);
    const std::uint32_t max_wait = scene.scheduler().settings().max_wait_frames;
    std::uint64_t gathers_calm = 0;
    std::uint64_t calm_frames = 0;
    std::uint64_t gathers_burst = 0;
    std::uint64_t retraces_burst = 0;
    std::uint64_t burst_frames = 0;
    for (std::uint64_t f = 0; f < kFrames; ++f) {
        const FrameReport r = scene.frame(kBudgetMs);
        // Every frame runs its units in the scheduler's order: overdue ones first, oldest
        // first, then by effective priority (units skipped for not fitting do not change it).
        for (std::size_t i = 1; i < r.units.size(); ++i) {
            const UnitRecord& a = r.units[i - 1];
            const UnitRecord& b = r.units[i];
            const bool a_overdue = a.waited_frames >= max_wait;
            const bool b_overdue = b.waited_frames >= max_wait;
            ASSERT_TRUE(a_overdue || !b_overdue) << "frame " << f;
            if (a_overdue && b_overdue) {
                ASSERT_GE(a.waited_frames, b.waited_frames) << "frame " << f;
            } else if (!a_overdue && !b_overdue) {
                ASSERT_GE(a.effective_priority, b.effective_priority) << "frame " << f;
            }
        }
        const std::uint64_t gathers = r.kinds[index(WorkKind::IimGather)].units_done;
        const std::uint64_t phase = f % 500;
        if (phase >= 250 && phase < 260) {
            gathers_burst += gathers;
            retraces_burst += r.kinds[index(WorkKind::GroupRetrace)].units_done;
            ++burst_frames;
        } else if (phase >= 400) {
            gathers_calm += gathers;
            ++calm_frames;
        }
    }
    auto per_frame = [](std::uint64_t units, std::uint64_t frames) {
        return static_cast<double>(units) / static_cast<double>(frames);
    };
    // 4 ms of 0.2 ms retraces is ~19 a frame; forced AIM rebuilds take a few frames whole.
    EXPECT_GE(per_frame(retraces_burst, burst_frames), 12.0);
    EXPECT_GT(per_frame(gathers_calm, calm_frames), 1.5);  // two arrive a frame; calm keeps up
    EXPECT_LT(per_frame(gathers_burst, burst_frames), 0.5 * per_frame(gathers_calm, calm_frames));
}

TEST(FrameBudget, PausedLightingKeepsItsQueuesAndResumingDrainsTheBacklog) {
    ScriptedScene scene(2024);
    for (int f = 0; f < 200; ++f) {
        scene.frame(kBudgetMs);
    }
    const std::uint64_t done_before = scene.units_done();
    // Paused for 300 frames while the objects keep moving: nothing runs, the queues grow (but
    // merging by key bounds them by the number of distinct units).
    std::size_t pending = scene.scheduler().pending_total();
    for (int f = 0; f < 300; ++f) {
        const FrameReport r = scene.frame(0.0);
        ASSERT_TRUE(r.paused);
        ASSERT_EQ(r.units_done, 0U);
        ASSERT_EQ(r.used_ms, 0.0);
        ASSERT_GE(r.pending_after(), pending);
        pending = r.pending_after();
    }
    EXPECT_EQ(scene.units_done(), done_before);
    EXPECT_GT(pending, 500U);
    EXPECT_LE(pending, 256U + 300U + 8U + 40U + 500U + 1U);
    // Resume with the scene at rest: the backlog drains at the budget's pace, no frame over
    // budget by more than one unit's error (or a forced unit's cost).
    int frames = 0;
    while (scene.scheduler().pending_total() > 0 && frames < 1000) {
        const FrameReport r = scene.frame(kBudgetMs, false);
        ASSERT_FALSE(r.units.empty()) << "a frame with a backlog did nothing";
        const double bound = r.forced_units == 1
                                 ? std::max(r.forced_ms, r.units.back().error_bound_ms)
                                 : r.units.back().error_bound_ms;
        ASSERT_LE(r.overrun_ms(), bound + kClockSlackMs);
        ++frames;
    }
    EXPECT_EQ(scene.scheduler().pending_total(), 0U);
    EXPECT_EQ(scene.outstanding(), 0U);
    // Measured: the backlog drains in 50 frames of 4 ms.
    EXPECT_LE(frames, 80);
    RecordProperty("frames_to_drain", frames);
}

TEST(FrameBudget, CostModelAdaptsWhenTheSceneGetsHeavier) {
    // An 8 ms budget, so that the scene still fits once three times heavier (7.2 ms a frame on
    // average) and every kind keeps running, hence keeps being measured.
    constexpr double kBudget = 8.0;
    ScriptedScene scene(777);
    for (int f = 0; f < 1000; ++f) {
        scene.frame(kBudget);
    }
    const CostModel& model = scene.scheduler().cost_model();
    auto relative_error = [&](WorkKind kind) {
        return std::abs(model.predict(kind, 1.0) - scene.true_cost(kind)) / scene.true_cost(kind);
    };
    // Kinds that run every frame (probes, retraces, gathers) are predicted within
    // 20 % before the change.
    const WorkKind frequent[] = {WorkKind::PhotonProbe, WorkKind::GroupRetrace,
                                 WorkKind::IimGather};
    for (const WorkKind kind : frequent) {
        EXPECT_LE(relative_error(kind), 0.2) << name(kind);
    }
    // Every cost triples. Within 20 frames the frequent kinds are predicted within 20 % of
    // the new cost again, and stay there. The bound is set by the gathers, measured twice a
    // frame when both fit: with smoothing 0.1 the gap (2x the old cost, 67 % of the new) shrinks
    // by 0.9 a sample, under 20 % after 12 samples, plus margin for the +-30 % noise.
    scene.set_cost_scale(3.0);
    for (int f = 0; f < 500; ++f) {
        scene.frame(kBudget);
        if (f == 0) {
            // It did have to adapt: the first frame after the change is far off.
            EXPECT_GT(relative_error(WorkKind::GroupRetrace), 0.2);
        }
        if (f + 1 >= 20) {
            for (const WorkKind kind : frequent) {
                ASSERT_LE(relative_error(kind), 0.2)
                    << name(kind) << ", " << f + 1 << " frames after the change";
            }
        }
    }
    // The rarer kinds (a caustic slice every 2 frames, an AIM rebuild every 10) got there too.
    EXPECT_LE(relative_error(WorkKind::CausticSlice), 0.2);
    EXPECT_LE(relative_error(WorkKind::AimRebuild), 0.25);
}

TEST(FrameBudget, SameSeedSameFrames) {
    ScriptedScene a(31);
    ScriptedScene b(31);
    for (int f = 0; f < 500; ++f) {
        const FrameReport ra = a.frame(kBudgetMs);
        const FrameReport rb = b.frame(kBudgetMs);
        ASSERT_EQ(ra.used_ms, rb.used_ms) << "frame " << f;
        ASSERT_EQ(ra.units.size(), rb.units.size()) << "frame " << f;
        for (std::size_t i = 0; i < ra.units.size(); ++i) {
            ASSERT_EQ(ra.units[i].kind, rb.units[i].kind);
            ASSERT_EQ(ra.units[i].key, rb.units[i].key);
        }
    }
}

}  // namespace
