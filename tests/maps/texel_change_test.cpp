// The per-texel change test of full gather passes (texel_change_test.hpp): a pass that only
// re-draws the noise keeps every texel's refinement; a patch whose light really changed
// restarts, and the texels far from it do not; a change too uniform for any neighbourhood to
// resolve restarts the surface; texels without a noise measure restart.

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "luxel/lighting/core/texel_change_test.hpp"

namespace {

using namespace luxel::lighting;

constexpr int kSide = 48;
constexpr float kMean = 2.0f;            ///< W/m^2 per channel
constexpr double kRelativeNoise = 0.15;  ///< one pass's standard deviation / value
constexpr std::uint32_t kPasses = 8;

/// A kSide x kSide surface at the page's (5, 7), every texel's mean kMean after kPasses passes
/// with a measured one-pass noise of kRelativeNoise.
struct Surface {
    std::vector<SurfaceTexel> texels;
    RefinementStats refinement;

    Surface() {
        for (int y = 0; y < kSide; ++y) {
            for (int x = 0; x < kSide; ++x) {
                SurfaceTexel texel;
                texel.x = 5 + x;
                texel.y = 7 + y;
                texels.push_back(texel);
            }
        }
        const std::size_t count = texels.size();
        refinement.mean.assign(count, glm::vec3(kMean));
        refinement.m2.assign(count, glm::vec3(0.0f));
        refinement.texel_passes.assign(count, kPasses);
        // Summed over the channels, relative to the squared mean's sum: the same as one
        // channel's.
        refinement.relative_pass_variance.assign(
            count, static_cast<float>(kRelativeNoise * kRelativeNoise));
        refinement.passes_averaged = kPasses;
    }

    /// A new pass: the true value `truth(x, y)` per channel with one pass's noise, the same
    /// noise in the three channels (a gather's rays see the same surroundings).
    template <typename Truth>
    [[nodiscard]] std::vector<glm::vec3> pass(Truth truth, std::uint32_t seed) const {
        std::mt19937 random(seed);
        std::normal_distribution<float> normal(0.0f, 1.0f);
        std::vector<glm::vec3> values;
        for (const SurfaceTexel& texel : texels) {
            const float value = truth(texel.x - 5, texel.y - 7);
            values.emplace_back(value *
                                (1.0f + static_cast<float>(kRelativeNoise) * normal(random)));
        }
        return values;
    }
};

std::size_t count_changed(const std::vector<std::uint8_t>& changed) {
    std::size_t count = 0;
    for (const std::uint8_t c : changed) {
        count += c != 0 ? 1 : 0;
    }
    return count;
}

TEST(TexelChange, APassThatOnlyRedrawsTheNoiseKeepsAlmostEveryTexel) {
    const Surface surface;
    for (std::uint32_t seed = 1; seed <= 5; ++seed) {
        const auto pass = surface.pass([](int, int) { return kMean; }, seed);
        const auto changed = texels_changed(surface.texels, pass, surface.refinement, 4, 3.0);
        ASSERT_EQ(changed.size(), surface.texels.size());
        EXPECT_LT(count_changed(changed), surface.texels.size() / 50) << "seed " << seed;
    }
}

TEST(TexelChange, APatchWhoseLightChangedRestartsAndTheFarTexelsDoNot) {
    const Surface surface;
    // A 12 x 12 patch 40% brighter (light through a door that opened), the rest unchanged.
    const auto in_patch = [](int x, int y) { return x >= 10 && x < 22 && y >= 30 && y < 42; };
    const auto pass =
        surface.pass([&](int x, int y) { return in_patch(x, y) ? 1.4f * kMean : kMean; }, 11);
    const auto changed = texels_changed(surface.texels, pass, surface.refinement, 4, 3.0);
    std::size_t patch = 0;
    std::size_t patch_changed = 0;
    std::size_t far = 0;
    std::size_t far_changed = 0;
    for (std::size_t i = 0; i < surface.texels.size(); ++i) {
        const int x = surface.texels[i].x - 5;
        const int y = surface.texels[i].y - 7;
        if (in_patch(x, y)) {
            ++patch;
            patch_changed += changed[i];
        } else if (x < 5 || x > 27 || y < 25) {  // beyond the test's radius of the patch
            ++far;
            far_changed += changed[i];
        }
    }
    EXPECT_GT(static_cast<double>(patch_changed), 0.95 * static_cast<double>(patch));
    EXPECT_LT(static_cast<double>(far_changed), 0.02 * static_cast<double>(far));
}

TEST(TexelChange, AUniformChangeNoNeighbourhoodResolvesRestartsTheSurface) {
    const Surface surface;
    // 4% brighter everywhere: under one neighbourhood's resolution (about 2% x 3 sigmas at
    // 15% noise), well over the whole surface's.
    const auto pass = surface.pass([](int, int) { return 1.04f * kMean; }, 21);
    const auto changed = texels_changed(surface.texels, pass, surface.refinement, 4, 3.0);
    EXPECT_EQ(count_changed(changed), surface.texels.size());
}

TEST(TexelChange, TexelsWithoutANoiseMeasureRestartAndSoDoTheirNeighbours) {
    Surface surface;
    const std::size_t unmeasured = 20 * kSide + 20;
    surface.refinement.relative_pass_variance[unmeasured] = -1.0f;
    const auto pass = surface.pass([](int, int) { return kMean; }, 31);
    const auto changed = texels_changed(surface.texels, pass, surface.refinement, 2, 3.0);
    EXPECT_EQ(changed[unmeasured], 1);
    EXPECT_EQ(changed[unmeasured + 2], 1);  // within the radius
    EXPECT_EQ(changed[unmeasured + 2 * kSide], 1);
    EXPECT_LT(count_changed(changed), 25u + surface.texels.size() / 50);

    // No statistics at all, or a test turned off: everything restarts.
    const auto none = texels_changed(surface.texels, pass, RefinementStats{}, 2, 3.0);
    EXPECT_EQ(count_changed(none), surface.texels.size());
    const auto off = texels_changed(surface.texels, pass, surface.refinement, 2, 0.0);
    EXPECT_EQ(count_changed(off), surface.texels.size());
}

TEST(TexelChange, NonFiniteValuesRestartInsteadOfPoisoningTheMean) {
    Surface surface;
    auto pass = surface.pass([](int, int) { return kMean; }, 41);
    pass[100] = glm::vec3(std::numeric_limits<float>::quiet_NaN());
    surface.refinement.mean[200] = glm::vec3(std::numeric_limits<float>::infinity());
    const auto changed = texels_changed(surface.texels, pass, surface.refinement, 2, 3.0);
    EXPECT_EQ(changed[100], 1);
    EXPECT_EQ(changed[200], 1);
    EXPECT_LT(count_changed(changed), 60u + surface.texels.size() / 50);
}

}  // namespace
