// Pixel area: the splat divides each photon's power by the world-space area of its pixel, so
// the same caustic seen from 2 m and 4 m (a quarter of the pixels, four times the photons per
// pixel) has the same irradiance at its centre, and that is the photons' power / disc area.
// On a plane seen at 60 degrees, accounting for the surface's orientation keeps the answer;
// the camera-facing area alone overestimates it by 1 / cos(60) = 2.

#include <cmath>

#include <gtest/gtest.h>

#include "caustic_test_support.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;

constexpr double kPi = 3.14159265358979323846;
constexpr float kDiscRadius = 0.1f;
constexpr float kPower = 1.0f;                                        // W per channel
const double kExpected = kPower / (kPi * kDiscRadius * kDiscRadius);  // W/m^2

class CausticPixelArea : public ::testing::Test {
  protected:
    void SetUp() override { context_ = test::make_caustic_gl_context(); }
    void TearDown() override { context_.reset(); }
    std::unique_ptr<GlContext> context_;
};

/// Mean filtered irradiance (green) over the pixels whose surface lies within `radius` of
/// the origin, the caustic's centre.
double centre_irradiance(const CausticPassSettings& settings, const glm::vec3& eye, glm::ivec2 size,
                         float radius = 0.03f) {
    const test::RectScene scene(test::look_at(eye, {0, 0, 0}, size),
                                {{{0, 0, 0}, {5, 0, 0}, {0, 5, 0}}});
    const std::vector<CausticPhoton> photons =
        test::disc_photons({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, kDiscRadius, 40'000, glm::vec3(kPower));
    CausticPass pass(settings, size);
    pass.upload(photons);
    pass.render(scene.camera(), scene.depth_texture().id());
    const std::vector<glm::vec4> image = test::read_rgba(pass.irradiance_texture(), size);
    double sum = 0.0;
    int count = 0;
    for (int y = 0; y < size.y; ++y) {
        for (int x = 0; x < size.x; ++x) {
            const auto p = scene.hit(x, y);
            if (p && glm::length(*p) < radius) {
                sum += static_cast<double>(image[static_cast<std::size_t>(y * size.x + x)].g);
                ++count;
            }
        }
    }
    EXPECT_GT(count, 10);
    return count > 0 ? sum / count : 0.0;
}

TEST_F(CausticPixelArea, SameIrradianceFromTwoDistances) {
    const glm::ivec2 size(384, 384);
    for (const CausticKernel kernel : {CausticKernel::Larsen, CausticKernel::WorldCone}) {
        CausticPassSettings settings;
        settings.kernel = kernel;
        settings.world_radius = 0.02f;
        const double near = centre_irradiance(settings, {0, 0, 2}, size);
        const double far = centre_irradiance(settings, {0, 0, 4}, size);
        const double between = std::abs(near - far) / far;
        EXPECT_LT(between, 0.05) << kernel_name(kernel) << ": " << near << " vs " << far;
        EXPECT_LT(std::abs(near - kExpected) / kExpected, 0.05) << kernel_name(kernel);
        EXPECT_LT(std::abs(far - kExpected) / kExpected, 0.05) << kernel_name(kernel);
        std::printf(
            "pixel area %s: E(2 m) = %.3f, E(4 m) = %.3f, analytic %.3f W/m^2, "
            "2 m vs 4 m %.3g\n",
            kernel_name(kernel), near, far, kExpected, between);
        RecordProperty(std::string("relative_difference_2m_4m_") + kernel_name(kernel),
                       std::to_string(between));
    }
}

TEST_F(CausticPixelArea, ObliqueSurfaceNeedsTheOrientation) {
    const glm::ivec2 size(384, 384);
    // 3 m away, 60 degrees from the plane's normal.
    const glm::vec3 eye(0.0f, -3.0f * std::sin(1.0471976f), 3.0f * std::cos(1.0471976f));
    CausticPassSettings settings;
    const double oriented = centre_irradiance(settings, eye, size);
    settings.account_for_orientation = false;
    const double facing = centre_irradiance(settings, eye, size);
    std::printf("oblique 60 deg: E = %.3f with orientation, %.3f without, analytic %.3f\n",
                oriented, facing, kExpected);
    EXPECT_LT(std::abs(oriented - kExpected) / kExpected, 0.05);
    EXPECT_NEAR(facing / kExpected, 2.0, 0.1);
}

}  // namespace
