// Stiff and extreme cases (issue 12): each asserts that everything stays finite and that the
// error is bounded, and prints the figure it checks ([ figures ] lines; docs/STABILITY.md).

#include <chrono>
#include <cstdio>

#include <glm/gtc/constants.hpp>

#include "stability_support.hpp"

namespace {

using namespace luxel;
using luxel::testing::for_each_texel;
using luxel::testing::LitLevel;
using luxel::testing::stability_config;

/// The furnace: a closed sphere of albedo rho emitting Le inside. Every point's outgoing
/// radiance is Le / (1 - rho), of which the AIM (light reflected by the wall) holds
/// rho Le / (1 - rho). Russian roulette survives with p = rho, so a photon makes 1 / (1 - rho)
/// hops on average: 2 at 0.5, 1,000 at 0.999 (paths stop at 65,536 interactions whatever).
/// The tolerance: with Russian roulette every hit carries the photon's full power and a path
/// makes a geometric number of hits (mean 1 / (1 - rho), deviation sqrt(rho) / (1 - rho)), so
/// the total stored energy of M photons has a relative deviation of about 1 / sqrt(M) whatever
/// the albedo: 1.8% for the paper's 77 x 40 photons; 6% is a bit over 3 sigma.
struct FurnaceCase {
    float albedo;
    double tolerance;  ///< on the mean AIM radiance over the texels, relative
};

class Furnace : public ::testing::TestWithParam<FurnaceCase> {};

TEST_P(Furnace, RealTimeApproachesLeOverOneMinusRho) {
    const FurnaceCase c = GetParam();
    scene::Scene scene = luxel::testing::load_prepared("furnace");
    scene.materials.at(0).base_color = glm::vec4(glm::vec3(c.albedo), 1.0f);
    const auto started = std::chrono::steady_clock::now();
    LitLevel level(std::move(scene), stability_config(77, 40));
    ASSERT_LE(level.converge(100), 100);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    const double expected = c.albedo * 1.0 / (1.0 - c.albedo);
    double sum = 0.0;
    std::size_t texels = 0;
    for_each_texel(level.lighting->maps(),
                   [&](std::uint32_t, const glm::vec3& aim, const glm::vec3&) {
                       ASSERT_TRUE(luxel::testing::finite_non_negative(aim));
                       sum += aim.g;
                       ++texels;
                   });
    ASSERT_GT(texels, 1000u);
    const double mean = sum / static_cast<double>(texels);
    std::printf(
        "[ figures  ] furnace rho %.3f: mean AIM radiance %.4f, expected %.4f (%.2f%%), "
        "%zu stored hits, %.2f s\n",
        c.albedo, mean, expected, 100.0 * (mean / expected - 1.0),
        level.lighting->stats().stored_hits, seconds);
    EXPECT_NEAR(mean / expected, 1.0, c.tolerance);
}

INSTANTIATE_TEST_SUITE_P(Albedos, Furnace,
                         ::testing::Values(FurnaceCase{0.5f, 0.06}, FurnaceCase{0.9f, 0.06},
                                           FurnaceCase{0.99f, 0.06}, FurnaceCase{0.999f, 0.06}),
                         [](const auto& param_info) {
                             return "rho_" + std::to_string(static_cast<int>(
                                                 param_info.param.albedo * 1000.0f + 0.5f));
                         });

/// Runs the Cornell box with its light's power scaled and returns every texel's AIM value.
std::vector<glm::vec3> cornell_aim(float power_scale, float geometry_scale) {
    scene::Scene scene = luxel::testing::load_prepared("cornell");
    for (auto& light : scene.lights) {
        light.intensity *= power_scale;
    }
    if (geometry_scale != 1.0f) {
        for (int root : scene.roots) {
            auto& node = scene.nodes.at(static_cast<std::size_t>(root));
            node.translation *= geometry_scale;
            node.scale *= geometry_scale;
        }
    }
    LitLevel level(std::move(scene), stability_config(77, 40));
    EXPECT_LE(level.converge(100), 100);
    std::vector<glm::vec3> values;
    for_each_texel(level.lighting->maps(),
                   [&](std::uint32_t, const glm::vec3& aim, const glm::vec3&) {
                       EXPECT_TRUE(luxel::testing::finite_non_negative(aim));
                       values.push_back(aim);
                   });
    return values;
}

double worst_relative(const std::vector<glm::vec3>& values, const std::vector<glm::vec3>& base,
                      double scale) {
    double worst = 0.0;
    for (std::size_t i = 0; i < values.size() && i < base.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            const double b = base[i][c];
            if (b > 0.0) {
                worst = std::max(worst, std::abs(values[i][c] * scale / b - 1.0));
            }
        }
    }
    return worst;
}

TEST(ExtremePowers, LightMapsScaleLinearlyFromMicrowattsToMegawatts) {
    const auto base = cornell_aim(1.0f, 1.0f);
    for (const float scale : {1e-6f, 1e6f}) {
        const auto scaled = cornell_aim(scale, 1.0f);
        ASSERT_EQ(scaled.size(), base.size());
        const double worst = worst_relative(scaled, base, 1.0 / scale);
        std::printf("[ figures  ] light power x %g: worst texel deviation from linear %.2e\n",
                    static_cast<double>(scale), worst);
        EXPECT_LE(worst, 1e-5);
    }
}

