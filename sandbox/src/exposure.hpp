#pragma once

#include "luxel/runtime/image.hpp"

namespace luxel::sandbox {

/// Automatic exposure for display and PNG (the linear frame and EXR are never scaled): maps the
/// frame's log-average luminance to a grey key, as a camera's meter would. Smoothed over frames
/// so a light switching does not make the picture pump.
class AutoExposure {
  public:
    /// Meters `frame` (every 4th pixel in each direction is plenty) and returns the exposure.
    float update(const Image& frame) {
        const float target = metered_exposure(frame, 4);
        exposure_ = metered_ ? exposure_ + 0.2f * (target - exposure_) : target;
        metered_ = true;
        return exposure_;
    }
    [[nodiscard]] float exposure() const { return exposure_; }

  private:
    float exposure_ = 1.0f;
    bool metered_ = false;
};

}  // namespace luxel::sandbox
