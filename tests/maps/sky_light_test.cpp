// The sky (issue 20): SkyRadiance's sampling against its own density, and a sky lighting the
// real-time maps. Closed forms: a plane under a uniform sky of radiance L receives pi L
// everywhere on top, so its AIM (photons) holds rho L and its IIM (gather rays that all leave
// the level) pi L; a plane inside a closed box receives nothing at all.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "cube_scene.hpp"
#include "luxel/ecs/transform_system.hpp"
#include "luxel/lighting/components.hpp"
#include "luxel/lighting/core/lighting_system.hpp"
#include "luxel/lighting/core/sky_radiance.hpp"
#include "luxel/lighting/sky_portal.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/runtime/jobs.hpp"
#include "map_test_scenes.hpp"

namespace {

using namespace luxel;
using lighting::SkyRadiance;

constexpr double kPi = glm::pi<double>();

/// A 16 x 8 sky with a bright patch, a dim band and a black cell: uneven enough that sampling
/// by the wrong density would show.
SkyRadiance uneven_sky() {
    std::vector<glm::vec3> cells(16 * 8, glm::vec3(0.2f, 0.3f, 0.5f));
    cells[2 * 16 + 5] = glm::vec3(40.0f, 30.0f, 20.0f);
    for (int col = 0; col < 16; ++col) {
        cells[6 * 16 + col] = glm::vec3(0.01f);
    }
    cells[7 * 16 + 3] = glm::vec3(0.0f);
    return SkyRadiance(16, 8, std::move(cells));
}

TEST(SkyRadiance, SamplesAgreeWithTheDensityAndEstimateTheIntegral) {
    const SkyRadiance sky = uneven_sky();
    // Radiance / pdf averaged over samples estimates the integral; with sampling proportional
    // to the channel sum every sample of this sky gives the same sum, so the estimate of the
    // summed channels is exact for each sample.
    const glm::dvec3 integral = sky.integral();
    const double want = integral.x + integral.y + integral.z;
    glm::dvec3 mean(0.0);
    constexpr int kSamples = 20'000;
    for (int i = 0; i < kSamples; ++i) {
        const glm::dvec2 u((i + 0.5) / kSamples, std::fmod(i * 0.6180339887498949, 1.0));
        const SkyRadiance::Sample s = sky.sample(u);
        ASSERT_GT(s.pdf, 0.0);
        ASSERT_NEAR(glm::length(s.direction), 1.0f, 1e-5f);
        // The direction lies in the cell it was drawn from: the density there is the same.
        ASSERT_NEAR(sky.pdf(s.direction), s.pdf, 1e-9 * s.pdf) << "sample " << i;
        ASSERT_EQ(sky.radiance(s.direction), s.radiance);
        const glm::dvec3 estimate = glm::dvec3(s.radiance) / s.pdf;
        ASSERT_NEAR(estimate.x + estimate.y + estimate.z, want, 1e-9 * want);
        mean += estimate / static_cast<double>(kSamples);
    }
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(mean[c], integral[c], 0.01 * integral[c]) << "channel " << c;
    }
    // The density integrates to one over the sphere: constant on each cell, so the sum over
    // cells of the density at the cell's centre times its solid angle.
    double total = 0.0;
    for (int r = 0; r < sky.height(); ++r) {
        const double top = kPi * r / sky.height();
        const double bottom = kPi * (r + 1) / sky.height();
        const double theta = 0.5 * (top + bottom);
        for (int c = 0; c < sky.width(); ++c) {
            const double phi = 2.0 * kPi * (c + 0.5) / sky.width();
            const glm::vec3 w(static_cast<float>(std::sin(theta) * std::cos(phi)),
                              static_cast<float>(std::cos(theta)),
                              static_cast<float>(std::sin(theta) * std::sin(phi)));
            total += sky.pdf(w) * (std::cos(top) - std::cos(bottom)) * 2.0 * kPi / sky.width();
        }
    }
    EXPECT_NEAR(total, 1.0, 1e-9);
}

