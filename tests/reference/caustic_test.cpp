// The dense photon estimate of caustics against a closed form: a point light over a perfect
// flat mirror lights the ceiling above as the light's mirror image would (E = I cos / d'^2,
// d' from the image), and the estimate is deterministic for a seed.

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
};

TEST(Caustics, AFlatMirrorLightsTheCeilingLikeTheLightsMirrorImage) {
    MirrorRoom room;
    ReferenceScene scene(room.rays, room.materials, {room.light},
                         {luxel::testing::quad_texels(0, 2.0f, 2.0f, false, 8)});
    ASSERT_EQ(scene.generator_spheres().size(), 1u);
    ReferenceSettings settings;
    settings.samples_per_pass = 1;
    settings.caustics.photons_per_pass = 1'000'000;
    ReferenceIntegrator integrator(scene, settings);
    JobSystem jobs(2);
    integrator.run_pass(jobs);
    const CausticReference& caustics = integrator.caustics();
    EXPECT_EQ(caustics.pair_count(), 1u);
    const double intensity = 40.0 / (4.0 * glm::pi<double>());
    const glm::dvec3 image(0.0, -1.0, 0.0);
    double sum = 0.0;
    double expected_sum = 0.0;
    double worst_sigma = 0.0;
    for (std::size_t t = 0; t < scene.texel_count(); ++t) {
        const glm::dvec3 to_image = image - glm::dvec3(scene.texel(t).position);
        const double d2 = glm::dot(to_image, to_image);
        // Every ceiling texel lies inside the mirror's reflected beam (|x|, |z| < 3 m at y = 2).
        const double expected = intensity * (-to_image.y / std::sqrt(d2)) / d2;
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

TEST(Caustics, ASeedFixesThePhotonEstimate) {
    MirrorRoom room;
    ReferenceScene scene(room.rays, room.materials, {room.light},
                         {luxel::testing::quad_texels(0, 2.0f, 2.0f, false, 8)});
    CausticReferenceSettings settings;
    settings.photons_per_pass = 100'000;
    CausticReference a(scene, settings);
    CausticReference b(scene, settings);
    JobSystem one(1);
    JobSystem two(2);
    a.run_pass(one);
    b.run_pass(two);
    for (std::size_t t = 0; t < scene.texel_count(); ++t) {
        ASSERT_EQ(a.irradiance(t), b.irradiance(t));
        ASSERT_EQ(a.standard_error(t), b.standard_error(t));
    }
}

}  // namespace
