// The level-adjusted mip-map kernel (S. Larsen 2006): where photons are sparse, as a camera
// close to a caustic sees them, it widens until an estimate holds mip_min_photons photons, so
// a uniform caustic reads smooth where a fixed screen-space kernel breaks into dots; where
// photons are dense it keeps the splat's own resolution; it keeps the photons' power.

#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "caustic_test_support.hpp"
#include "luxel/lighting/gpu/caustic_kernel.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;

class CausticMipLevels : public ::testing::Test {
  protected:
    void SetUp() override { context_ = test::make_caustic_gl_context(); }
    void TearDown() override { context_.reset(); }
    std::unique_ptr<GlContext> context_;
};

/// `count` photons at uniformly random points of the 2 x 2 m square around the origin on the
/// z = 0 plane, `watts` in all: an irradiance of watts / 4 everywhere on it.
std::vector<CausticPhoton> uniform_photons(int count, float watts) {
    std::mt19937 random(7);
    std::uniform_real_distribution<float> along(-1.0f, 1.0f);
    std::vector<CausticPhoton> photons(static_cast<std::size_t>(count));
    for (CausticPhoton& p : photons) {
        p.position = {along(random), along(random), 0.0f};
        p.power = glm::vec3(watts / static_cast<float>(count));
    }
    return photons;
}

TEST_F(CausticMipLevels, SparsePhotonsReadSmootherThroughTheMipLevelsThanLarsensKernel) {
    // A camera 0.6 m from a uniformly lit plane: about 0.12 photons a pixel, a close-up, where
    // Larsen's 7 x 7 kernel holds about 6 and the 5 cm radius the mip kernel may widen to
    // about 20.
    const glm::ivec2 size(128, 96);
    const test::RectScene scene(test::look_at({0.0f, 0.0f, 0.6f}, {0.0f, 0.0f, 0.0f}, size),
                                {{{0, 0, 0}, {5, 0, 0}, {0, 5, 0}}});
    const float watts = 4.0f;
    const std::vector<CausticPhoton> photons = uniform_photons(10'000, watts);
    const double expected = watts / 4.0;

    CausticPassSettings larsen;
    CausticPassSettings mip;
    mip.kernel = CausticKernel::MipLevels;
    const auto [larsen_error, larsen_mean] =
        test::uniform_error(test::filtered(larsen, scene, size, photons), size, expected, 16);
    const auto [mip_error, mip_mean] =
        test::uniform_error(test::filtered(mip, scene, size, photons), size, expected, 16);
    std::printf(
        "[ figures  ] 0.12 photons a pixel: relRMSE Larsen k=3 %.1f%% (mean %.3f), "
        "mip levels (16 photons) %.1f%% (mean %.3f)\n",
        100.0 * larsen_error, larsen_mean, 100.0 * mip_error, mip_mean);
    EXPECT_LT(mip_error, 0.7 * larsen_error);
    EXPECT_LT(mip_error, 0.35) << "about 1 / sqrt(16), and the blend between levels";
    EXPECT_NEAR(mip_mean, 1.0, 0.1);
}

TEST_F(CausticMipLevels, DensePhotonsKeepTheSplatsResolutionAndThePowerIsKept) {
    // Far from a disc of 40,000 photons: most of its pixels hold 16 or more, where the estimate
    // is the splat's own pixel. The filtered power is the photons' and a little more: pixels
    // just outside the disc widen until they reach it (within the 5 cm radius), the edge bias
    // of any nearest-photons estimate (measured 4.6% here).
    const glm::ivec2 size(250, 250);  // not a power of two: the chain ends at 1 x 1
    const test::RectScene scene(test::look_at({0.2f, 0.1f, 3.0f}, {0.2f, 0.1f, 0.0f}, size),
                                {{{0, 0, 0}, {5, 0, 0}, {0, 5, 0}}});
    const glm::vec3 power(0.5f, 1.0f, 2.0f);
    const std::vector<CausticPhoton> photons =
        test::disc_photons({0.5f, -0.2f, 0.0f}, {1, 0, 0}, {0, 1, 0}, 0.2f, 40'000, power);
    CausticPassSettings settings;
    settings.kernel = CausticKernel::MipLevels;
    CausticPass pass(settings, size);
    pass.upload(photons);
    pass.render(scene.camera(), scene.depth_texture().id());
    EXPECT_EQ(pass.stats().photons_splatted, photons.size());
    const std::vector<glm::vec4> splat = test::read_rgba(pass.splat_texture(), size);
    const std::vector<glm::vec4> out = test::read_rgba(pass.irradiance_texture(), size);
    int dense = 0;
    for (std::size_t i = 0; i < splat.size(); ++i) {
        if (splat[i].a >= 16.0f) {
            ++dense;
            ASSERT_EQ(out[i], splat[i]) << "pixel " << i;
        }
        ASSERT_TRUE(std::isfinite(out[i].r) && out[i].g >= 0.0f);
    }
    EXPECT_GT(dense, 100);
    const glm::dvec3 total = test::total_power(out, scene);
    for (int c = 0; c < 3; ++c) {
        const double expected = power[c];
        EXPECT_NEAR(total[c], expected, 0.06 * expected) << "channel " << c;
    }
    std::printf("[ figures  ] mip levels: %d dense pixels, filtered power %.4f of the photons'\n",
                dense, total.g / power.g);
    // Switching kernels on a live pass rebuilds the splat's chain.
    settings.kernel = CausticKernel::Larsen;
    pass.set_settings(settings);
    pass.render(scene.camera(), scene.depth_texture().id());
    settings.kernel = CausticKernel::MipLevels;
    pass.set_settings(settings);
    pass.render(scene.camera(), scene.depth_texture().id());
    EXPECT_EQ(test::read_rgba(pass.irradiance_texture(), size), out);
    settings.mip_min_photons = 0.0f;
    EXPECT_THROW(pass.set_settings(settings), Error);
}

}  // namespace
