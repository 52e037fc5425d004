// The ground below the horizon (lighting::with_ground, issue 20): a flat diffuse ground of
// albedo rho lit by the sky above it and by a sun stands in for the world outside a level's
// windows. Closed forms: under a uniform sky of radiance L the ground's radiance is rho L, so a
// face looking straight down receives pi rho L; with a sun of irradiance E_s at elevation a the
// ground adds rho E_s sin(a) / pi. The sky above the horizon is left as it was.

#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "luxel/lighting/core/sky_radiance.hpp"

namespace {

using namespace luxel;
using lighting::SkyRadiance;

constexpr double kPi = glm::pi<double>();

/// Irradiance on a face with normal `normal`, by the sky's own importance sampling (a
/// stratified sequence over the cells and a golden-ratio one within them).
glm::dvec3 irradiance_by_sampling(const SkyRadiance& sky, const glm::vec3& normal, int samples) {
    glm::dvec3 sum(0.0);
    for (int i = 0; i < samples; ++i) {
        const SkyRadiance::Sample s =
            sky.sample({(i + 0.5) / samples, std::fmod(i * 0.7548776662466927, 1.0)});
        const double cosine = glm::dot(s.direction, normal);
        if (cosine > 0.0 && s.pdf > 0.0) {
            sum += glm::dvec3(s.radiance) * (cosine / s.pdf);
        }
    }
    return sum / static_cast<double>(samples);
}

TEST(SkyGround, TheUpperHemispheresIrradianceIsExactForConstantCells) {
    const glm::vec3 radiance(0.5f, 1.0f, 2.0f);
    const glm::dvec3 e = lighting::horizontal_irradiance(SkyRadiance::uniform(radiance));
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(e[c], kPi * radiance[c], 1e-6 * kPi * radiance[c]) << c;
    }
    // A daylight sky is scaled to give its asked-for luminance by the same cell integrals.
    const glm::dvec3 day = lighting::horizontal_irradiance(
        lighting::daylight_sky(glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f)), 3.0f, 2.0f));
    EXPECT_NEAR(0.2126 * day.r + 0.7152 * day.g + 0.0722 * day.b, 2.0, 1e-4);
}

TEST(SkyGround, AUniformSkysGroundHasRadianceRhoLAndADownwardFaceGetsPiRhoL) {
    const glm::vec3 radiance(0.5f, 1.0f, 2.0f);
    const glm::vec3 albedo(0.2f, 0.3f, 0.1f);
    const SkyRadiance sky = lighting::with_ground(SkyRadiance::uniform(radiance), albedo, {});
    const glm::vec3 below = sky.radiance({0.2f, -0.9f, 0.1f});
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(below[c], albedo[c] * radiance[c], 1e-5f) << c;
    }
    EXPECT_EQ(sky.radiance({0.2f, 0.9f, 0.1f}), radiance);  // the sky itself is unchanged
    const glm::dvec3 down = irradiance_by_sampling(sky, {0.0f, -1.0f, 0.0f}, 40'000);
    const glm::dvec3 up = irradiance_by_sampling(sky, {0.0f, 1.0f, 0.0f}, 40'000);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(down[c], kPi * albedo[c] * radiance[c], 2e-3 * kPi * radiance[c]) << c;
        EXPECT_NEAR(up[c], kPi * radiance[c], 2e-3 * kPi * radiance[c]) << c;
    }
    // The sky's flux grows by the ground's: 2 pi rho L more over the lower hemisphere.
    EXPECT_NEAR(sky.integral().g, 2.0 * kPi * (radiance.g + albedo.g * radiance.g), 1e-5);
}

TEST(SkyGround, TheSunLightsTheGroundAtItsElevation) {
    const glm::vec3 towards_sun = glm::normalize(glm::vec3(0.0f, 0.5f, 1.0f));
    const SkyRadiance clear = lighting::daylight_sky(towards_sun, 3.0f, 1.5f);
    const glm::vec3 albedo(0.25f);
    const glm::vec3 sun(4.0f, 3.5f, 3.0f);
    const glm::vec3 on_ground = sun * towards_sun.y;
    const SkyRadiance sky = lighting::with_ground(clear, albedo, on_ground);
    const glm::dvec3 e_sky = lighting::horizontal_irradiance(clear);
    const glm::vec3 below = sky.radiance({-0.3f, -0.4f, 0.5f});
    for (int c = 0; c < 3; ++c) {
        const double want = albedo[c] * (e_sky[c] + on_ground[c]) / kPi;
        EXPECT_NEAR(below[c], want, 1e-5 * want) << c;
    }
    // Above the horizon every cell is the clear sky's.
    for (int row = 0; row < sky.height() / 2; ++row) {
        for (int col = 0; col < sky.width(); ++col) {
            const std::size_t i = static_cast<std::size_t>(row * sky.width() + col);
            ASSERT_EQ(sky.cells()[i], clear.cells()[i]) << row << " " << col;
        }
    }
    EXPECT_EQ(clear.radiance({-0.3f, -0.4f, 0.5f}), glm::vec3(0.0f));
}

TEST(SkyGround, ARowAcrossTheHorizonKeepsItsRadianceAndBadAlbedosAreClamped) {
    // Three rows: the middle one straddles the horizon and is kept; only the last is ground.
    const SkyRadiance odd(1, 3, {glm::vec3(1.0f), glm::vec3(0.5f), glm::vec3(0.0f)});
    const SkyRadiance grounded = lighting::with_ground(odd, glm::vec3(0.5f), {});
    EXPECT_EQ(grounded.cells()[1], glm::vec3(0.5f));
    EXPECT_GT(grounded.cells()[2].g, 0.0f);
    const float nan = std::nanf("");
    const float inf = std::numeric_limits<float>::infinity();
    const SkyRadiance bad = lighting::with_ground(SkyRadiance::uniform(glm::vec3(1.0f)),
                                                  glm::vec3(nan, 7.0f, -1.0f), glm::vec3(inf));
    const glm::vec3 below = bad.radiance({0.0f, -1.0f, 0.0f});
    EXPECT_EQ(below.r, 0.0f);  // NaN albedo: black
    EXPECT_EQ(below.b, 0.0f);  // negative albedo: black
    EXPECT_TRUE(std::isfinite(below.g));
    EXPECT_NEAR(below.g, 1.0f, 1e-5f);  // albedo 7 taken as 1, an infinite sun as none
    EXPECT_TRUE(std::isfinite(bad.integral().g));
}

}  // namespace