TEST(SkyRadiance, UniformSkyGivesPiLOnAnUpwardFaceAndNothingBelowTheHorizon) {
    const glm::vec3 radiance(0.5f, 1.0f, 2.0f);
    const SkyRadiance sky = SkyRadiance::uniform(radiance);
    EXPECT_EQ(sky.radiance({0.3f, 0.8f, -0.2f}), radiance);
    EXPECT_EQ(sky.radiance({0.3f, -0.8f, -0.2f}), glm::vec3(0.0f));
    // Its integral is the upper hemisphere's 2 pi sr.
    EXPECT_NEAR(sky.integral().y, 2.0 * kPi, 1e-9);
    // Irradiance on an upward face: radiance cos / pdf averaged over samples.
    glm::dvec3 irradiance(0.0);
    constexpr int kSamples = 40'000;
    for (int i = 0; i < kSamples; ++i) {
        const SkyRadiance::Sample s =
            sky.sample({(i + 0.5) / kSamples, std::fmod(i * 0.7548776662466927, 1.0)});
        ASSERT_GE(s.direction.y, 0.0f);
        irradiance += glm::dvec3(s.radiance) * (static_cast<double>(s.direction.y) / s.pdf) /
                      static_cast<double>(kSamples);
    }
    EXPECT_NEAR(irradiance.y, kPi, 1e-3 * kPi);
}

TEST(SkyRadiance, BadCellsReadAsBlackAndBadSizesAreRefused) {
    const float nan = std::nanf("");
    const float inf = std::numeric_limits<float>::infinity();
    const SkyRadiance sky(2, 1, {glm::vec3(nan, -1.0f, inf), glm::vec3(1.0f)});
    EXPECT_EQ(sky.cells()[0], glm::vec3(0.0f));
    EXPECT_TRUE(std::isfinite(sky.integral().x));
    EXPECT_EQ(sky.radiance(glm::vec3(nan)), glm::vec3(0.0f));
    EXPECT_EQ(sky.radiance(glm::vec3(0.0f)), glm::vec3(0.0f));
    EXPECT_EQ(sky.pdf(glm::vec3(inf, 0.0f, 0.0f)), 0.0);
    EXPECT_EQ(SkyRadiance(1, 1, {glm::vec3(3e38f)}).cells()[0],
              glm::vec3(SkyRadiance::kMaxRadiance));
    const auto clamp = [](float scale) {
        return lighting::SkyLight{nullptr, scale, true}.effective_scale();
    };
    EXPECT_EQ(clamp(2.0f), 2.0f);
    EXPECT_EQ(clamp(-1.0f), 0.0f);
    EXPECT_EQ(clamp(nan), 0.0f);
    EXPECT_EQ(clamp(inf), 1e6f);
    EXPECT_THROW(SkyRadiance(3, 2, std::vector<glm::vec3>(5)), Error);
    EXPECT_THROW(SkyRadiance(0, 2, {}), Error);
    EXPECT_THROW(SkyRadiance(1 << 20, 1 << 20, {}), Error);  // refused before allocating
    const SkyRadiance black;
    EXPECT_TRUE(black.black());
    EXPECT_EQ(black.sample({0.5, 0.5}).pdf, 0.0);
}

TEST(SkyRadiance, ADaylightSkyGivesTheIrradianceAskedForAndIsBrightestByTheSun) {
    const glm::vec3 towards_sun = glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f));  // 45 degrees up
    const SkyRadiance sky = lighting::daylight_sky(towards_sun, 3.0f, 2.0f);
    // Irradiance on an upward face, by the sky's own sampling: its luminance is 2 W/m^2.
    glm::dvec3 irradiance(0.0);
    constexpr int kSamples = 200'000;
    for (int i = 0; i < kSamples; ++i) {
        const SkyRadiance::Sample s =
            sky.sample({(i + 0.5) / kSamples, std::fmod(i * 0.7548776662466927, 1.0)});
        if (s.direction.y > 0.0f) {
            irradiance += glm::dvec3(s.radiance) * (static_cast<double>(s.direction.y) / s.pdf) /
                          static_cast<double>(kSamples);
        }
    }
    const double luminance = 0.2126 * irradiance.r + 0.7152 * irradiance.g + 0.0722 * irradiance.b;
    std::printf(
        "[ figures  ] daylight sky, sun 45 degrees up, T 3: horizontal irradiance %.4f "
        "(asked 2), RGB %.3f %.3f %.3f\n",
        luminance, irradiance.r, irradiance.g, irradiance.b);
    EXPECT_NEAR(luminance, 2.0, 0.01);
    // A clear sky is blue: more blue than red in the light it gives.
    EXPECT_GT(irradiance.b, irradiance.r);
    // Brightest round the sun, dimmest 90 degrees from it (the Perez minimum), black below.
    const glm::vec3 by_sun = sky.radiance(glm::normalize(towards_sun + glm::vec3(0, 0.1f, 0)));
    const glm::vec3 across = sky.radiance(glm::normalize(glm::vec3(-1.0f, 1.0f, 0.0f)));
    EXPECT_GT(by_sun.g, 3.0f * across.g);
    EXPECT_EQ(sky.radiance({0.3f, -0.5f, 0.2f}), glm::vec3(0.0f));
    // Stiff inputs still give a finite sky: a sun under the horizon, a zero or NaN direction,
    // turbidity and irradiance out of range.
    for (const glm::vec3& sun :
         {glm::vec3(1.0f, -0.2f, 0.0f), glm::vec3(0.0f), glm::vec3(std::nanf(""))}) {
        for (const float turbidity : {0.0f, 50.0f, std::nanf("")}) {
            const SkyRadiance stiff = lighting::daylight_sky(sun, turbidity, 1.0f);
            const glm::dvec3 integral = stiff.integral();
            EXPECT_TRUE(std::isfinite(integral.x + integral.y + integral.z));
            EXPECT_GT(integral.g, 0.0);
        }
    }
    EXPECT_TRUE(lighting::daylight_sky(towards_sun, 3.0f, -1.0f).black());
    EXPECT_TRUE(lighting::daylight_sky(towards_sun, 3.0f, std::nanf("")).black());
}

