#include "luxel/lighting/core/scheduler.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace luxel::lighting {

double FrameReport::predicted_ms() const {
    double sum = 0.0;
    for (const KindFrameReport& k : kinds) {
        sum += k.predicted_ms;
    }
    return sum;
}

std::size_t FrameReport::pending_after() const {
    std::size_t sum = 0;
    for (const KindFrameReport& k : kinds) {
        sum += k.pending_after;
    }
    return sum;
}

namespace {

/// Priorities beyond this are clamped: it keeps priority * weight + aging finite, so the sort
/// below always sees a strict weak order (a NaN or inf - inf would break it).
constexpr double kMaxPriority = 1e12;
constexpr double kMaxWeight = 1e6;

double clamp_finite(double value, double lo, double hi, double fallback) {
    return std::isfinite(value) ? std::clamp(value, lo, hi) : fallback;
}

/// Resets Scheduler::running_ however run() leaves (a callback may throw).
class RunningFlag {
  public:
    explicit RunningFlag(bool& flag) : flag_(flag) { flag_ = true; }
    ~RunningFlag() { flag_ = false; }
    RunningFlag(const RunningFlag&) = delete;
    RunningFlag& operator=(const RunningFlag&) = delete;

  private:
    bool& flag_;
};

}  // namespace

/// One queued unit as seen at the start of a frame.
struct Scheduler::Candidate {
    WorkKind kind;
    std::uint64_t key;
    std::uint64_t sequence;
    std::uint64_t waited;
    double effective;
    bool overdue;

    /// Overdue units first, oldest first; then by effective priority; ties by enqueue order.
    [[nodiscard]] bool goes_before(const Candidate& other) const {
        if (overdue != other.overdue) {
            return overdue;
        }
        if (overdue && waited != other.waited) {
            return waited > other.waited;
        }
        if (effective != other.effective) {
            return effective > other.effective;
        }
        return sequence < other.sequence;
    }
};

Scheduler::Scheduler(const Clock& clock, SchedulerSettings settings)
    : clock_(&clock), settings_(settings), cost_(settings.cost) {
    const SchedulerSettings defaults;
    for (std::size_t k = 0; k < kWorkKindCount; ++k) {
        settings_.weight[k] =
            clamp_finite(settings_.weight[k], 0.0, kMaxWeight, defaults.weight[k]);
        set_max_share(static_cast<WorkKind>(k), settings_.max_share[k]);
    }
    settings_.aging_per_frame =
        clamp_finite(settings_.aging_per_frame, 0.0, kMaxPriority, defaults.aging_per_frame);
    settings_.cost = cost_.settings();
}

void Scheduler::set_max_share(WorkKind kind, double share) {
    // Outside (0, 1) a share is no cap at all.
    settings_.max_share[index(kind)] =
        std::isfinite(share) && share > 0.0 && share < 1.0 ? share : 0.0;
}

void Scheduler::enqueue(WorkUnit unit) {
    if (!unit.run) {
        throw std::invalid_argument("Scheduler::enqueue: work unit without a callback");
    }
    if (index(unit.kind) >= kWorkKindCount) {
        throw std::invalid_argument("Scheduler::enqueue: work unit of no known kind");
    }
    const double priority = clamp_finite(unit.priority, -kMaxPriority, kMaxPriority, 0.0);
    // A size that is not a finite non-negative number predicts nothing and teaches nothing.
    const double size = std::isfinite(unit.size) && unit.size > 0.0 ? unit.size : 0.0;
    Queue& queue = queues_[index(unit.kind)];
    auto [it, inserted] = queue.try_emplace(unit.key);
    Entry& entry = it->second;
    if (inserted) {
        entry.priority = priority;
        entry.enqueued_frame = frame_;
        entry.sequence = next_sequence_++;
    } else {
        entry.priority = std::max(entry.priority, priority);
    }
    entry.size = size;
    entry.run = std::move(unit.run);
}

bool Scheduler::cancel(WorkKind kind, std::uint64_t key) {
    return index(kind) < kWorkKindCount && queues_[index(kind)].erase(key) > 0;
}

void Scheduler::clear() {
    for (Queue& queue : queues_) {
        queue.clear();
    }
}

bool Scheduler::queued(WorkKind kind, std::uint64_t key) const {
    return index(kind) < kWorkKindCount && queues_[index(kind)].contains(key);
}

std::size_t Scheduler::pending(WorkKind kind) const {
    return index(kind) < kWorkKindCount ? queues_[index(kind)].size() : 0;
}

std::size_t Scheduler::pending_total() const {
    std::size_t total = 0;
    for (const Queue& queue : queues_) {
        total += queue.size();
    }
    return total;
}

FrameReport Scheduler::paused_report() const {
    // Paused: nothing runs and nothing ages (frame_ does not advance).
    FrameReport report;
    report.frame = frame_;
    report.paused = true;
    report.budget_ms = 0.0;
    for (std::size_t k = 0; k < kWorkKindCount; ++k) {
        report.kinds[k].pending_after = queues_[k].size();
    }
    return report;
}

