// The caustic filter conserves energy: photons splatted onto a plane facing the camera, away
// from the screen border, give a filtered image whose sum of E * (pixel area) is the photons'
// total power, for every kernel; the kernels themselves sum to 1. The reference area is the
// test's own ray cast, not the pass's.

#include <cmath>

#include <gtest/gtest.h>

#include "caustic_test_support.hpp"
#include "luxel/lighting/gpu/caustic_kernel.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;

class CausticEnergy : public ::testing::Test {
  protected:
    void SetUp() override { context_ = test::make_caustic_gl_context(); }
    void TearDown() override { context_.reset(); }
    std::unique_ptr<GlContext> context_;
};

TEST(CausticKernelWeights, SumToOneAndFollowTheirFormulas) {
    for (const CausticKernel kernel :
         {CausticKernel::Larsen, CausticKernel::Box, CausticKernel::RoundCone}) {
        for (const int k : {0, 1, 3, 8}) {
            const std::vector<float> w = caustic_kernel_weights(kernel, k);
            ASSERT_EQ(w.size(), static_cast<std::size_t>((2 * k + 1) * (2 * k + 1)));
            double sum = 0.0;
            for (const float x : w) {
                EXPECT_GE(x, 0.0f);
                sum += static_cast<double>(x);
            }
            EXPECT_NEAR(sum, 1.0, 1e-6) << kernel_name(kernel) << " k = " << k;
        }
    }
    // Larsen, k = 3: the centre weighs sqrt(19) times a corner.
    const std::vector<float> larsen = caustic_kernel_weights(CausticKernel::Larsen, 3);
    EXPECT_NEAR(larsen[24] / larsen[0], std::sqrt(19.0f), 1e-5f);
    // Round cone, k = 3, d = 4: the corner (r = 4.24) is out, (3, 0) weighs 1/4 of the centre.
    const std::vector<float> cone = caustic_kernel_weights(CausticKernel::RoundCone, 3);
    EXPECT_EQ(cone[0], 0.0f);
    EXPECT_NEAR(cone[3 * 7 + 6] / cone[24], 0.25f, 1e-6f);
    EXPECT_THROW(static_cast<void>(caustic_kernel_weights(CausticKernel::WorldCone, 3)), Error);
    EXPECT_THROW(static_cast<void>(caustic_kernel_weights(CausticKernel::Box, 9)), Error);
}

TEST_F(CausticEnergy, FilteredTotalEqualsSplattedPowerForEveryKernel) {
    const glm::ivec2 size(256, 256);
    const test::RectScene scene(test::look_at({0.2f, 0.1f, 3.0f}, {0.2f, 0.1f, 0.0f}, size),
                                {{{0, 0, 0}, {5, 0, 0}, {0, 5, 0}}});
    // An off-centre caustic 0.4 m across; the screen spans ~3.3 m at 3 m.
    const glm::vec3 power(0.5f, 1.0f, 2.0f);
    const std::vector<CausticPhoton> photons =
        test::disc_photons({0.5f, -0.2f, 0.0f}, {1, 0, 0}, {0, 1, 0}, 0.2f, 5000, power);

    for (const CausticKernel kernel : {CausticKernel::Larsen, CausticKernel::Box,
                                       CausticKernel::RoundCone, CausticKernel::WorldCone}) {
        for (const int k : {3, 6}) {
            CausticPassSettings settings;
            settings.kernel = kernel;
            settings.kernel_radius = k;
            settings.world_radius = 0.03f;  // ~2.4 pixels at 3 m
            CausticPass pass(settings, size);
            pass.upload(photons);
            pass.render(scene.camera(), scene.depth_texture().id());
            const CausticPassStats& stats = pass.stats();
            EXPECT_EQ(stats.photons_splatted, photons.size());

            const glm::dvec3 splatted =
                test::total_power(test::read_rgba(pass.splat_texture(), size), scene);
            const glm::dvec3 filtered =
                test::total_power(test::read_rgba(pass.irradiance_texture(), size), scene);
            double worst = 0.0;
            for (int c = 0; c < 3; ++c) {
                const double expected = static_cast<double>(power[c]);
                const double splat_error = std::abs(splatted[c] - expected) / expected;
                const double filter_error = std::abs(filtered[c] - expected) / expected;
                worst = std::max({worst, splat_error, filter_error});
                EXPECT_LT(splat_error, 0.01) << kernel_name(kernel) << " k " << k << " c " << c;
                EXPECT_LT(filter_error, 0.01) << kernel_name(kernel) << " k " << k << " c " << c
                                              << ": " << filtered[c] << " vs " << expected;
            }
            RecordProperty(
                std::string("max_relative_error_") + kernel_name(kernel) + "_k" + std::to_string(k),
                std::to_string(worst));
            std::printf("energy %s k=%d: max relative error %.3g\n", kernel_name(kernel), k, worst);
        }
    }
}

