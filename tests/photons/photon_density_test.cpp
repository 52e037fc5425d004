// The AIM density estimate: uniform densities come back, sparse regions stay finite, corners do
// not leak through the disc filter, indirect-only selects bounced photons.

#include <cmath>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "luxel/lighting/core/halton.hpp"
#include "luxel/lighting/core/photon_density.hpp"

namespace {

using namespace luxel::lighting;

/// Stores `hops` on one group of a fresh map (one photon per hop).
PhotonMap map_with(std::uint32_t surfaces, const std::vector<TracedHop>& hops) {
    PhotonMap map(surfaces, 1);
    TracedGroup group;
    group.hops = hops;
    for (std::uint32_t i = 0; i <= hops.size(); ++i) {
        group.starts.push_back(i);
    }
    map.replace_group(0, group);
    return map;
}

/// 40,000 photons spread over the 2 m x 2 m square of the plane y = 0 as the tracer spreads
/// them, quasi-randomly (Halton points, bases 2 and 3, from `first`), each carrying `power`.
std::vector<TracedHop> floor_photons(float power, std::int32_t surface, std::uint32_t bounces,
                                     std::uint64_t first = 1) {
    std::vector<TracedHop> hops;
    for (std::uint64_t i = first; i < first + 40'000; ++i) {
        const glm::dvec2 u = halton2(i);
        hops.push_back({{-1.0f + 2.0f * float(u.x), 0.0f, -1.0f + 2.0f * float(u.y)},
                        glm::vec3(power),
                        surface,
                        kNoObject,
                        bounces});
    }
    return hops;
}

TEST(PhotonDensity, AUniformDensityIsRecovered) {
    // 1e-4 W per 1 cm^2 cell: E = 1 W/m^2.
    const PhotonMap map = map_with(1, floor_photons(1e-4f, 0, 0));
    const std::uint32_t surfaces[] = {0};
    const PhotonDensity density(map, surfaces, PhotonSelection::Full);
    EXPECT_EQ(density.photon_count(), 40'000u);
    for (const glm::vec3 at :
         {glm::vec3(0.0f), glm::vec3(0.3f, 0.0f, -0.41f), glm::vec3(-0.7f, 0.0f, 0.66f)}) {
        const glm::vec3 e = density.irradiance(at, {0, 1, 0}, {});
        // N = 50: the estimator's relative spread is about 1/sqrt(N) for random photons, and
        // far smaller for these low-discrepancy ones.
        EXPECT_NEAR(e.r, 1.0f, 0.05f) << at.x << " " << at.z;
        // Radiance of a 0.5-albedo Lambertian surface: rho E / pi.
        EXPECT_NEAR(density.radiance(at, {0, 1, 0}, glm::vec3(0.5f), {}).g,
                    0.5f * e.g / glm::pi<float>(), 1e-6f);
    }
}

TEST(PhotonDensity, FewerThanNPhotonsUseTheCappedRadiusAndNoneGiveZero) {
    const PhotonMap map =
        map_with(1, {{glm::vec3(0.0f), glm::vec3(2.0f), 0, kNoObject, 0},
                     {glm::vec3(0.1f, 0.0f, 0.0f), glm::vec3(1.0f), 0, kNoObject, 0}});
    const std::uint32_t surfaces[] = {0};
    const PhotonDensity density(map, surfaces, PhotonSelection::Full);
    DensitySettings settings;
    settings.max_radius = 0.5f;
    settings.kernel = DensityKernel::Disc;  // equal weights, so the sum is exact
    const glm::vec3 e = density.irradiance({0.05f, 0.0f, 0.0f}, {0, 1, 0}, settings);
    EXPECT_NEAR(e.r, 3.0f / (glm::pi<float>() * 0.25f), 1e-5f);  // both photons, r = the cap
    // Far away: nothing within the cap.
    EXPECT_EQ(density.irradiance({5.0f, 0.0f, 0.0f}, {0, 1, 0}, settings), glm::vec3(0.0f));

    const PhotonMap empty(1, 1);
    const PhotonDensity nothing(empty, surfaces, PhotonSelection::Full);
    const glm::vec3 zero = nothing.irradiance(glm::vec3(0.0f), {0, 1, 0}, settings);
    EXPECT_EQ(zero, glm::vec3(0.0f));
    EXPECT_FALSE(std::isnan(zero.r));
}

TEST(PhotonDensity, TheDiscFilterKeepsAWallOutOfTheFloorAtACorner) {
    // Floor photons (surface 0) and a bright wall (surface 1) standing on the floor at x = 0.
    std::vector<TracedHop> hops = floor_photons(1e-4f, 0, 0);
    for (int i = 0; i < 200; ++i) {
        for (int j = 0; j < 200; ++j) {
            hops.push_back({{0.0f, 0.01f * (i + 0.5f), -1.0f + 0.01f * (j + 0.5f)},
                            glm::vec3(1e-2f),
                            1,
                            kNoObject,
                            0});
        }
    }
    const PhotonMap map = map_with(2, hops);
    const std::uint32_t both[] = {0, 1};
    const PhotonDensity density(map, both, PhotonSelection::Full);
    // Near the corner, on the floor: the wall's photons are within r but off the floor's plane;
    // with the disc filter the estimate stays near the floor's 1 W/m^2, not the wall's 100.
    DensitySettings thin;
    thin.disc_thickness = 0.1f;
    const glm::vec3 e = density.irradiance({0.03f, 0.0f, 0.0f}, {0, 1, 0}, thin);
    EXPECT_LT(e.r, 1.5f);
    EXPECT_GT(e.r, 0.5f);
    DensitySettings no_filter;
    no_filter.disc_thickness = 1e9f;
    no_filter.kernel = DensityKernel::Disc;
    EXPECT_GT(density.irradiance({0.03f, 0.0f, 0.0f}, {0, 1, 0}, no_filter).r, 10.0f);
}

TEST(PhotonDensity, IndirectOnlySelectsBouncedPhotons) {
    std::vector<TracedHop> hops = floor_photons(1e-4f, 0, 0);
    const std::vector<TracedHop> bounced = floor_photons(3e-4f, 0, 2, 40'001);
    hops.insert(hops.end(), bounced.begin(), bounced.end());
    const PhotonMap map = map_with(1, hops);
    const std::uint32_t surfaces[] = {0};
    const PhotonDensity full(map, surfaces, PhotonSelection::Full);
    const PhotonDensity indirect(map, surfaces, PhotonSelection::IndirectOnly);
    EXPECT_EQ(full.photon_count(), 80'000u);
    EXPECT_EQ(indirect.photon_count(), 40'000u);
    // Two interleaved photon populations of different power: their share among the N nearest
    // varies, so this estimate uses more neighbours.
    DensitySettings wide;
    wide.nearest = 200;
    EXPECT_NEAR(indirect.irradiance(glm::vec3(0.0f), {0, 1, 0}, wide).r, 3.0f, 0.15f);
    EXPECT_NEAR(full.irradiance(glm::vec3(0.0f), {0, 1, 0}, wide).r, 4.0f, 0.2f);
}

}  // namespace
