// The local error measures (worst region, 99th-percentile texel) on hand-made light maps: a dark
// patch that a global relRMSE dilutes stands out, and the two agree with relRMSE where they must.

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "luxel/lighting/reference/error_metrics.hpp"
#include "luxel/lighting/reference/local_error.hpp"
#include "luxel/runtime/error.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting::reference;

/// `regions` regions of `per_region` texels each, reference 1 (grey) everywhere.
struct Maps {
    std::vector<glm::dvec3> estimate;
    std::vector<glm::dvec3> reference;
    std::vector<double> area;
    std::vector<std::uint32_t> region;

    Maps(std::uint32_t regions, std::uint32_t per_region) {
        for (std::uint32_t r = 0; r < regions; ++r) {
            for (std::uint32_t t = 0; t < per_region; ++t) {
                estimate.emplace_back(1.0);
                reference.emplace_back(1.0);
                area.push_back(0.01);
                region.push_back(r);
            }
        }
    }
};

TEST(LocalError, ADarkPatchIsFoundWhereTheGlobalErrorDilutesIt) {
    // 64 regions of 16 texels; one region (a footprint) is black in the estimate.
    Maps maps(64, 16);
    for (std::size_t i = 0; i < maps.region.size(); ++i) {
        if (maps.region[i] == 37) {
            maps.estimate[i] = glm::dvec3(0.0);
        }
    }
    const double global = relative_rmse(maps.estimate, maps.reference, maps.area);
    EXPECT_NEAR(global, std::sqrt(1.0 / 64.0), 1e-12);  // 12.5%: looks like noise
    const LocalError local = local_error(maps.estimate, maps.reference, maps.area, maps.region);
    EXPECT_NEAR(local.worst_region, 1.0, 1e-12);  // the whole reference value is missing there
    EXPECT_EQ(local.worst_region_id, 37u);
    EXPECT_EQ(local.regions, 64u);
    // 1/64 of the area is black: more than 1%, so the 99th percentile is the black texels'.
    EXPECT_NEAR(local.texel_p99, 1.0, 1e-12);
}

TEST(LocalError, AUniformRelativeErrorIsTheSameEverywhere) {
    Maps maps(10, 20);
    for (glm::dvec3& value : maps.estimate) {
        value *= 1.1;
    }
    const LocalError local = local_error(maps.estimate, maps.reference, maps.area, maps.region);
    EXPECT_NEAR(local.worst_region, 0.1, 1e-12);
    EXPECT_NEAR(local.texel_p99, 0.1, 1e-12);
    EXPECT_NEAR(relative_rmse(maps.estimate, maps.reference, maps.area), 0.1, 1e-12);
}

TEST(LocalError, TheGlobalErrorIsTheAreaWeightedRmsOfTheRegionErrors) {
    // Random maps: relRMSE^2 = sum_r (W_r / W) e_r^2, whatever the values; checked by making
    // every region but one exact, for each region in turn.
    std::mt19937 random(7);
    std::uniform_real_distribution<double> value(0.1, 3.0);
    Maps maps(6, 16);
    for (std::size_t i = 0; i < maps.estimate.size(); ++i) {
        maps.reference[i] = glm::dvec3(value(random), value(random), value(random));
        maps.estimate[i] = glm::dvec3(value(random), value(random), value(random));
        maps.area[i] = value(random);
    }
    double sum = 0.0;
    double total_area = 0.0;
    for (double a : maps.area) {
        total_area += a;
    }
    for (std::uint32_t r = 0; r < 6; ++r) {
        std::vector<glm::dvec3> one = maps.reference;
        double region_area = 0.0;
        for (std::size_t i = 0; i < one.size(); ++i) {
            if (maps.region[i] == r) {
                one[i] = maps.estimate[i];
                region_area += maps.area[i];
            }
        }
        const LocalError local = local_error(one, maps.reference, maps.area, maps.region);
        EXPECT_EQ(local.worst_region_id, r);
        sum += region_area / total_area * local.worst_region * local.worst_region;
    }
    const double global = relative_rmse(maps.estimate, maps.reference, maps.area);
    EXPECT_NEAR(std::sqrt(sum), global, 1e-12 * global);
}

TEST(LocalError, RegionsWithTooFewTexelsAreLeftOutButTheirTexelsCount) {
    Maps maps(4, 16);
    // A 3-texel sliver (region 4), all wrong.
    for (int t = 0; t < 3; ++t) {
        maps.estimate.emplace_back(0.0);
        maps.reference.emplace_back(1.0);
        maps.area.push_back(0.01);
        maps.region.push_back(4);
    }
    const LocalError local = local_error(maps.estimate, maps.reference, maps.area, maps.region);
    EXPECT_EQ(local.regions, 4u);
    EXPECT_EQ(local.worst_region, 0.0);
    EXPECT_NEAR(local.texel_p99, 1.0, 1e-12);  // 3 of 67 texels: over 1% of the area
    const LocalError counted =
        local_error(maps.estimate, maps.reference, maps.area, maps.region, 3);
    EXPECT_EQ(counted.worst_region_id, 4u);
    EXPECT_NEAR(counted.worst_region, 1.0, 1e-12);
}

TEST(LocalError, GuardsAsRelativeRmseDoes) {
    Maps maps(2, 16);
    std::vector<std::uint32_t> short_regions(maps.region.begin(), maps.region.end() - 1);
    EXPECT_THROW((void)local_error(maps.estimate, maps.reference, maps.area, short_regions), Error);
    std::vector<double> negative = maps.area;
    negative[3] = -1.0;
    EXPECT_THROW((void)local_error(maps.estimate, maps.reference, negative, maps.region), Error);

    std::vector<glm::dvec3> nan = maps.estimate;
    nan[5].y = std::numeric_limits<double>::quiet_NaN();
    const LocalError broken = local_error(nan, maps.reference, maps.area, maps.region);
    EXPECT_TRUE(std::isinf(broken.worst_region));
    EXPECT_TRUE(std::isinf(broken.texel_p99));

    const std::vector<glm::dvec3> black(maps.estimate.size(), glm::dvec3(0.0));
    const LocalError dark = local_error(black, black, maps.area, maps.region);
    EXPECT_EQ(dark.worst_region, 0.0);
    EXPECT_EQ(dark.texel_p99, 0.0);
    const LocalError lit_on_black = local_error(maps.estimate, black, maps.area, maps.region);
    EXPECT_TRUE(std::isinf(lit_on_black.worst_region));
}

}  // namespace
