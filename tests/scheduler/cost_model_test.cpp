// The cost model: priors, learning from measurements, robustness to bad samples, adaptation.

#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "luxel/lighting/core/cost_model.hpp"

namespace {

using namespace luxel::lighting;

TEST(CostModel, NamesAreStableAndDistinct) {
    EXPECT_EQ(name(WorkKind::PhotonProbe), "photon_probe");
    EXPECT_EQ(name(WorkKind::GroupRetrace), "group_retrace");
    EXPECT_EQ(name(WorkKind::CausticSlice), "caustic_slice");
    EXPECT_EQ(name(WorkKind::AimRebuild), "aim_rebuild");
    EXPECT_EQ(name(WorkKind::IimGather), "iim_gather");
    EXPECT_EQ(name(WorkKind::ProbeGather), "probe_gather");
    EXPECT_EQ(index(WorkKind::ProbeGather), kWorkKindCount - 1);
}

TEST(CostModel, PredictsThePriorTimesSizeBeforeAnyMeasurement) {
    CostModelSettings settings;
    settings.prior_ms[index(WorkKind::AimRebuild)] = 2.0;
    const CostModel model(settings);
    EXPECT_DOUBLE_EQ(model.predict(WorkKind::AimRebuild, 1.0), 2.0);
    EXPECT_DOUBLE_EQ(model.predict(WorkKind::AimRebuild, 3.0), 6.0);
    EXPECT_DOUBLE_EQ(model.predict(WorkKind::AimRebuild, 0.0), 0.0);
    EXPECT_DOUBLE_EQ(model.predict(WorkKind::AimRebuild, -1.0), 0.0);
    EXPECT_DOUBLE_EQ(model.predict(WorkKind::AimRebuild, std::nan("")), 0.0);
    // An unmeasured kind is uncertain: the bound is error_factor * 50 % of the prior.
    EXPECT_NEAR(model.prediction_error(WorkKind::AimRebuild, 1.0),
                settings.error_factor * 0.5 * 2.0 + settings.min_error_ms, 1e-12);
    EXPECT_EQ(model.cost(WorkKind::AimRebuild).samples, 0U);
}

TEST(CostModel, IgnoresNonFiniteAndNegativeSamples) {
    CostModel model;
    const double before = model.predict(WorkKind::GroupRetrace, 1.0);
    const double inf = std::numeric_limits<double>::infinity();
    model.record(WorkKind::GroupRetrace, 1.0, std::nan(""));
    model.record(WorkKind::GroupRetrace, 1.0, inf);
    model.record(WorkKind::GroupRetrace, 1.0, -1.0);
    model.record(WorkKind::GroupRetrace, 0.0, 1.0);
    model.record(WorkKind::GroupRetrace, -2.0, 1.0);
    model.record(WorkKind::GroupRetrace, inf, 1.0);
    model.record(WorkKind::GroupRetrace, std::numeric_limits<double>::denorm_min(), 1e300);
    EXPECT_EQ(model.cost(WorkKind::GroupRetrace).samples, 0U);
    EXPECT_DOUBLE_EQ(model.predict(WorkKind::GroupRetrace, 1.0), before);
    EXPECT_TRUE(std::isfinite(model.prediction_error(WorkKind::GroupRetrace, 1.0)));
}

TEST(CostModel, NonsenseSettingsFallBackToDefaults) {
    CostModelSettings bad;
    bad.prior_ms[0] = std::nan("");
    bad.prior_ms[1] = -3.0;
    bad.smoothing = 0.0;
    bad.error_factor = std::numeric_limits<double>::infinity();
    const CostModel model(bad);
    const CostModelSettings defaults;
    EXPECT_DOUBLE_EQ(model.settings().prior_ms[0], defaults.prior_ms[0]);
    EXPECT_DOUBLE_EQ(model.settings().prior_ms[1], defaults.prior_ms[1]);
    EXPECT_DOUBLE_EQ(model.settings().smoothing, defaults.smoothing);
    EXPECT_DOUBLE_EQ(model.settings().error_factor, defaults.error_factor);
}

TEST(CostModel, LearnsPerUnitOfSizeAndForgetsAWrongPrior) {
    CostModel model;  // gather prior: 0.05 ms per unit of size
    // Real cost: 0.004 ms per texel, batches of 16..64 texels, +-20 % noise.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> texels(16.0, 64.0);
    std::uniform_real_distribution<double> noise(0.8, 1.2);
    for (int i = 0; i < 10; ++i) {
        const double size = texels(rng);
        model.record(WorkKind::IimGather, size, 0.004 * size * noise(rng));
    }
    // The prior (0.05) was 12x off; ten samples suffice, the first replaced it.
    EXPECT_NEAR(model.predict(WorkKind::IimGather, 32.0), 0.004 * 32.0, 0.2 * 0.004 * 32.0);
    // The bound covers the noise (+-20 %) but is not absurdly wide.
    const double bound = model.prediction_error(WorkKind::IimGather, 32.0);
    EXPECT_GT(bound, 0.0);
    EXPECT_LT(bound, 0.004 * 32.0 * 1.5);
    // One sample with prior_weight 1 is averaged with the prior instead.
    CostModelSettings weighted;
    weighted.prior_weight = 1.0;
    CostModel cautious(weighted);
    cautious.record(WorkKind::IimGather, 10.0, 0.1);  // 0.01 per unit
    EXPECT_NEAR(cautious.predict(WorkKind::IimGather, 1.0), 0.03, 1e-12);
    model.reset();
    EXPECT_DOUBLE_EQ(model.predict(WorkKind::IimGather, 1.0), 0.05);
    EXPECT_EQ(model.cost(WorkKind::IimGather).samples, 0U);
}

TEST(CostModel, ErrorBoundCoversSteadyNoise) {
    CostModel model;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> noise(0.7, 1.3);  // +-30 %
    int outside = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
        const double actual = 0.3 * noise(rng);
        const double predicted = model.predict(WorkKind::GroupRetrace, 1.0);
        const double bound = model.prediction_error(WorkKind::GroupRetrace, 1.0);
        if (i >= 20 && std::abs(actual - predicted) > bound) {
            ++outside;
        }
        model.record(WorkKind::GroupRetrace, 1.0, actual);
    }
    // After 20 samples of warm-up the bound (3 mean absolute deviations) holds for every sample
    // but a handful in 20000.
    EXPECT_LE(outside, n / 1000);
}