/// A light-mapped plane (6 x 6 m at 0.25 m texels, albedo 0.5) lit by a uniform sky, with the
/// lighting system over it; optionally shut in a closed box.
struct SkyPlane {
    static constexpr float kSide = 6.0f;
    ecs::Registry registry;
    ecs::TransformSystem transforms{registry};
    JobSystem jobs{2};
    std::unique_ptr<lighting::LightingSystem> lighting;
    ecs::Entity sky;
    ecs::Entity portal = ecs::null_entity;
    double time = 0.0;

    /// `portal_height` > 0: a SkyPortal as large as the plane, that high above it.
    SkyPlane(const glm::vec3& radiance, bool shut, float portal_height = 0.0f) {
        const ecs::Entity plane = registry.create();
        registry.emplace<scene::MeshInstance>(
            plane, luxel::testing::lightmapped_plane(kSide, 8, 0.25f, 64, glm::vec3(0.5f)), 0);
        scene::LightmapLayout layout;
        layout.texel_size = 0.25f;
        layout.page_size = 64;
        scene::LightmapSurface surface;
        surface.id = 0;
        surface.primitive = 0;
        surface.rect = {2, 2, 24, 24};
        surface.charts = {surface.rect};
        surface.area = static_cast<double>(kSide) * kSide;
        surface.texels = 24 * 24;
        layout.surfaces.push_back(surface);
        registry.emplace<lighting::LightmappedSurface>(plane, layout);
        registry.emplace<ecs::Transform>(plane, ecs::Transform{});
        if (shut) {
            const ecs::Entity box = registry.create();
            registry.emplace<scene::MeshInstance>(
                box, luxel::testing::cube_scene(kSide, luxel::testing::diffuse_material(0.5f)), 0);
            ecs::Transform t;
            t.translation = glm::vec3(0.5f * kSide, 0.0f, 0.5f * kSide);
            registry.emplace<ecs::Transform>(box, t);
        }
        if (portal_height > 0.0f) {
            portal = registry.create();
            const float h = portal_height;
            registry.emplace<lighting::SkyPortal>(portal, lighting::SkyPortal{{{0, h, 0},
                                                                               {0, h, kSide},
                                                                               {kSide, h, kSide},
                                                                               {0, h, 0},
                                                                               {kSide, h, kSide},
                                                                               {kSide, h, 0}},
                                                                              true});
            registry.emplace<ecs::Transform>(portal, ecs::Transform{});
        }
        sky = registry.create();
        registry.emplace<lighting::SkyLight>(
            sky,
            lighting::SkyLight{std::make_shared<const SkyRadiance>(SkyRadiance::uniform(radiance)),
                               1.0f, true});
        transforms.update();
        // 8,192 photons; converged once every group has been probed (32 frames).
        lighting = std::make_unique<lighting::LightingSystem>(
            registry, jobs, luxel::testing::closed_form_config(256, 32));
    }

    int converge() { return luxel::testing::converge(transforms, *lighting, time); }

    [[nodiscard]] std::size_t photon_hits() const {
        return lighting->photons().photon_map().stored_hit_count();
    }

