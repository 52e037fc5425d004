#pragma once

#include <chrono>
#include <cstdint>

namespace luxel {

using Nanoseconds = std::chrono::nanoseconds;

/// A source of monotonic time. Everything that budgets or measures work takes a Clock& so that
/// tests inject a ManualClock and never depend on how fast the machine is.
class Clock {
  public:
    virtual ~Clock() = default;
    [[nodiscard]] virtual Nanoseconds now() const = 0;
};

/// std::chrono::steady_clock.
class SteadyClock final : public Clock {
  public:
    [[nodiscard]] Nanoseconds now() const override;
    /// A process-wide instance for callers that do not inject one.
    static const SteadyClock& instance();
};

/// A clock that moves only when told to: the injected clock of frame-budget tests.
class ManualClock final : public Clock {
  public:
    explicit ManualClock(Nanoseconds start = Nanoseconds{0}) : now_(start) {}
    [[nodiscard]] Nanoseconds now() const override { return now_; }
    void advance(Nanoseconds by) { now_ += by; }
    void set(Nanoseconds to) { now_ = to; }

  private:
    Nanoseconds now_;
};

[[nodiscard]] inline double to_milliseconds(Nanoseconds d) {
    return std::chrono::duration<double, std::milli>(d).count();
}
[[nodiscard]] inline double to_seconds(Nanoseconds d) {
    return std::chrono::duration<double>(d).count();
}
[[nodiscard]] inline Nanoseconds from_milliseconds(double ms) {
    return std::chrono::duration_cast<Nanoseconds>(std::chrono::duration<double, std::milli>(ms));
}

/// Measures elapsed time on a Clock since construction or the last restart().
class Stopwatch {
  public:
    explicit Stopwatch(const Clock& clock = SteadyClock::instance())
        : clock_(&clock), start_(clock.now()) {}
    void restart() { start_ = clock_->now(); }
    [[nodiscard]] Nanoseconds elapsed() const { return clock_->now() - start_; }
    [[nodiscard]] double elapsed_ms() const { return to_milliseconds(elapsed()); }

  private:
    const Clock* clock_;
    Nanoseconds start_;
};

/// One tick of a FrameClock.
struct FrameTime {
    std::uint64_t index = 0;     ///< 0 for the first frame
    double delta_seconds = 0.0;  ///< time since the previous tick (0 on the first)
    double total_seconds = 0.0;  ///< time since the first tick
};

/// Frame pacing: call tick() once at the start of each frame.
class FrameClock {
  public:
    explicit FrameClock(const Clock& clock = SteadyClock::instance()) : clock_(&clock) {}
    FrameTime tick();
    [[nodiscard]] const FrameTime& current() const { return current_; }

  private:
    const Clock* clock_;
    bool started_ = false;
    Nanoseconds first_{0};
    Nanoseconds previous_{0};
    FrameTime current_{};
};

}  // namespace luxel
