#pragma once

#include <vector>

#include <glm/glm.hpp>

/// The geometry of the hemi-plane: its frame and its pixel weights (docs/METHOD.md §6.2): the
/// plane z = 1 in the texel's tangent frame, [-a, a]^2, rasterised at `resolution` x `resolution`
/// pixels. A pixel centred at (x, y) sees the solid angle dA cos / r^2 with cos = 1 / r and r^2 =
/// x^2 + y^2 + 1, so integral L cos dw over the plane is sum L dA / r^4. Dividing by pi makes the
/// weights of the whole plane sum to the covered cosine-weighted fraction F(a)
/// (hemi_plane_coverage), so E = pi * sum(w L) / F(a).
namespace luxel::lighting {

/// The plane's axes for a texel normal: plane x = right, plane y = up, the plane at forward
/// distance 1. right x up = -forward, so front faces that face the texel wind
/// counter-clockwise on the plane (GL's convention).
struct HemiPlaneFrame {
    glm::vec3 right{1.0f, 0.0f, 0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    glm::vec3 forward{0.0f, 0.0f, 1.0f};
};

/// The frame the gatherer renders texel `normal` (unit) with: Duff et al. 2017, "Building an
/// orthonormal basis, revisited" (continuous except at the sign flip, no threshold branch).
[[nodiscard]] HemiPlaneFrame hemi_plane_frame(const glm::vec3& normal);

/// dA / (pi (x^2 + y^2 + 1)^2) for pixel (px, py), x = a * (-1 + (2 px + 1) / resolution):
/// the midpoint rule at the pixel centre, where the rasteriser samples the scene.
[[nodiscard]] double hemi_plane_pixel_weight(int px, int py, int resolution, double half_width);

/// Every pixel's weight, row by row (py = 0 first): what the reduction shader multiplies by.
[[nodiscard]] std::vector<float> hemi_plane_weights(int resolution, double half_width);

}  // namespace luxel::lighting
