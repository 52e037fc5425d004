#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <unordered_map>
#include <vector>

#include "luxel/lighting/core/cost_model.hpp"
#include "luxel/runtime/clock.hpp"

namespace luxel::lighting {

/// One piece of lighting work. `key` names the unit within its kind (surface id, group id,
/// texel batch...): enqueuing a (kind, key) that is already queued merges into the queued one.
struct WorkUnit {
    WorkKind kind = WorkKind::PhotonProbe;
    std::uint64_t key = 0;
    /// Larger runs first within a kind; scaled by the kind's weight across kinds. Typical
    /// values are 0..1 (e.g. delta_f / area, delta_i normalised), but any finite value works.
    double priority = 0.0;
    std::function<void()> run;
    /// Scales the predicted cost (texels in a gather batch, photons in a slice...).
    double size = 1.0;
};

struct SchedulerSettings {
    /// Weight of each kind's priorities, in docs/METHOD.md §1.2's order: photon probes,
    /// retraces, caustic slices, AIM rebuilds, IIM gathers; then irradiance probe passes,
    /// between the AIM they read and the IIM gathers. Photons come first because everything
    /// downstream is computed from them.
    PerKind<double> weight = {6.0, 5.0, 4.0, 3.0, 2.0, 2.5};
    /// Added to a unit's effective priority for each frame it has waited, so that low-priority
    /// work rises over time instead of waiting behind a stream of fresh high-priority units.
    double aging_per_frame = 0.1;
    /// Guaranteed minimum progress: a unit that has waited this many frames is overdue. Overdue
    /// units go before all others, oldest first, and every frame with a positive budget starts
    /// the oldest one even if it is predicted not to fit (a "forced" unit; at most one a frame).
    std::uint32_t max_wait_frames = 30;
    /// Optional split of the budget: the fraction of each frame's budget a kind may use while
    /// other kinds have work that fits; what they leave, a capped kind may use after all.
    /// 0 (the default) or >= 1 means no cap: all kinds share one pool. A forced unit ignores it.
    PerKind<double> max_share = {};
    CostModelSettings cost;
    /// Fill FrameReport::units with one record per unit run (tests, luxel-bench, debugging).
    bool record_units = false;
};

/// One unit as run by Scheduler::run (when SchedulerSettings::record_units).
struct UnitRecord {
    WorkKind kind = WorkKind::PhotonProbe;
    std::uint64_t key = 0;
    double size = 0.0;
    double predicted_ms = 0.0;
    double error_bound_ms = 0.0;  ///< CostModel::prediction_error when it was started
    double actual_ms = 0.0;
    std::uint64_t waited_frames = 0;  ///< active frames between its enqueue and this one
    double effective_priority = 0.0;  ///< priority * weight + aging, as sorted this frame
    bool forced = false;
};

/// Per kind, one frame.
struct KindFrameReport {
    std::uint32_t units_done = 0;
    double ms = 0.0;            ///< measured time of this kind's units (the actual cost)
    double predicted_ms = 0.0;  ///< sum of the predictions of the units that ran
    std::size_t pending_after = 0;
};

/// What one Scheduler::run did: what the HUD and luxel-bench show.
struct FrameReport {
    std::uint64_t frame = 0;  ///< active (budget > 0) frames before this one
    double budget_ms = 0.0;
    double used_ms = 0.0;  ///< clock time of the whole run(), scheduling included
    bool paused = false;   ///< budget <= 0: nothing ran
    PerKind<KindFrameReport> kinds{};
    std::uint32_t units_done = 0;
    std::uint32_t forced_units = 0;   ///< 0 or 1
    double forced_ms = 0.0;           ///< measured time of the forced unit
    double max_error_ms = 0.0;        ///< largest |actual - predicted| of a unit this frame
    double max_error_bound_ms = 0.0;  ///< largest prediction_error of a unit run this frame
    std::vector<UnitRecord> units;    ///< only with SchedulerSettings::record_units

