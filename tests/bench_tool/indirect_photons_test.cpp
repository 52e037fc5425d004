// IndirectPhotons, the reference's photon estimate of the indirect component: the furnace's
// closed form, agreement with path tracing on the Cornell box, standard error against photon
// count, and determinism for a seed whatever the thread count.

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "luxel/lighting/reference/reference_integrator.hpp"
#include "reference_test_support.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting::reference;

ReferenceSettings photon_settings(std::uint64_t photons, std::uint32_t spp) {
    ReferenceSettings settings;
    settings.samples_per_pass = spp;
    settings.caustics.photons_per_pass = 1000;
    settings.indirect = IndirectMethod::Photons;
    settings.indirect_photons.photons_per_pass = photons;
    return settings;
}

double area_weighted_total(const ReferenceIntegrator& integrator, Component component) {
    const ReferenceScene& scene = integrator.scene();
    double sum = 0.0;
    for (std::size_t t = 0; t < scene.texel_count(); ++t) {
        const glm::dvec3 e = integrator.irradiance(component, t);
        sum += scene.texel(t).area * (e.x + e.y + e.z);
    }
    return sum;
}

TEST(IndirectPhotons, TheFurnaceGetsEmissionOverOneMinusAlbedo) {
    luxel::testing::ReferenceLevel level("furnace");
    ReferenceScene& scene = *level.scene;
    constexpr double kAlbedo = 0.5;
    for (auto& material : scene.materials()) {
        material.albedo = glm::vec3(static_cast<float>(kAlbedo));
    }
    ReferenceIntegrator integrator(scene, photon_settings(400'000, 4));
    JobSystem jobs(2);
    integrator.run_pass(jobs);
    const double emitted = scene.lights()[0].source.power.x;
    const double expected = glm::pi<double>() * emitted / (1.0 - kAlbedo);
    double mean = 0.0;
    double area = 0.0;
    for (std::size_t t = 0; t < scene.texel_count(); ++t) {
        const double a = scene.texel(t).area;
        mean += a * integrator.total(t).x;
        area += a;
    }
    mean /= area;
    // Direct by paths, indirect by photons: their sum is the closed form. The photons are
    // texel-area means and the mean over the sphere averages their noise: 1%.
    EXPECT_NEAR(mean, expected, 0.01 * expected);
    std::printf(
        "[ figures  ] furnace rho 0.5 (photons): mean E %.5f, expected %.5f (%+.3f%%), "
        "rel. std. error indirect %.4f\n",
        mean, expected, 100.0 * (mean / expected - 1.0),
        integrator.relative_standard_error(Component::Indirect));
}

TEST(IndirectPhotons, AgreeWithPathTracingOnTheCornellBox) {
    luxel::testing::ReferenceLevel level("cornell");
    JobSystem jobs(2);
    ReferenceSettings paths_settings;
    paths_settings.samples_per_pass = 128;
    paths_settings.caustics.photons_per_pass = 100'000;
    ReferenceIntegrator paths(*level.scene, paths_settings);
    paths.run_pass(jobs);
    ReferenceIntegrator photons(*level.scene, photon_settings(1'000'000, 1));
    photons.run_pass(jobs);
    const double by_paths = area_weighted_total(paths, Component::Indirect);
    const double by_photons = area_weighted_total(photons, Component::Indirect);
    // The indirect power on all light-mapped surfaces: the paths' noise (rel. std. error
    // ~0.3 per texel at 128 spp) averages to about 1% over 8,722 texels; 3%.
    EXPECT_NEAR(by_photons / by_paths, 1.0, 0.03);
    // Same work, far less noise: the point of the photon estimate.
    EXPECT_LT(photons.relative_standard_error(Component::Indirect),
              0.5 * paths.relative_standard_error(Component::Indirect));
    std::printf(
        "[ figures  ] cornell indirect power photons/paths %.4f; rel. std. error "
        "photons (1e6) %.4f, paths (128 spp) %.4f\n",
        by_photons / by_paths, photons.relative_standard_error(Component::Indirect),
        paths.relative_standard_error(Component::Indirect));
}

TEST(IndirectPhotons, StandardErrorFallsAsOneOverSqrtPhotons) {
    luxel::testing::ReferenceLevel level("cornell");
    JobSystem jobs(2);
    ReferenceIntegrator integrator(*level.scene, photon_settings(100'000, 1));
    integrator.run_pass(jobs);
    const double one = integrator.relative_standard_error(Component::Indirect);
    for (int pass = 1; pass < 4; ++pass) {
        integrator.run_pass(jobs);
    }
    const double four = integrator.relative_standard_error(Component::Indirect);
    EXPECT_NEAR(one / four, 2.0, 0.2);
    std::printf("[ figures  ] photon rel. std. error at 1e5, 4e5: %.4f %.4f (ratio %.3f)\n", one,
                four, one / four);
}

TEST(IndirectPhotons, ASeedFixesTheEstimateWhateverTheThreadCount) {
    luxel::testing::ReferenceLevel level("cornell");
    const auto run = [&](int threads, std::uint32_t seed) {
        ReferenceSettings settings = photon_settings(70'000, 1);
        settings.indirect_photons.seed = seed;
        ReferenceIntegrator integrator(*level.scene, settings);
        JobSystem jobs(threads);
        integrator.run_pass(jobs);
        return integrator.irradiance(Component::Indirect);
    };
    const auto one = run(1, 7);
    const auto two = run(2, 7);
    const auto other = run(2, 8);
    ASSERT_EQ(one.size(), two.size());
    std::size_t differ = 0;
    for (std::size_t t = 0; t < one.size(); ++t) {
        EXPECT_EQ(one[t], two[t]) << "texel " << t;
        differ += one[t] != other[t] ? 1 : 0;
    }
    EXPECT_GT(differ, one.size() / 2);
}

}  // namespace
