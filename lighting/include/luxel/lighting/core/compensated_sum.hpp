#pragma once

#include <cmath>

namespace luxel::lighting {

/// A running sum that does not drift: double precision with Neumaier's compensation, so a
/// million additions and removals of photon powers of very different sizes end within a few
/// ulps of a fresh recount.
class CompensatedSum {
  public:
    void add(double value) {
        const double total = sum_ + value;
        // Keep the low-order bits the larger operand would swallow.
        compensation_ +=
            std::abs(sum_) >= std::abs(value) ? (sum_ - total) + value : (value - total) + sum_;
        sum_ = total;
    }
    void subtract(double value) { add(-value); }
    [[nodiscard]] double value() const { return sum_ + compensation_; }
    void reset() {
        sum_ = 0.0;
        compensation_ = 0.0;
    }

  private:
    double sum_ = 0.0;
    double compensation_ = 0.0;
};

}  // namespace luxel::lighting