TEST_F(CausticEnergy, OutputIsFiniteAndNonNegativeWhateverThePhotons) {
    const glm::ivec2 size(128, 96);
    const test::RectScene scene(test::look_at({0, 0, 2}, {0, 0, 0}, size),
                                {{{0, 0, 0}, {5, 0, 0}, {0, 5, 0}}});
    const float nan = std::nanf("");
    const float inf = std::numeric_limits<float>::infinity();
    std::vector<CausticPhoton> photons =
        test::disc_photons({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0.3f, 500, glm::vec3(1.0f));
    auto add = [&](glm::vec3 position, glm::vec3 power) {
        CausticPhoton p;
        p.position = position;
        p.power = power;
        photons.push_back(p);
    };
    add({nan, 0, 0}, {1, 1, 1});
    add({0.1f, 0.1f, 0}, {nan, 1, 1});
    add({0.1f, 0.1f, 0}, {inf, 1, 1});
    add({0.1f, -0.1f, 0}, {-5, -1, 2});           // negative channels count as zero
    add({0, 0, 5}, {1, 1, 1});                    // behind the camera
    add({0, 0, 2}, {1, 1, 1});                    // at the eye
    add({50, 0, 0}, {1, 1, 1});                   // off screen
    add({1.44f, 1.08f, 0}, {1, 1, 1});            // in the corner pixel
    add({0.2f, 0.2f, 0}, {1e20f, 1e20f, 1e20f});  // huge but finite
    CausticPass pass(CausticPassSettings{}, size);
    pass.upload(photons);
    pass.render(scene.camera(), scene.depth_texture().id());
    for (const GLuint texture : {pass.splat_texture(), pass.irradiance_texture()}) {
        int bad = 0;
        for (const glm::vec4& e : test::read_rgba(texture, size)) {
            for (int c = 0; c < 4; ++c) {
                bad += std::isfinite(e[c]) && e[c] >= 0.0f ? 0 : 1;
            }
        }
        EXPECT_EQ(bad, 0);
    }
    EXPECT_EQ(pass.stats().photons_splatted, 500u + 3u);  // the negative, corner and huge

    // No photons: a zero image, no counters, no crash; also after a frame that had some.
    pass.upload(std::span<const CausticPhoton>{});
    pass.render(scene.camera(), scene.depth_texture().id());
    for (const glm::vec4& e : test::read_rgba(pass.irradiance_texture(), size)) {
        ASSERT_EQ(e, glm::vec4(0.0f));
    }
    EXPECT_EQ(pass.stats().photons_splatted, 0u);
    EXPECT_EQ(pass.stats().tiles_filtered, 0u);
    CausticPass empty(CausticPassSettings{}, size);
    empty.render(scene.camera(), scene.depth_texture().id());
    for (const glm::vec4& e : test::read_rgba(empty.irradiance_texture(), size)) {
        ASSERT_EQ(e, glm::vec4(0.0f));
    }
}

}  // namespace