    [[nodiscard]] double overrun_ms() const {
        return used_ms > budget_ms ? used_ms - budget_ms : 0.0;
    }
    [[nodiscard]] double predicted_ms() const;
    [[nodiscard]] std::size_t pending_after() const;
};

/// Lifetime counters, per kind.
struct KindTotals {
    std::uint64_t units_done = 0;
    double predicted_ms = 0.0;
    double actual_ms = 0.0;
};
struct SchedulerTotals {
    std::uint64_t frames = 0;  ///< active frames
    std::uint64_t forced_units = 0;
    PerKind<KindTotals> kinds{};
};

/// Queues of lighting work units, run in priority order within a frame budget (docs/METHOD.md
/// §1.2 step 3, §1.3). Every unit's duration is measured on the injected clock and teaches the
/// CostModel.
///
/// Within run(budget_ms), units are taken in this order: overdue units (waited >=
/// max_wait_frames), oldest first; then by effective priority = priority * weight[kind] +
/// aging_per_frame * frames waited; ties by enqueue order (so a run is deterministic). A unit
/// starts only if its predicted cost fits in what is left of the budget (and in its kind's
/// share, if any); units that do not fit are skipped for smaller ones behind them. Hence only
/// the last unit of a frame can overrun the budget, by what it cost beyond its prediction
/// (within CostModel::prediction_error once the model has measurements), except:
///
/// - Minimum progress: if the first unit in that order is overdue and predicted not to fit,
///   it runs anyway (forced), before anything else. At most one unit a frame is forced, so a
///   frame overruns by at most that unit's cost (or, if it turned out cheap, as above). With
///   k overdue units, all are done within k
///   frames; a unit is therefore done within max_wait_frames + (overdue units ahead of it) + 1
///   active frames, provided the work arriving does not exceed what the budget can do.
///
/// - Budget 0 (or negative, or NaN) pauses lighting: no unit runs, not even an overdue one;
///   the queues are kept and do not age (paused frames are not counted as waited). A later
///   positive budget resumes, and the backlog drains in the usual order.
///
/// A unit's callback may enqueue or cancel units (those it enqueues run from the next frame
/// on); it must not call run(). If a callback throws, that unit is dropped, the exception
/// propagates, and the scheduler stays usable.
class Scheduler {
  public:
    Scheduler(const Clock& clock, SchedulerSettings settings = {});

    /// Queues a unit. If (kind, key) is already queued, keeps the higher priority, the new
    /// callback and size, and the original enqueue frame (the wait keeps counting, so a unit
    /// that is re-enqueued every frame by a moving object still ages). An empty callback throws
    /// std::invalid_argument.
    void enqueue(WorkUnit unit);
    /// Removes a queued unit; false if it was not queued.
    bool cancel(WorkKind kind, std::uint64_t key);
    /// Removes every queued unit of every kind.
    void clear();
    /// Changes a kind's SchedulerSettings::max_share from the next run() on (outside (0, 1): no
    /// cap), e.g. a larger share for work that is catching up after a change.
    void set_max_share(WorkKind kind, double share);
    [[nodiscard]] double max_share(WorkKind kind) const { return settings_.max_share[index(kind)]; }

    [[nodiscard]] bool queued(WorkKind kind, std::uint64_t key) const;
    [[nodiscard]] std::size_t pending(WorkKind kind) const;
    [[nodiscard]] std::size_t pending_total() const;

    /// Runs units until the budget (ms) is spent; see the class comment for the order and
    /// the guarantees.
    FrameReport run(double budget_ms);

    [[nodiscard]] const CostModel& cost_model() const { return cost_; }
    [[nodiscard]] CostModel& cost_model() { return cost_; }
    [[nodiscard]] const SchedulerSettings& settings() const { return settings_; }
    [[nodiscard]] const SchedulerTotals& totals() const { return totals_; }
    /// Active frames run so far (the frame index the next active run() will have).
    [[nodiscard]] std::uint64_t frame() const { return frame_; }

  private:
    struct Candidate;
    [[nodiscard]] FrameReport paused_report() const;
    /// Every queued unit in the order run() takes them (see the class comment).
    [[nodiscard]] std::vector<Candidate> ordered_candidates() const;
    /// Runs candidate `c` (queued and chosen), learns its cost and records it in `report`;
    /// returns what it took (ms).
    double run_unit(const Candidate& c, double predicted, bool forced, FrameReport& report);

    struct Entry {
        double priority = 0.0;
        double size = 1.0;
        std::function<void()> run;
        std::uint64_t enqueued_frame = 0;
        std::uint64_t sequence = 0;  ///< enqueue order, the deterministic tie-break
    };
    using Queue = std::unordered_map<std::uint64_t, Entry>;

    const Clock* clock_;
    SchedulerSettings settings_;
    CostModel cost_;
    PerKind<Queue> queues_;
    std::uint64_t frame_ = 0;
    std::uint64_t next_sequence_ = 0;
    bool running_ = false;
    SchedulerTotals totals_;
};

}  // namespace luxel::lighting
