#pragma once

#include <algorithm>
#include <cmath>

#include "luxel/runtime/image.hpp"

namespace luxel::sandbox {

/// Automatic exposure for display and PNG (the linear frame and EXR are never scaled): maps the
/// frame's log-average luminance to a grey key, as a camera's meter would. Smoothed over frames
/// so a light switching does not make the picture pump.
class AutoExposure {
    /// The grey the log-average maps to: a little under the photographic 0.18, since these
    /// interiors are mostly pale walls.
    static constexpr double kKey = 0.12;

  public:
    /// Meters `frame` (every 4th pixel in each direction is plenty) and returns the exposure.
    float update(const Image& frame) {
        double log_sum = 0.0;
        std::size_t count = 0;
        for (int y = 0; y < frame.height; y += 4) {
            for (int x = 0; x < frame.width; x += 4) {
                const glm::vec4 p = frame.pixel(x, y);
                const double luminance = 0.2126 * p.r + 0.7152 * p.g + 0.0722 * p.b;
                // Black pixels are the sky or the void beyond an open level, not a dark
                // surface: metering them would expose the lit part to white.
                if (std::isfinite(luminance) && luminance > 1e-6) {
                    log_sum += std::log(1e-4 + luminance);
                    ++count;
                }
            }
        }
        if (count == 0) {
            return exposure_;
        }
        const double average = std::exp(log_sum / static_cast<double>(count));
        const auto target = static_cast<float>(std::clamp(kKey / average, 1e-3, 1e4));
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