TEST(CostModel, AConstantCostStillGetsAFloorOfError) {
    CostModel model;
    for (int i = 0; i < 200; ++i) {
        model.record(WorkKind::IimGather, 1.0, 0.1);
    }
    EXPECT_NEAR(model.predict(WorkKind::IimGather, 1.0), 0.1, 1e-9);
    // 5 % of the mean plus 1 microsecond, not 0.
    EXPECT_NEAR(model.prediction_error(WorkKind::IimGather, 1.0), 0.005 + 0.001, 1e-6);
}

TEST(CostModel, AdaptsWhenCostsTriple) {
    CostModel model;
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> noise(0.85, 1.15);
    for (int i = 0; i < 500; ++i) {
        model.record(WorkKind::CausticSlice, 1.0, 0.4 * noise(rng));
    }
    ASSERT_NEAR(model.predict(WorkKind::CausticSlice, 1.0), 0.4, 0.04);
    // The scene gets heavier: 1.2 ms. With smoothing 0.1, the gap of 0.8 ms shrinks by 0.9 per
    // sample: under 20 % of the new cost (0.24 ms) after ln(0.3)/ln(0.9) = 12 samples; 20 with
    // margin for the noise.
    int first_within = -1;
    for (int i = 0; i < 200; ++i) {
        model.record(WorkKind::CausticSlice, 1.0, 1.2 * noise(rng));
        const double rel = std::abs(model.predict(WorkKind::CausticSlice, 1.0) - 1.2) / 1.2;
        if (rel <= 0.2 && first_within < 0) {
            first_within = i + 1;
        }
        if (i + 1 >= 20) {
            ASSERT_LE(rel, 0.2) << "after " << i + 1 << " samples of the new cost";
        }
    }
    EXPECT_GT(first_within, 1);  // it did have to adapt
    EXPECT_LE(first_within, 20);
}

}  // namespace
