// The hemi-plane's coverage F(a) and the pixel weights the reduction uses: the weights of the
// whole plane, summed at the resolution the gatherer renders, must equal F(a).

#include <cmath>
#include <numbers>
#include <numeric>

#include <gtest/gtest.h>

#include "luxel/lighting/core/gather.hpp"
#include "luxel/lighting/gpu/hemi_plane_gatherer.hpp"
#include "luxel/lighting/gpu/hemi_plane_geometry.hpp"

namespace {

using namespace luxel::lighting;

/// Exact integral of dx dy / (pi (1 + x^2 + y^2)^2) over [-a, a]^2 from the antiderivative
/// G(x, y) = x / (2 sqrt(1+x^2)) atan(y / sqrt(1+x^2)) + (x <-> y): a check of F(a) that shares
/// no formula with hemi_plane_coverage.
double exact_plane_fraction(double a) {
    const auto g = [](double x, double y) {
        const double sx = std::sqrt(1.0 + x * x);
        const double sy = std::sqrt(1.0 + y * y);
        return x / (2.0 * sx) * std::atan(y / sx) + y / (2.0 * sy) * std::atan(x / sy);
    };
    return (g(a, a) - g(-a, a) - g(a, -a) + g(-a, -a)) / std::numbers::pi;
}

TEST(HemiPlaneCoverage, MatchesTheSeedsFigures) {
    EXPECT_NEAR(hemi_plane_coverage(1.0), 0.554, 0.001);
    EXPECT_NEAR(hemi_plane_coverage(2.0), 0.831, 0.001);
    EXPECT_NEAR(hemi_plane_coverage(1.0), exact_plane_fraction(1.0), 1e-9);
    EXPECT_NEAR(hemi_plane_coverage(2.0), exact_plane_fraction(2.0), 1e-9);
}

TEST(HemiPlaneWeights, SumOverThePlaneIsTheCoverageAtTheDefaultResolution) {
    const HemiPlaneSettings defaults;
    for (const double a : {1.0, 2.0, static_cast<double>(defaults.half_width)}) {
        const std::vector<float> w = hemi_plane_weights(defaults.resolution, a);
        ASSERT_EQ(w.size(), static_cast<std::size_t>(defaults.resolution * defaults.resolution));
        const double sum = std::accumulate(w.begin(), w.end(), 0.0);
        EXPECT_NEAR(sum, hemi_plane_coverage(a), 0.001) << "a = " << a;
        EXPECT_NEAR(sum, exact_plane_fraction(a), 0.001) << "a = " << a;
    }
}

TEST(HemiPlaneWeights, AreSymmetricAndLargestAtTheCentre) {
    const int n = 64;
    const std::vector<float> w = hemi_plane_weights(n, 2.0);
    const auto at = [&](int x, int y) { return w[static_cast<std::size_t>(y * n + x)]; };
    for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
            ASSERT_GT(at(x, y), 0.0f);
            ASSERT_FLOAT_EQ(at(x, y), at(n - 1 - x, y));
            ASSERT_FLOAT_EQ(at(x, y), at(y, x));
        }
    }
    // Pixel (31, 31) is centred at (-a/64, -a/64): r^2 = 1 + 2 (1/32)^2.
    const double pixel = 4.0 / 64.0;
    const double r2 = 1.0 + 2.0 * (2.0 / 64.0) * (2.0 / 64.0);
    EXPECT_NEAR(at(31, 31), pixel * pixel / (std::numbers::pi * r2 * r2), 1e-9);
    EXPECT_LT(at(0, 0), at(31, 31) / 20.0f);
}

TEST(HemiPlaneFrame, IsOrthonormalWithFrontFacesCounterClockwise) {
    for (const glm::vec3 n :
         {glm::vec3(0, 0, 1), glm::vec3(0, 0, -1), glm::vec3(0, 1, 0), glm::vec3(-1, 0, 0),
          glm::normalize(glm::vec3(1, -2, 0.5f)), glm::normalize(glm::vec3(-0.1f, 0.2f, -3.0f))}) {
        const HemiPlaneFrame f = hemi_plane_frame(n);
        EXPECT_NEAR(glm::length(f.right), 1.0f, 1e-6f);
        EXPECT_NEAR(glm::length(f.up), 1.0f, 1e-6f);
        EXPECT_NEAR(glm::dot(f.right, f.up), 0.0f, 1e-6f);
        EXPECT_NEAR(glm::dot(f.right, n), 0.0f, 1e-6f);
        EXPECT_EQ(f.forward, n);
        // right x up = -forward: a triangle facing the texel projects counter-clockwise.
        const glm::vec3 c = glm::cross(f.right, f.up);
        EXPECT_NEAR(glm::dot(c, n), -1.0f, 1e-5f);
    }
}

TEST(HemiPlaneWeights, InvalidInputsGiveNothing) {
    EXPECT_TRUE(hemi_plane_weights(0, 2.0).empty());
    EXPECT_EQ(hemi_plane_pixel_weight(0, 0, 64, 0.0), 0.0);
    EXPECT_EQ(hemi_plane_pixel_weight(0, 0, -1, 2.0), 0.0);
}

}  // namespace
