#pragma once

// A clock for tests that bound work by time without the wall clock.

#include <chrono>

#include "luxel/runtime/clock.hpp"

namespace luxel::testing {

/// A clock that advances a millisecond each time it is read: time passes with the work done,
/// the same on every machine.
class TickingClock final : public Clock {
  public:
    [[nodiscard]] Nanoseconds now() const override {
        now_ += std::chrono::milliseconds(1);
        return now_;
    }

  private:
    mutable Nanoseconds now_{0};
};

}  // namespace luxel::testing
