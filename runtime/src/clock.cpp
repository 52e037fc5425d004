#include "luxel/runtime/clock.hpp"

namespace luxel {

Nanoseconds SteadyClock::now() const {
    return std::chrono::duration_cast<Nanoseconds>(
        std::chrono::steady_clock::now().time_since_epoch());
}

const SteadyClock& SteadyClock::instance() {
    static const SteadyClock clock;
    return clock;
}

FrameTime FrameClock::tick() {
    const Nanoseconds now = clock_->now();
    if (!started_) {
        started_ = true;
        first_ = now;
        previous_ = now;
        current_ = FrameTime{};
        return current_;
    }
    current_.index += 1;
    current_.delta_seconds = to_seconds(now - previous_);
    current_.total_seconds = to_seconds(now - first_);
    previous_ = now;
    return current_;
}

}  // namespace luxel