TEST(ExtremeScales, TheCornellBoxScaledGivesTheSameLightMaps) {
    const auto base = cornell_aim(1.0f, 1.0f);
    // Same power over s^2 the area: irradiance and radiance scale by 1 / s^2.
    for (const float scale : {1e-3f, 1e4f}) {
        const auto scaled = cornell_aim(1.0f, scale);
        ASSERT_EQ(scaled.size(), base.size());
        double num = 0.0;
        double den = 0.0;
        for (std::size_t i = 0; i < base.size(); ++i) {
            const glm::dvec3 d =
                glm::dvec3(scaled[i]) * static_cast<double>(scale) * static_cast<double>(scale) -
                glm::dvec3(base[i]);
            num += glm::dot(d, d);
            den += glm::dot(glm::dvec3(base[i]), glm::dvec3(base[i]));
        }
        const double rel_rmse = den > 0.0 ? std::sqrt(num / den) : 0.0;
        std::printf("[ figures  ] Cornell box x %g: light-map relRMSE against x 1 = %.2e\n",
                    static_cast<double>(scale), rel_rmse);
        EXPECT_LE(rel_rmse, 1e-3);
    }
}

TEST(Geometry, ThousandsOfPhotonsAtOnePointStayFinite) {
    scene::Scene scene = luxel::testing::load_prepared("cornell");
    LitLevel level(std::move(scene), stability_config(4, 4));
    ASSERT_LE(level.converge(50), 50);
    // 5,000 photons of 1 mW each piled on one point of surface 0.
    lighting::PhotonMap& map = level.lighting->photons().photon_map();
    const std::uint32_t group = map.add_groups(1);
    lighting::TracedGroup traced;
    traced.starts.push_back(0);
    const glm::vec3 point = level.lighting->maps().world_texels(0).at(10).position;
    for (int i = 0; i < 5000; ++i) {
        traced.hops.push_back({point, glm::vec3(1e-3f), 0, lighting::kNoObject, 0});
        traced.starts.push_back(static_cast<std::uint32_t>(traced.hops.size()));
    }
    map.replace_group(group, traced);
    ASSERT_LE(level.converge(50), 50);
    double peak = 0.0;
    for_each_texel(level.lighting->maps(),
                   [&](std::uint32_t, const glm::vec3& aim, const glm::vec3& iim) {
                       ASSERT_TRUE(luxel::testing::finite_non_negative(aim));
                       ASSERT_TRUE(luxel::testing::finite_non_negative(iim));
                       peak = std::max(peak, static_cast<double>(aim.g));
                   });
    // Bounded by N photons' power over the floor radius (1/1000 of the cap) disc.
    std::printf("[ figures  ] 5,000 photons at one point: peak AIM radiance %.3g W/(m^2 sr)\n",
                peak);
    EXPECT_GT(peak, 1.0);
    EXPECT_LT(peak, 1e9);
}

TEST(Budgets, ExtremeBudgetsStayFiniteAndProgress) {
    for (const double budget : {0.0, 0.01, 1000.0}) {
        LitLevel level(luxel::testing::load_prepared("cornell"), stability_config(77, 40), true);
        std::uint64_t units = 0;
        for (int i = 0; i < 120; ++i) {
            units += level.frame(budget).schedule.units_done;
        }
        std::printf("[ figures  ] budget %g ms: %llu units in 120 animated frames\n", budget,
                    static_cast<unsigned long long>(units));
        if (budget == 0.0) {
            EXPECT_EQ(units, 0u);  // paused
        } else {
            // Even 0.01 ms makes progress: a unit that waited 30 frames runs (at most one a
            // frame, when it is first in line), so every queue moves; after the first 30
            // frames that is at least one unit every few frames.
            EXPECT_GE(units, 30u);
        }
        for_each_texel(level.lighting->maps(),
                       [&](std::uint32_t, const glm::vec3& aim, const glm::vec3& iim) {
                           ASSERT_TRUE(luxel::testing::finite_non_negative(aim));
                           ASSERT_TRUE(luxel::testing::finite_non_negative(iim));
                       });
    }
}

TEST(PhotonCounts, OneGroupOfOnePhotonAndHugeGroups) {
    for (const auto& [groups, per_group] : {std::pair{1u, 1u}, std::pair{1u, 1'000'000u}}) {
        LitLevel level(luxel::testing::load_prepared("cornell"),
                       stability_config(groups, per_group));
        ASSERT_LE(level.converge(100), 100) << level.pending();
        std::size_t texels = 0;
        for_each_texel(level.lighting->maps(),
                       [&](std::uint32_t, const glm::vec3& aim, const glm::vec3& iim) {
                           ASSERT_TRUE(luxel::testing::finite_non_negative(aim));
                           ASSERT_TRUE(luxel::testing::finite_non_negative(iim));
                           ++texels;
                       });
        std::printf("[ figures  ] %u group(s) of %u photons: %zu stored hits, %zu texels finite\n",
                    groups, per_group, level.lighting->stats().stored_hits, texels);
        EXPECT_GT(texels, 0u);
    }
}

}  // namespace