std::vector<Scheduler::Candidate> Scheduler::ordered_candidates() const {
    std::vector<Candidate> order;
    order.reserve(pending_total());
    for (std::size_t k = 0; k < kWorkKindCount; ++k) {
        for (const auto& [key, entry] : queues_[k]) {
            const std::uint64_t waited = frame_ - entry.enqueued_frame;
            const double effective = entry.priority * settings_.weight[k] +
                                     settings_.aging_per_frame * static_cast<double>(waited);
            order.push_back(Candidate{static_cast<WorkKind>(k), key, entry.sequence, waited,
                                      effective, waited >= settings_.max_wait_frames});
        }
    }
    std::sort(order.begin(), order.end(),
              [](const Candidate& a, const Candidate& b) { return a.goes_before(b); });
    return order;
}

FrameReport Scheduler::run(double budget_ms) {
    if (running_) {
        throw std::logic_error("Scheduler::run called from a work unit");
    }
    // NaN compares false: it pauses like 0. +inf runs everything queued.
    if (!(budget_ms > 0.0)) {
        return paused_report();
    }
    FrameReport report;
    report.frame = frame_;
    report.budget_ms = budget_ms;
    const RunningFlag running(running_);
    const Nanoseconds start = clock_->now();
    const double budget = report.budget_ms;
    const std::vector<Candidate> order = ordered_candidates();

    PerKind<double> kind_used{};
    // Two sweeps: the first keeps each kind within its share of the budget; if a unit was held
    // back only by its share, a second sweep lets the capped kinds use what the others left
    // (a share limits a kind while others have work, it does not waste budget).
    bool held_by_share = false;
    for (int sweep = 0; sweep < 2; ++sweep) {
        if (sweep == 1 && !held_by_share) {
            break;
        }
        for (std::size_t i = 0; i < order.size(); ++i) {
            const Candidate& c = order[i];
            const double remaining = budget - to_milliseconds(clock_->now() - start);
            // Nothing fits any more, not even a unit predicted to cost 0; but an overdue first
            // unit still runs (guaranteed progress even when a caller's sync used the budget).
            if (remaining < 0.0 && !(sweep == 0 && i == 0 && c.overdue)) {
                break;
            }
            const std::size_t k = index(c.kind);
            auto it = queues_[k].find(c.key);
            // Cancelled by an earlier callback, or cancelled and enqueued again (a new unit, which
            // runs from the next frame on).
            if (it == queues_[k].end() || it->second.sequence != c.sequence) {
                continue;
            }
            const double predicted = cost_.predict(c.kind, it->second.size);
            const double share = settings_.max_share[k];
            const bool within_share =
                sweep == 1 || share == 0.0 || kind_used[k] + predicted <= share * budget;
            const bool fits = predicted <= remaining && within_share;
            held_by_share = held_by_share || (predicted <= remaining && !within_share);
            // Minimum progress: only the first unit of the frame can be forced, so a forced unit
            // starts on an untouched budget and the frame overruns by at most its cost.
            const bool forced = !fits && sweep == 0 && i == 0 && c.overdue;
            if (!fits && !forced) {
                continue;
            }
            kind_used[k] += run_unit(c, predicted, forced, report);
        }
    }

    report.used_ms = to_milliseconds(clock_->now() - start);
    for (std::size_t k = 0; k < kWorkKindCount; ++k) {
        report.kinds[k].pending_after = queues_[k].size();
    }
    totals_.frames += 1;
    totals_.forced_units += report.forced_units;
    frame_ += 1;
    return report;
}

double Scheduler::run_unit(const Candidate& c, double predicted, bool forced, FrameReport& report) {
    const std::size_t k = index(c.kind);
    const auto it = queues_[k].find(c.key);
    std::function<void()> callback = std::move(it->second.run);
    const double size = it->second.size;
    const double bound = cost_.prediction_error(c.kind, size);
    queues_[k].erase(it);  // before the callback, which may enqueue the same key again

    const Nanoseconds t0 = clock_->now();
    callback();
    const double actual = to_milliseconds(clock_->now() - t0);
    cost_.record(c.kind, size, actual);

    KindFrameReport& kr = report.kinds[k];
    kr.units_done += 1;
    kr.ms += actual;
    kr.predicted_ms += predicted;
    report.units_done += 1;
    report.max_error_ms = std::max(report.max_error_ms, std::abs(actual - predicted));
    report.max_error_bound_ms = std::max(report.max_error_bound_ms, bound);
    if (forced) {
        report.forced_units += 1;
        report.forced_ms = actual;
    }
    if (settings_.record_units) {
        report.units.push_back(UnitRecord{c.kind, c.key, size, predicted, bound, actual, c.waited,
                                          c.effective, forced});
    }
    KindTotals& kt = totals_.kinds[k];
    kt.units_done += 1;
    kt.predicted_ms += predicted;
    kt.actual_ms += actual;
    return actual;
}

}  // namespace luxel::lighting