    /// Per texel of the plane: the AIM's reflected radiance and the IIM's irradiance (green).
    struct Texels {
        std::vector<double> aim;
        std::vector<double> iim;
        std::vector<glm::ivec2> at;  ///< page texel
    };
    [[nodiscard]] Texels texels() const {
        const auto& maps = lighting->maps();
        Texels out;
        const lighting::MapSurface& surface = maps.surfaces()[0];
        const std::int32_t page = maps.aim().surface_page.at(0);
        EXPECT_GE(page, 0);
        const auto& aim = maps.aim().pages.at(static_cast<std::size_t>(page));
        const auto& iim = maps.iim_pages()[static_cast<std::size_t>(page)].current;
        const double to_irradiance = surface.content == lighting::IimContent::Radiance
                                         ? kPi / static_cast<double>(surface.albedo.g)
                                         : 1.0;
        for (const auto& texel : surface.texels.texels) {
            out.aim.push_back(aim.at(texel.x, texel.y).g);
            out.at.emplace_back(texel.x, texel.y);
            out.iim.push_back(iim.at(texel.x, texel.y).g * to_irradiance);
        }
        return out;
    }
};

double mean_of(const std::vector<double>& values) {
    double sum = 0.0;
    for (const double v : values) {
        sum += v;
    }
    return values.empty() ? 0.0 : sum / static_cast<double>(values.size());
}

TEST(SkyLightMaps, APlaneUnderAUniformSkyGetsPiLFromPhotonsAndGathers) {
    const float radiance = 0.8f;
    SkyPlane world(glm::vec3(radiance), false);
    ASSERT_LE(world.converge(), 100);
    const SkyPlane::Texels texels = world.texels();
    ASSERT_EQ(texels.iim.size(), 24u * 24u);
    // Every gather ray from the plane's top leaves the level: exactly pi L, up to float sums.
    const double irradiance = kPi * radiance;
    for (const double e : texels.iim) {
        ASSERT_NEAR(e, irradiance, 1e-4 * irradiance);
    }
    // The photons' estimate of the reflected radiance rho E / pi = rho L, within their noise
    // (8,192 photons, about a third of them landing on the plane: under 2% on the mean).
    const double aim = mean_of(texels.aim);
    std::printf(
        "[ figures  ] uniform sky L %.2f over a plane: IIM E %.5f (pi L %.5f), AIM mean "
        "%.5f (rho L %.5f, %+.2f%%)\n",
        radiance, mean_of(texels.iim), irradiance, aim, 0.5 * radiance,
        100.0 * (aim / (0.5 * radiance) - 1.0));
    EXPECT_NEAR(aim, 0.5 * radiance, 0.04 * 0.5 * radiance);
    // Where a user would see it: the mean of every 6 x 6 texel region (1.5 m), the plane's
    // edges and corners included, where a density estimate that lost the photons beyond the
    // border would show dark.
    constexpr int kRegion = 6;
    std::vector<double> sums(16, 0.0);
    std::vector<int> counts(16, 0);
    for (std::size_t t = 0; t < texels.aim.size(); ++t) {
        const int region = ((texels.at[t].y - 2) / kRegion) * 4 + (texels.at[t].x - 2) / kRegion;
        ASSERT_GE(region, 0);
        ASSERT_LT(region, 16);
        sums[static_cast<std::size_t>(region)] += texels.aim[t];
        ++counts[static_cast<std::size_t>(region)];
    }
    double worst = 0.0;
    for (std::size_t r = 0; r < sums.size(); ++r) {
        ASSERT_EQ(counts[r], kRegion * kRegion);
        worst = std::max(worst, std::abs(sums[r] / counts[r] / (0.5 * radiance) - 1.0));
    }
    std::printf(
        "[ figures  ] uniform sky over a plane: worst 1.5 m region of the AIM %.2f%% "
        "from rho L\n",
        100.0 * worst);
    EXPECT_LT(worst, 0.15);
}

/// The worst mean over the 16 regions of 6 x 6 texels (1.5 m) of `values`, relative to `expected`.
double worst_region(const SkyPlane::Texels& texels, const std::vector<double>& values,
                    double expected) {
    constexpr int kRegion = 6;
    std::vector<double> sums(16, 0.0);
    for (std::size_t t = 0; t < values.size(); ++t) {
        const int region = ((texels.at[t].y - 2) / kRegion) * 4 + (texels.at[t].x - 2) / kRegion;
        sums[static_cast<std::size_t>(std::clamp(region, 0, 15))] += values[t];
    }
    double worst = 0.0;
    for (const double sum : sums) {
        worst = std::max(worst, std::abs(sum / (kRegion * kRegion) / expected - 1.0));
    }
    return worst;
}

