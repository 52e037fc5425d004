#include "luxel/lighting/core/gather.hpp"

#include <cmath>
#include <numbers>

namespace luxel::lighting {

double hemi_plane_coverage(double half_width) {
    if (!(half_width > 0.0)) {
        return 0.0;
    }
    if (std::isinf(half_width)) {
        return 1.0;
    }
    const double s = half_width / std::sqrt(1.0 + half_width * half_width);
    return 4.0 / std::numbers::pi * s * std::atan(s);
}

}  // namespace luxel::lighting
