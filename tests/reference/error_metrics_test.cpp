// docs/METHOD.md §10.2's relRMSE on hand-made arrays and images.

#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "luxel/lighting/reference/error_metrics.hpp"
#include "luxel/runtime/error.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting::reference;

TEST(ErrorMetrics, RelativeRmseWeighsTexelsByArea) {
    const std::vector<double> reference{1.0, 2.0, 4.0};
    const std::vector<double> estimate{1.5, 2.0, 3.0};
    const std::vector<double> areas{2.0, 1.0, 0.5};
    // sqrt((2 * 0.25 + 0 + 0.5 * 1) / (2 * 1 + 1 * 4 + 0.5 * 16)) = sqrt(1 / 14)
    EXPECT_NEAR(relative_rmse(estimate, reference, areas), std::sqrt(1.0 / 14.0), 1e-15);
    EXPECT_EQ(relative_rmse(reference, reference, areas), 0.0);
    // Scale invariant: the same relative error at any light level (1 uW or 1 MW).
    std::vector<double> small_reference;
    std::vector<double> small_estimate;
    for (std::size_t i = 0; i < reference.size(); ++i) {
        small_reference.push_back(1e-6 * reference[i]);
        small_estimate.push_back(1e-6 * estimate[i]);
    }
    EXPECT_NEAR(relative_rmse(small_estimate, small_reference, areas), std::sqrt(1.0 / 14.0),
                1e-12);
}

TEST(ErrorMetrics, RgbValuesSumTheirChannels) {
    const std::vector<glm::dvec3> reference{{1.0, 0.0, 0.0}, {0.0, 2.0, 0.0}};
    const std::vector<glm::dvec3> estimate{{1.0, 1.0, 0.0}, {0.0, 2.0, 0.0}};
    const std::vector<double> areas{1.0, 1.0};
    EXPECT_NEAR(relative_rmse(estimate, reference, areas), std::sqrt(1.0 / 5.0), 1e-15);
}

TEST(ErrorMetrics, DivisionsAreGuarded) {
    const std::vector<double> zero{0.0, 0.0};
    const std::vector<double> one{1.0, 0.0};
    const std::vector<double> areas{1.0, 1.0};
    EXPECT_EQ(relative_rmse(zero, zero, areas), 0.0);  // nothing lit, nothing to light
    EXPECT_EQ(relative_rmse(one, zero, areas), std::numeric_limits<double>::infinity());
    const std::vector<double> broken{std::nan(""), 0.0};
    EXPECT_EQ(relative_rmse(broken, one, areas), std::numeric_limits<double>::infinity());
    EXPECT_EQ(relative_rmse(one, one, std::vector<double>{0.0, 0.0}), 0.0);
    EXPECT_THROW(static_cast<void>(relative_rmse(one, one, std::vector<double>{1.0})), Error);
    EXPECT_THROW(static_cast<void>(relative_rmse(one, one, std::vector<double>{-1.0, 1.0})), Error);
}

TEST(ErrorMetrics, ImageRelativeRmseIgnoresAlpha) {
    Image reference(2, 1, glm::vec4(1.0f, 1.0f, 1.0f, 1.0f));
    Image estimate(2, 1, glm::vec4(1.0f, 1.0f, 1.0f, 0.0f));
    EXPECT_EQ(image_relative_rmse(estimate, reference), 0.0);
    estimate.set_pixel(1, 0, glm::vec4(2.0f, 1.0f, 1.0f, 1.0f));
    EXPECT_NEAR(image_relative_rmse(estimate, reference), std::sqrt(1.0 / 6.0), 1e-7);
    EXPECT_THROW(static_cast<void>(image_relative_rmse(Image(3, 1), reference)), Error);
}

}  // namespace
