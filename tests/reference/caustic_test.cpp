// The dense photon estimate of caustics against a closed form: a point light over a perfect
// flat mirror lights the ceiling above as the light's mirror image would (E = I cos / d'^2,
// d' from the image), and the estimate is deterministic for a seed.

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "luxel/lighting/reference/caustic_pixels.hpp"
#include "luxel/lighting/reference/reference_integrator.hpp"
#include "luxel/runtime/error.hpp"
#include "scene_builder.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;
using namespace luxel::lighting::reference;

struct MirrorRoom {
    RayScene rays;
    std::vector<TraceMaterial> materials;
    LightSource light;

    MirrorRoom() {
        TraceMaterial wall;
        TraceMaterial mirror;
        mirror.scattering = Scattering::Mirror;
        mirror.tint = glm::vec3(1.0f);  // Schlick with F0 = 1 reflects everything
        materials = {wall, mirror};
        rays.add_object(luxel::testing::horizontal_quad(0.0f, 1.0f, true, -1, 1), glm::mat4(1.0f),
                        false);
        rays.add_object(luxel::testing::horizontal_quad(2.0f, 2.0f, false, 0, 0), glm::mat4(1.0f),
                        false);
        rays.commit();
        light.kind = LightKind::Point;
        light.position = {0.0f, 1.0f, 0.0f};
        light.power = glm::vec3(40.0f);
    }

    /// The room with the ceiling's 8 x 8 texels, the only light-mapped surface.
    [[nodiscard]] ReferenceScene scene() const {
        return ReferenceScene(rays, materials, {light},
                              {luxel::testing::quad_texels(0, 2.0f, 2.0f, false, 8)});
    }

    /// The closed form on the ceiling: the light's mirror image at y = -1 lights `point` with
    /// E = I cos / d^2.
    [[nodiscard]] static double ceiling_irradiance(const glm::dvec3& point) {
        const double intensity = 40.0 / (4.0 * glm::pi<double>());
        const glm::dvec3 to_image = glm::dvec3(0.0, -1.0, 0.0) - point;
        const double d2 = glm::dot(to_image, to_image);
        return intensity * (-to_image.y / std::sqrt(d2)) / d2;
    }
};

TEST(Caustics, AFlatMirrorLightsTheCeilingLikeTheLightsMirrorImage) {
    MirrorRoom room;
    const ReferenceScene scene = room.scene();
    ASSERT_EQ(scene.generator_spheres().size(), 1u);
    ReferenceSettings settings;
    settings.samples_per_pass = 1;
    settings.caustics.photons_per_pass = 1'000'000;
    ReferenceIntegrator integrator(scene, settings);
    JobSystem jobs(2);
    integrator.run_pass(jobs);
    const CausticReference& caustics = integrator.caustics();
    EXPECT_EQ(caustics.pair_count(), 1u);
    double sum = 0.0;
    double expected_sum = 0.0;
    double worst_sigma = 0.0;
    for (std::size_t t = 0; t < scene.texel_count(); ++t) {
        // Every ceiling texel lies inside the mirror's reflected beam (|x|, |z| < 3 m at y = 2).
        const double expected = MirrorRoom::ceiling_irradiance(glm::dvec3(scene.texel(t).position));
        const double got = caustics.irradiance(t).x;
        const double se = caustics.standard_error(t).x;
        EXPECT_NEAR(got, expected, 3.0 * se + 0.02 * expected) << "texel " << t;
        worst_sigma = std::max(worst_sigma, se / expected);
        sum += got;
        expected_sum += expected;
    }
    EXPECT_NEAR(sum, expected_sum, 0.01 * expected_sum);
    std::printf(
        "[ figures  ] mirror caustic: mean %+.3f%% off the image's E, worst relative "
        "std. error %.4f, %llu of %llu photons stored\n",
        100.0 * (sum / expected_sum - 1.0), worst_sigma,
        static_cast<unsigned long long>(caustics.counters().stored),
        static_cast<unsigned long long>(caustics.counters().emitted));
}

