// Direct light against closed forms on a hand-built plane: a point light (E = I cos / d^2), a
// spot light's falloff, and a square area light (MIS of light and cosine sampling) against
// the form factor of a parallel rectangle.

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "luxel/lighting/reference/reference_integrator.hpp"
#include "scene_builder.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;
using namespace luxel::lighting::reference;

constexpr float kHalf = 2.0f;  // the floor spans 4 x 4 m
constexpr int kSize = 16;      // texels per edge: 0.25 m texels

struct Floor {
    RayScene rays;
    std::vector<TraceMaterial> materials{TraceMaterial{}};

    Floor() {
        rays.add_object(luxel::testing::horizontal_quad(0.0f, kHalf, true, 0, 0), glm::mat4(1.0f),
                        false);
    }
};

TEST(PointLight, DirectIrradianceIsIntensityTimesCosineOverDistanceSquared) {
    Floor floor;
    floor.rays.commit();
    LightSource light;
    light.kind = LightKind::Point;
    light.position = {0.3f, 1.5f, -0.2f};
    light.power = glm::vec3(100.0f, 50.0f, 10.0f);
    ReferenceScene scene(floor.rays, floor.materials, {light},
                         {luxel::testing::quad_texels(0, 0.0f, kHalf, true, kSize)});
    ASSERT_EQ(scene.texel_count(), static_cast<std::size_t>(kSize * kSize));
    for (double area : scene.texel_areas()) {
        EXPECT_NEAR(area, 0.0625, 1e-6);  // (4 m / 16)^2, whole texels
    }
    ReferenceSettings settings;
    settings.samples_per_pass = 4;
    ReferenceIntegrator integrator(scene, settings);
    JobSystem jobs(2);
    integrator.run_pass(jobs);
    const glm::dvec3 intensity = glm::dvec3(light.power) / (4.0 * glm::pi<double>());
    double worst = 0.0;
    for (std::size_t t = 0; t < scene.texel_count(); ++t) {
        const glm::dvec3 to_light =
            glm::dvec3(light.position) - glm::dvec3(scene.texel(t).position);
        const double d2 = glm::dot(to_light, to_light);
        const double cosine = to_light.y / std::sqrt(d2);
        const glm::dvec3 expected = intensity * cosine / d2;
        const glm::dvec3 got = integrator.irradiance(Component::Direct, t);
        for (int c = 0; c < 3; ++c) {
            worst = std::max(worst, std::abs(got[c] / expected[c] - 1.0));
            EXPECT_NEAR(got[c], expected[c], 0.01 * expected[c]) << "texel " << t;
        }
        // A lone plane: nothing comes back, no caustic.
        EXPECT_EQ(integrator.irradiance(Component::Indirect, t), glm::dvec3(0.0));
        EXPECT_EQ(integrator.irradiance(Component::Caustic, t), glm::dvec3(0.0));
    }
    std::printf("[ figures  ] point light over a plane: worst relative error %.2e\n", worst);
}

// A point light with a radius (a sphere of the point's intensity) over the plane: every texel
// sees the whole sphere above its horizon, where the sphere delivers what the point did.
TEST(PointLight, ASphereOfThePointsIntensityDeliversItsIrradiance) {
    Floor floor;
    floor.rays.commit();
    LightSource light;
    light.kind = LightKind::Point;
    light.position = {0.3f, 1.5f, -0.2f};
    light.power = glm::vec3(100.0f);
    light.radius = 0.3f;
    ReferenceScene scene(floor.rays, floor.materials, {light},
                         {luxel::testing::quad_texels(0, 0.0f, kHalf, true, kSize)});
    // The cosine varies across the cone (up to +-20% at the plane's far corners): 1,024
    // directions a texel bring each texel's noise well under the 2% asked.
    ReferenceSettings settings;
    settings.samples_per_pass = 1024;
    ReferenceIntegrator integrator(scene, settings);
    JobSystem jobs(2);
    integrator.run_pass(jobs);
    const double intensity = 100.0 / (4.0 * glm::pi<double>());
    double worst = 0.0;
    for (std::size_t t = 0; t < scene.texel_count(); ++t) {
        const glm::dvec3 to_light =
            glm::dvec3(light.position) - glm::dvec3(scene.texel(t).position);
        const double d2 = glm::dot(to_light, to_light);
        const double expected = intensity * (to_light.y / std::sqrt(d2)) / d2;
        const double got = integrator.irradiance(Component::Direct, t).g;
        worst = std::max(worst, std::abs(got / expected - 1.0));
        EXPECT_NEAR(got, expected, 0.02 * expected) << "texel " << t;
    }
    std::printf("[ figures  ] a 30 cm sphere over a plane: worst relative error %.2e\n", worst);
}

