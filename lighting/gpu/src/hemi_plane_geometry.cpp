#include "luxel/lighting/gpu/hemi_plane_geometry.hpp"

#include <cmath>
#include <numbers>

namespace luxel::lighting {

HemiPlaneFrame hemi_plane_frame(const glm::vec3& normal) {
    const float sign = std::copysign(1.0f, normal.z);
    const float a = -1.0f / (sign + normal.z);
    const float b = normal.x * normal.y * a;
    HemiPlaneFrame frame;
    frame.forward = normal;
    frame.right = {1.0f + sign * normal.x * normal.x * a, sign * b, -sign * normal.x};
    frame.up = glm::cross(frame.right, normal);
    return frame;
}

double hemi_plane_pixel_weight(int px, int py, int resolution, double half_width) {
    if (resolution <= 0 || !(half_width > 0.0)) {
        return 0.0;
    }
    const double n = static_cast<double>(resolution);
    const double pixel = 2.0 * half_width / n;
    const double x = half_width * (-1.0 + (2.0 * static_cast<double>(px) + 1.0) / n);
    const double y = half_width * (-1.0 + (2.0 * static_cast<double>(py) + 1.0) / n);
    const double r2 = x * x + y * y + 1.0;
    return pixel * pixel / (std::numbers::pi * r2 * r2);
}

std::vector<float> hemi_plane_weights(int resolution, double half_width) {
    std::vector<float> weights;
    if (resolution <= 0) {
        return weights;
    }
    weights.reserve(static_cast<std::size_t>(resolution) * static_cast<std::size_t>(resolution));
    for (int py = 0; py < resolution; ++py) {
        for (int px = 0; px < resolution; ++px) {
            weights.push_back(
                static_cast<float>(hemi_plane_pixel_weight(px, py, resolution, half_width)));
        }
    }
    return weights;
}

}  // namespace luxel::lighting
