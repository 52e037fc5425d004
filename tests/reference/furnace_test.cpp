// The furnace (docs/LEVELS.md): inside a closed sphere of uniform albedo rho and emitted
// radiance Le, the radiance leaving every point is Le / (1 - rho), so every texel's irradiance
// is pi Le / (1 - rho). Also: the reported standard error falls as 1 / sqrt(samples), and a
// seed fixes the result.

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "luxel/lighting/reference/reference_integrator.hpp"
#include "reference_test_support.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting::reference;

ReferenceSettings few_samples(std::uint32_t samples = 2) {
    ReferenceSettings settings;
    settings.samples_per_pass = samples;
    settings.caustics.photons_per_pass = 1000;  // no delta light here: nothing is emitted
    return settings;
}

TEST(Furnace, TheLevelHasOneEmittingSphereAndLightMappedTexels) {
    luxel::testing::ReferenceLevel level("furnace");
    const ReferenceScene& scene = *level.scene;
    ASSERT_EQ(scene.lights().size(), 1u);
    EXPECT_EQ(scene.lights()[0].source.kind, lighting::LightKind::Area);
    EXPECT_GT(scene.texel_count(), 100u);
    double area = 0.0;
    for (double a : scene.texel_areas()) {
        area += a;
    }
    // The tessellated unit sphere's area, a little under 4 pi.
    EXPECT_NEAR(area, 4.0 * glm::pi<double>(), 0.02 * 4.0 * glm::pi<double>());
    std::printf("[ figures  ] furnace: %zu texels, %.4f m^2\n", scene.texel_count(), area);
}

void check_furnace(double albedo) {
    luxel::testing::ReferenceLevel level("furnace");
    ReferenceScene& scene = *level.scene;
    for (auto& material : scene.materials()) {
        material.albedo = glm::vec3(static_cast<float>(albedo));
    }
    const double emitted = scene.lights()[0].source.power.x;
    ReferenceIntegrator integrator(scene, few_samples(16));
    JobSystem jobs(2);
    for (int pass = 0; pass < 4; ++pass) {
        integrator.run_pass(jobs);
    }
    const double expected = glm::pi<double>() * emitted / (1.0 - albedo);
    double worst_sigma = 0.0;
    double mean = 0.0;
    std::size_t outside = 0;
    const std::size_t texels = scene.texel_count();
    for (std::size_t t = 0; t < texels; ++t) {
        const double e = integrator.total(t).x;
        const double se = integrator.total_standard_error(t).x;
        mean += e / static_cast<double>(texels);
        // 3 sigma of the reported error plus 1% (the texel's interpolated normal and the
        // tessellation's facets differ by up to 3 degrees).
        const double tolerance = 3.0 * se + 0.01 * expected;
        if (std::abs(e - expected) > tolerance) {
            ++outside;
        }
        if (se > 0.0) {
            worst_sigma = std::max(worst_sigma, std::abs(e - expected) / se);
        }
        ASSERT_TRUE(std::isfinite(e));
    }
    // 3 sigma: 0.3% of texels would fall outside by chance if the errors were normal; the
    // indirect samples are skewed (path lengths are geometric) and their variance is
    // estimated from 64 samples, which often underestimates it, hence 2%.
    EXPECT_LE(static_cast<double>(outside), 0.02 * static_cast<double>(texels) + 1.0)
        << outside << " of " << texels << " texels outside 3 sigma + 1%";
    // The mean over all texels averages the noise away: 0.5%.
    EXPECT_NEAR(mean, expected, 0.005 * expected);
    // L = Le + rho E / pi on the wall.
    const double radiance = emitted + albedo * mean / glm::pi<double>();
    EXPECT_NEAR(radiance, emitted / (1.0 - albedo), 0.005 * emitted / (1.0 - albedo));
    std::printf(
        "[ figures  ] furnace rho %.2f: mean E %.5f (expected %.5f, %+.3f%%), L %.5f, %zu of %zu "
        "texels outside 3 sigma + 1%%, rel. std. error direct %.4f indirect %.4f, %llu rays\n",
        albedo, mean, expected, 100.0 * (mean / expected - 1.0), radiance, outside, texels,
        integrator.relative_standard_error(Component::Direct),
        integrator.relative_standard_error(Component::Indirect),
        static_cast<unsigned long long>(integrator.path_counters().rays));
    EXPECT_EQ(integrator.path_counters().non_finite, 0u);
}

TEST(Furnace, RadianceIsEmissionOverOneMinusAlbedoAtHalf) {
    check_furnace(0.5);
}

TEST(Furnace, RadianceIsEmissionOverOneMinusAlbedoAtNineTenths) {
    check_furnace(0.9);
}

TEST(Furnace, StandardErrorFallsAsOneOverSqrtSamples) {
    luxel::testing::ReferenceLevel level("furnace");
    ReferenceIntegrator integrator(*level.scene, few_samples(4));
    JobSystem jobs(2);
    const auto errors = [&] {
        return glm::dvec2(integrator.relative_standard_error(Component::Direct),
                          integrator.relative_standard_error(Component::Indirect));
    };
    integrator.run_pass(jobs);
    const glm::dvec2 one = errors();
    for (int pass = 1; pass < 4; ++pass) {
        integrator.run_pass(jobs);
    }
    const glm::dvec2 four = errors();
    for (int pass = 4; pass < 16; ++pass) {
        integrator.run_pass(jobs);
    }
    const glm::dvec2 sixteen = errors();
    for (int c = 0; c < 2; ++c) {
        const char* name = c == 0 ? "direct" : "indirect";
        ASSERT_GT(sixteen[c], 0.0) << name;
        // sqrt(4) = 2 per step. The first step starts from variances estimated from 4
        // samples per texel, themselves noisy (and low for the skewed indirect samples).
        EXPECT_NEAR(one[c] / four[c], 2.0, 0.4) << name;
        EXPECT_NEAR(four[c] / sixteen[c], 2.0, 0.2) << name;
        std::printf(
            "[ figures  ] %s rel. std. error at 4, 16, 64 samples: %.5f %.5f %.5f (ratios %.3f "
            "%.3f, ideal 2)\n",
            name, one[c], four[c], sixteen[c], one[c] / four[c], four[c] / sixteen[c]);
    }
}

TEST(Furnace, ASeedFixesTheResultWhateverTheThreadCount) {
    luxel::testing::ReferenceLevel level("furnace");
    ReferenceSettings settings = few_samples();
    settings.seed = 7;
    ReferenceIntegrator a(*level.scene, settings);
    ReferenceIntegrator b(*level.scene, settings);
    settings.seed = 8;
    ReferenceIntegrator c(*level.scene, settings);
    JobSystem one(1);
    JobSystem two(2);
    a.run_pass(one);
    b.run_pass(two);
    c.run_pass(two);
    std::size_t differ = 0;
    for (std::size_t t = 0; t < level.scene->texel_count(); ++t) {
        for (std::size_t k = 0; k < kComponentCount; ++k) {
            const auto component = static_cast<Component>(k);
            ASSERT_EQ(a.irradiance(component, t), b.irradiance(component, t)) << "texel " << t;
            ASSERT_EQ(a.standard_error(component, t), b.standard_error(component, t));
        }
        differ += a.total(t) != c.total(t) ? 1 : 0;
    }
    EXPECT_GT(differ, level.scene->texel_count() / 2) << "another seed gives other samples";
}

}  // namespace