TEST(PointLight, ASpotLightFallsOffAsTheEmitterSays) {
    Floor floor;
    floor.rays.commit();
    LightSource spot;
    spot.kind = LightKind::Spot;
    spot.position = {0.0f, 2.0f, 0.0f};
    spot.direction = {0.0f, -1.0f, 0.0f};
    spot.inner_cone = 0.3f;
    spot.outer_cone = 0.6f;
    spot.power = glm::vec3(60.0f);
    ReferenceScene scene(floor.rays, floor.materials, {spot},
                         {luxel::testing::quad_texels(0, 0.0f, kHalf, true, kSize)});
    ReferenceIntegrator integrator(scene, {});
    JobSystem jobs(2);
    integrator.run_pass(jobs);
    const double i0 = 60.0 / (2.0 * glm::pi<double>() * (1.0 - std::cos(0.6)));
    for (std::size_t t = 0; t < scene.texel_count(); ++t) {
        const glm::dvec3 to_light = glm::dvec3(spot.position) - glm::dvec3(scene.texel(t).position);
        const double d2 = glm::dot(to_light, to_light);
        const double cosine = to_light.y / std::sqrt(d2);
        const double x =
            std::clamp((cosine - std::cos(0.6)) / (std::cos(0.3) - std::cos(0.6)), 0.0, 1.0);
        const double expected = i0 * x * x * (3.0 - 2.0 * x) * cosine / d2;
        EXPECT_NEAR(integrator.irradiance(Component::Direct, t).x, expected, 0.01 * expected + 1e-9)
            << "texel " << t;
    }
}

/// Form factor from a point to a parallel rectangle a x b at height h above one corner.
double corner_form_factor(double a, double b, double h) {
    const double x = a / h;
    const double y = b / h;
    const double sx = std::sqrt(1.0 + x * x);
    const double sy = std::sqrt(1.0 + y * y);
    return (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy)) / (2.0 * glm::pi<double>());
}

TEST(AreaLight, ASquareEmitterMatchesTheFormFactorUnderItsCentre) {
    Floor floor;
    TraceMaterial black;
    black.albedo = glm::vec3(0.0f);
    floor.materials.push_back(black);
    const TriangleMesh panel = luxel::testing::horizontal_quad(1.0f, 0.25f, false, -1, 1);
    LightSource light;
    light.kind = LightKind::Area;
    light.power = glm::vec3(2.0f);  // emitted radiance
    light.triangles = luxel::testing::triangles_of(panel);
    floor.rays.add_object(panel, glm::mat4(1.0f), false);
    floor.rays.commit();
    ReferenceScene scene(floor.rays, floor.materials, {light},
                         {luxel::testing::quad_texels(0, 0.0f, kHalf, true, kSize)});
    ReferenceSettings settings;
    settings.samples_per_pass = 64;
    ReferenceIntegrator integrator(scene, settings);
    JobSystem jobs(2);
    for (int pass = 0; pass < 4; ++pass) {
        integrator.run_pass(jobs);
    }
    // The four texels around the centre: (7|8, 7|8), at (+-0.125, 0, +-0.125). By symmetry
    // each sees the panel as four rectangles with corners under the texel.
    const double p = 0.125;
    const double expected =
        2.0 * glm::pi<double>() *
        (corner_form_factor(0.25 + p, 0.25 + p, 1.0) + corner_form_factor(0.25 - p, 0.25 - p, 1.0) +
         2.0 * corner_form_factor(0.25 + p, 0.25 - p, 1.0));
    for (std::size_t t : {7u * kSize + 7u, 7u * kSize + 8u, 8u * kSize + 7u, 8u * kSize + 8u}) {
        const double got = integrator.irradiance(Component::Direct, t).x;
        const double se = integrator.standard_error(Component::Direct, t).x;
        EXPECT_NEAR(got, expected, 3.0 * se + 0.01 * expected) << "texel " << t;
        std::printf("[ figures  ] area light texel %zu: E %.5f expected %.5f (%+.3f%%, se %.5f)\n",
                    t, got, expected, 100.0 * (got / expected - 1.0), se);
    }
}

}  // namespace