TEST(Caustics, PixelFootprintsMeasureTheCausticAtTheirOwnSize) {
    // The texel-binned estimate averages over a 0.5 m texel here; discs of 5 and 15 cm at
    // chosen points read the closed form there, and discs that face the other way or float
    // off the ceiling read nothing.
    MirrorRoom room;
    const ReferenceScene scene = room.scene();
    CausticReferenceSettings settings;
    settings.photons_per_pass = 4'000'000;
    CausticReference caustics(scene, settings);
    const glm::vec3 down(0.0f, -1.0f, 0.0f);
    const std::vector<glm::vec2> points = {{0.0f, 0.0f}, {0.5f, -0.3f}, {-1.4f, 1.1f}};
    std::vector<CausticFootprint> footprints;
    for (const glm::vec2& p : points) {
        for (const float radius : {0.05f, 0.15f}) {
            footprints.push_back({glm::vec3(p.x, 2.0f, p.y), down, radius});
        }
    }
    const std::size_t checked = footprints.size();
    footprints.push_back({glm::vec3(0.0f, 2.0f, 0.0f), -down, 0.1f});   // facing away
    footprints.push_back({glm::vec3(0.0f, 1.95f, 0.0f), down, 0.05f});  // 5 cm off the plane
    caustics.set_footprints(footprints);
    ASSERT_EQ(caustics.footprint_count(), footprints.size());
    JobSystem jobs(2);
    caustics.run_pass(jobs);

    for (std::size_t i = 0; i < checked; ++i) {
        const double expected = MirrorRoom::ceiling_irradiance(glm::dvec3(footprints[i].centre));
        const double got = caustics.footprint_irradiance(i).x;
        const double se = caustics.footprint_standard_error(i).x;
        EXPECT_GT(se, 0.0);
        EXPECT_LT(se, 0.1 * expected) << "enough photons to judge footprint " << i;
        EXPECT_NEAR(got, expected, 3.0 * se + 0.01 * expected)
            << "footprint " << i << " radius " << footprints[i].radius;
    }
    EXPECT_EQ(caustics.footprint_irradiance(checked), glm::dvec3(0.0));
    EXPECT_EQ(caustics.footprint_irradiance(checked + 1), glm::dvec3(0.0));
    EXPECT_EQ(caustics.footprint_irradiance(footprints.size()), glm::dvec3(0.0));
}

TEST(Caustics, ACameraSeesTheCausticAtPixelResolution) {
    // Looking up at the ceiling from beside the light: every pixel sees the ceiling, and shows
    // albedo / pi times the mirror image's irradiance at its centre (the field is smooth over a
    // 10 cm pixel), with a footprint the size of the patch the pixel covers.
    MirrorRoom room;
    const ReferenceScene scene = room.scene();
    const float fov = glm::radians(40.0f);
    const ReferenceCamera camera = ReferenceCamera::look_at({0.3f, 0.2f, 0.0f}, {0.3f, 2.0f, 0.0f},
                                                            fov, 16, 12, {0.0f, 0.0f, -1.0f});
    const CausticPixels pixels = caustic_pixels(scene, camera);
    ASSERT_EQ(pixels.footprints.size(), 16u * 12u) << "every pixel sees the ceiling";
    CausticReferenceSettings settings;
    settings.photons_per_pass = 4'000'000;
    CausticReference caustics(scene, settings);
    caustics.set_footprints(pixels.footprints);
    JobSystem jobs(2);
    caustics.run_pass(jobs);
    const Image image = caustic_pixel_image(pixels, caustics);

    const double side = 2.0 * 1.8 * std::tan(fov / 2.0) / 12.0;  // a pixel on the ceiling
    double worst = 0.0;
    for (int y = 0; y < 12; ++y) {
        for (int x = 0; x < 16; ++x) {
            const auto f = static_cast<std::size_t>(pixels.footprint_of_pixel[y * 16 + x]);
            const CausticFootprint& footprint = pixels.footprints[f];
            EXPECT_NEAR(footprint.centre.y, 2.0f, 1e-4f);
            // Off-axis pixels are farther and tilted: larger than the centre's, not much.
            const double area = glm::pi<double>() * footprint.radius * footprint.radius;
            EXPECT_GT(area, 0.98 * side * side);
            EXPECT_LT(area, 1.3 * side * side);
            const double want = 0.5 / glm::pi<double>() *
                                MirrorRoom::ceiling_irradiance(glm::dvec3(footprint.centre));
            const double se = 0.5 / glm::pi<double>() * caustics.footprint_standard_error(f).x;
            const double got = image.pixel(x, y).x;
            EXPECT_NEAR(got, want, 3.0 * se + 0.01 * want) << "pixel " << x << "," << y;
            worst = std::max(worst, se / want);
        }
    }
    EXPECT_LT(worst, 0.1) << "enough photons per pixel to judge";
    std::printf("[ figures  ] pixel caustic: worst relative std. error %.3f\n", worst);
}

