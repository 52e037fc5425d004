// The reference integrator's furnace at albedo 0.99 and 0.999 (issue 12; the `reference` label
// covers 0.5 and 0.9): inside a closed sphere of albedo rho emitting Le, the radiance leaving
// every point is Le / (1 - rho), so every texel's irradiance is pi Le / (1 - rho).
//
// Bounded work. PathEstimator plays Russian roulette at every diffuse vertex with survival
// max(albedo) = rho, so the number of diffuse vertices of a path is geometric: the first
// always, each further one with probability rho, 1 / (1 - rho) on average (100 at 0.99, 1,000
// at 0.999). Each vertex costs two rays (the continuation and one shadow ray to the sphere, the
// only light). Whatever roulette says, a path stops at PathSettings::max_vertices = 10,000
// scattering events; that drops rho^10000 of the light (4.5e-5 at 0.999, nothing measurable at
// 0.99) and bounds the time of every path. The test asserts both: the mean rays per sample
// against 2 / (1 - rho), and the count of truncated paths.
//
// Few texels: at 0.999 a sample costs ~2,000 rays, so the 5,440 texels of the level at a few
// samples each would take minutes. The test integrates every 40th texel (136, spread over the
// whole sphere by the atlas order) with more samples each; the integrator's own standard error
// says how well that pins the mean down.

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "luxel/lighting/reference/reference_integrator.hpp"
#include "reference_test_support.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting::reference;

struct FurnaceCase {
    double albedo;
    std::uint32_t samples;  ///< per texel, over all passes
};

/// Every `stride`-th texel of `full`, in a scene over the same geometry and lights.
ReferenceScene every_nth_texel(const ReferenceScene& full, std::size_t stride) {
    std::vector<ReferenceSurface> surfaces;
    std::size_t global = 0;
    for (const ReferenceSurface& surface : full.surfaces()) {
        ReferenceSurface kept = surface;
        kept.texels.clear();
        for (const ReferenceTexel& texel : surface.texels) {
            if (global++ % stride == 0) {
                kept.texels.push_back(texel);
            }
        }
        if (!kept.texels.empty()) {
            surfaces.push_back(std::move(kept));
        }
    }
    std::vector<lighting::LightSource> lights;
    for (const ReferenceLight& light : full.lights()) {
        lights.push_back(light.source);
    }
    return {full.rays(),
            std::vector<lighting::TraceMaterial>(full.materials().begin(), full.materials().end()),
            std::move(lights), std::move(surfaces)};
}

class ReferenceFurnace : public ::testing::TestWithParam<FurnaceCase> {};

TEST_P(ReferenceFurnace, MeanIrradianceIsPiLeOverOneMinusRho) {
    const FurnaceCase c = GetParam();
    luxel::testing::ReferenceLevel level("furnace");
    ReferenceScene scene = every_nth_texel(*level.scene, 40);
    ASSERT_GT(scene.texel_count(), 100u);
    for (auto& material : scene.materials()) {
        material.albedo = glm::vec3(static_cast<float>(c.albedo));
    }
    ASSERT_EQ(scene.lights().size(), 1u);
    const double emitted = scene.lights()[0].source.power.x;
    ReferenceSettings settings;
    settings.samples_per_pass = c.samples / 4;
    settings.caustics.photons_per_pass = 1000;  // no delta light: nothing is emitted
    ReferenceIntegrator integrator(scene, settings);
    JobSystem jobs(2);
    for (int pass = 0; pass < 4; ++pass) {
        integrator.run_pass(jobs);
    }

    // The area-weighted mean over the texels and its standard error: the texels' samples are
    // independent, so their variances add.
    double weighted = 0.0;
    double area = 0.0;
    double variance = 0.0;
    for (std::size_t t = 0; t < scene.texel_count(); ++t) {
        const double a = scene.texel(t).area;
        const double e = integrator.total(t).x;
        const double se = integrator.total_standard_error(t).x;
        ASSERT_TRUE(std::isfinite(e)) << "texel " << t;
        weighted += a * e;
        area += a;
        variance += a * a * se * se;
    }
    ASSERT_GT(area, 0.0);
    const double expected = glm::pi<double>() * emitted / (1.0 - c.albedo);
    const double mean = weighted / area;
    const double relative_error = mean / expected - 1.0;
    const double relative_se = std::sqrt(variance) / area / expected;
    const PathCounters& counters = integrator.path_counters();
    const double samples =
        static_cast<double>(integrator.samples()) * static_cast<double>(scene.texel_count());
    const double rays_per_sample = static_cast<double>(counters.rays) / samples;
    const double vertices = 1.0 / (1.0 - c.albedo);
    std::printf(
        "[ figures  ] reference furnace rho %.3f: mean E %.3f, expected %.3f (%+.2f%%, standard "
        "error %.2f%%) over %zu texels x %llu samples; %.0f rays per sample (2 / (1 - rho) = "
        "%.0f), %llu of %.0f paths truncated\n",
        c.albedo, mean, expected, 100.0 * relative_error, 100.0 * relative_se, scene.texel_count(),
        static_cast<unsigned long long>(integrator.samples()), rays_per_sample, 2.0 * vertices,
        static_cast<unsigned long long>(counters.truncated), samples);

    // 4 standard errors of the mean (a normal deviate beyond 4 sigma: 6e-5; the samples are
    // skewed, path lengths being geometric, but the mean of thousands of them is close to
    // normal), plus 0.3% of bias allowance: the texels' interpolated normals lean up to 3
    // degrees off the facets, and directions below the facet carry nothing, which cuts at most
    // sin^2(3 deg) = 0.27% of the cosine-weighted hemisphere; plus the truncation's rho^10000.
    const double tolerance = 4.0 * relative_se + 0.003 + std::pow(c.albedo, 10000.0);
    EXPECT_LE(std::abs(relative_error), tolerance);
    EXPECT_GT(relative_se, 0.0) << "the integrator reports no error: nothing to judge by";
    EXPECT_EQ(counters.non_finite, 0u);
    // Bounded work: rays per sample against two per vertex, 2 / (1 - rho). The mean of N
    // geometric path lengths is within 1 / sqrt(N) relative (<= 2% here) of 1 / (1 - rho); the
    // texel's own shadow ray and the first segment add ~2 rays. 10% leaves 5 sigma; a roulette
    // that failed to end paths would sit at the 10,000-vertex cap, 10x (0.999) to 100x (0.99).
    EXPECT_NEAR(rays_per_sample / (2.0 * vertices), 1.0, 0.1);
    // Expected truncated paths: N rho^10000 (0.2 at 0.999); 5 or more has probability 1e-6.
    EXPECT_LT(static_cast<double>(counters.truncated), 5.0);
}

// Samples per texel: at 0.999 the per-sample relative deviation is ~1 (the path length is
// geometric), so 136 x 32 samples give a standard error of ~1.5%; 0.99 is ten times cheaper
// per sample and gets 128 each (~0.8%). Both take a few seconds in RelWithDebInfo on 2 cores.
INSTANTIATE_TEST_SUITE_P(Albedos, ReferenceFurnace,
                         ::testing::Values(FurnaceCase{0.99, 128}, FurnaceCase{0.999, 32}),
                         [](const auto& param_info) {
                             return "rho_" + std::to_string(static_cast<int>(
                                                 param_info.param.albedo * 1000.0 + 0.5));
                         });

}  // namespace