TEST(SkyLightMaps, APortalOverThePlaneCarriesTheSameLightWithMoreOfItsPhotonsOnThePlane) {
    // A portal 2 cm above the plane, as large as it: every direction the sky lights the plane
    // from passes through it, so the photons that start on it must give rho L as the scene's
    // disc does, but without spending photons beside the plane.
    const float radiance = 0.8f;
    SkyPlane disc(glm::vec3(radiance), false);
    SkyPlane portal(glm::vec3(radiance), false, 0.02f);
    ASSERT_LE(disc.converge(), 100);
    ASSERT_LE(portal.converge(), 100);
    const SkyPlane::Texels texels = portal.texels();
    const double aim = mean_of(texels.aim);
    const double worst = worst_region(texels, texels.aim, 0.5 * radiance);
    std::printf(
        "[ figures  ] uniform sky over a plane, 8,192 photons: from the scene's disc %zu land "
        "on the plane, AIM mean %+.2f%% from rho L; from a portal over it %zu, AIM mean "
        "%+.2f%%, worst 1.5 m region %.2f%%\n",
        disc.photon_hits(), 100.0 * (mean_of(disc.texels().aim) / (0.5 * radiance) - 1.0),
        portal.photon_hits(), 100.0 * (aim / (0.5 * radiance) - 1.0), 100.0 * worst);
    EXPECT_NEAR(aim, 0.5 * radiance, 0.04 * 0.5 * radiance);
    EXPECT_LT(worst, 0.15);
    EXPECT_GT(portal.photon_hits(), 2 * disc.photon_hits());
    // The gathers do not use portals: the IIM is pi L as before.
    for (const double e : texels.iim) {
        ASSERT_NEAR(e, kPi * radiance, 1e-4 * kPi * radiance);
    }
    // A portal switched off: the sky's photons start on the scene's disc again.
    portal.registry.patch<lighting::SkyPortal>(
        portal.portal, [](lighting::SkyPortal& opening) { opening.enabled = false; });
    ASSERT_LE(portal.converge(), 100);
    EXPECT_EQ(portal.photon_hits(), disc.photon_hits());
}

TEST(SkyLightMaps, APortalInsideAClosedBoxLetsNoSkyLightIn) {
    // The portal's photons look back at the sky through the box's lid: not one carries light.
    SkyPlane world(glm::vec3(1.0f), true, 0.5f);
    ASSERT_LE(world.converge(), 100);
    EXPECT_EQ(world.photon_hits(), 0u);
    for (const double a : world.texels().aim) {
        ASSERT_EQ(a, 0.0);
    }
}

TEST(SkyLightMaps, APlaneShutInABoxReceivesNoSkyLightAtAll) {
    SkyPlane world(glm::vec3(1.0f), true);
    ASSERT_LE(world.converge(), 100);
    EXPECT_GT(world.lighting->stats().photons_traced + world.lighting->stats().stored_hits, 0u);
    const SkyPlane::Texels texels = world.texels();
    for (std::size_t t = 0; t < texels.aim.size(); ++t) {
        ASSERT_EQ(texels.aim[t], 0.0) << "texel " << t;
        ASSERT_EQ(texels.iim[t], 0.0) << "texel " << t;
    }
}

TEST(SkyLightMaps, ChangingTheSkyRegathersAndSwitchingItOffClearsTheMaps) {
    SkyPlane world(glm::vec3(0.5f), false);
    ASSERT_LE(world.converge(), 100);
    const double before = mean_of(world.texels().iim);
    world.registry.patch<lighting::SkyLight>(world.sky,
                                             [](lighting::SkyLight& sky) { sky.scale = 2.0f; });
    ASSERT_LE(world.converge(), 100);
    EXPECT_NEAR(mean_of(world.texels().iim) / before, 2.0, 1e-4);
    world.registry.patch<lighting::SkyLight>(world.sky,
                                             [](lighting::SkyLight& sky) { sky.enabled = false; });
    ASSERT_LE(world.converge(), 100);
    const SkyPlane::Texels off = world.texels();
    for (std::size_t t = 0; t < off.aim.size(); ++t) {
        ASSERT_EQ(off.aim[t], 0.0) << "texel " << t;
        ASSERT_EQ(off.iim[t], 0.0) << "texel " << t;
    }
}

}  // namespace