TEST(Caustics, APixelsFootprintGrowsWithDistanceAndTilt) {
    const double omega = 1e-6;  // about a 1 mrad pixel
    EXPECT_DOUBLE_EQ(camera_footprint_area(omega, 2.0, 1.0), 4e-6);
    EXPECT_DOUBLE_EQ(camera_footprint_area(omega, 2.0, 0.5), 8e-6);
    EXPECT_DOUBLE_EQ(camera_footprint_area(omega, 2.0, 0.0), 4e-6 / 0.05) << "bounded";
    const CausticFootprint disc = footprint_of_area({0, 0, 0}, {0, 1, 0}, glm::pi<double>());
    EXPECT_FLOAT_EQ(disc.radius, 1.0f);
    EXPECT_THROW(CausticFootprints({{{0, 0, 0}, {0, 1, 0}, 0.0f}}), luxel::Error);
    EXPECT_THROW(CausticFootprints({{{0, 0, 0}, {0, 0, 0}, 1.0f}}), luxel::Error);
    EXPECT_THROW(CausticFootprints({{{NAN, 0, 0}, {0, 1, 0}, 1.0f}}), luxel::Error);
    // Discs of very different sizes in one set: each holds what lies in it.
    CausticFootprints set({{{0, 0, 0}, {0, 1, 0}, 0.001f}, {{0, 0, 0}, {0, 1, 0}, 3.0f}});
    set.add({0.0005f, 0.0f, 0.0f}, {0, 1, 0}, glm::dvec3(1.0));
    set.add({2.0f, 0.0f, 1.0f}, {0, 1, 0}, glm::dvec3(2.0));
    set.add({2.0f, 0.0f, 1.0f}, {1, 0, 0}, glm::dvec3(4.0));  // a wall's photon
    EXPECT_EQ(set.flux(0), glm::dvec3(1.0));
    EXPECT_EQ(set.flux(1), glm::dvec3(3.0));
}

TEST(Caustics, ASeedFixesThePhotonEstimate) {
    MirrorRoom room;
    const ReferenceScene scene = room.scene();
    CausticReferenceSettings settings;
    settings.photons_per_pass = 100'000;
    CausticReference a(scene, settings);
    CausticReference b(scene, settings);
    std::vector<CausticFootprint> footprints;
    for (int i = 0; i < 40; ++i) {
        footprints.push_back({glm::vec3(-1.9f + 0.1f * i, 2.0f, 0.1f), {0, -1, 0}, 0.05f});
    }
    a.set_footprints(footprints);
    b.set_footprints(footprints);
    JobSystem one(1);
    JobSystem two(2);
    a.run_pass(one);
    b.run_pass(two);
    for (std::size_t t = 0; t < scene.texel_count(); ++t) {
        ASSERT_EQ(a.irradiance(t), b.irradiance(t));
        ASSERT_EQ(a.standard_error(t), b.standard_error(t));
    }
    for (std::size_t i = 0; i < footprints.size(); ++i) {
        ASSERT_EQ(a.footprint_irradiance(i), b.footprint_irradiance(i));
        ASSERT_GT(a.footprint_irradiance(i).x, 0.0);
    }
}

}  // namespace
