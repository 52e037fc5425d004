// The reference's spherical lights (a point or spot light with a radius): directions drawn over
// the cone the sphere subtends must land on the sphere, and a fully visible sphere of radiance
// I / (pi r^2) must deliver what the point did, I cos / d^2 (Nusselt: a sphere wholly above a
// receiver's horizon projects to the same disc as seen from its centre's direction).

#include <cmath>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "luxel/lighting/reference/sphere_light.hpp"

namespace {

using luxel::lighting::reference::sample_sphere_light;
using luxel::lighting::reference::SphereSample;

TEST(SphereLight, SamplesLandOnTheSphereInsideItsCone) {
    const glm::vec3 origin(0.3f, -0.2f, 0.1f);
    const glm::vec3 centre(1.0f, 2.0f, -0.5f);
    const float radius = 0.25f;
    const double distance = glm::length(glm::dvec3(centre - origin));
    const double cos_max = std::sqrt(1.0 - radius * radius / (distance * distance));
    for (int i = 0; i < 32; ++i) {
        for (int j = 0; j < 32; ++j) {
            SphereSample sample;
            ASSERT_TRUE(sample_sphere_light(origin, centre, radius,
                                            glm::vec2((i + 0.5f) / 32.0f, j / 32.0f), sample));
            EXPECT_NEAR(glm::length(sample.direction), 1.0f, 1e-5f);
            const glm::vec3 on_sphere = origin + sample.direction * sample.distance;
            EXPECT_NEAR(glm::length(on_sphere - centre), radius, 1e-4f);
            const double cosine =
                glm::dot(glm::dvec3(sample.direction), glm::dvec3(centre - origin)) / distance;
            EXPECT_GE(cosine, cos_max - 1e-6);
            EXPECT_NEAR(sample.solid_angle, 2.0 * glm::pi<double>() * (1.0 - cos_max), 1e-6);
        }
    }
}

TEST(SphereLight, AFullyVisibleSphereDeliversThePointsIrradiance) {
    // A receiver facing up, lights at several heights, offsets and sizes (all above its
    // horizon): the cone's quadrature on a 64 x 64 grid of the unit square.
    const glm::vec3 origin(0.0f);
    const glm::dvec3 normal(0.0, 1.0, 0.0);
    constexpr double kIntensity = 10.0;  // W/sr
    for (const glm::vec3 centre :
         {glm::vec3(0.0f, 2.0f, 0.0f), glm::vec3(1.5f, 1.0f, 0.5f), glm::vec3(-0.4f, 0.6f, 0.2f)}) {
        for (const float radius : {0.01f, 0.1f, 0.3f}) {
            const double r = radius;
            const double radiance = kIntensity / (glm::pi<double>() * r * r);
            double irradiance = 0.0;
            constexpr int kGrid = 64;
            for (int i = 0; i < kGrid; ++i) {
                for (int j = 0; j < kGrid; ++j) {
                    SphereSample sample;
                    ASSERT_TRUE(sample_sphere_light(
                        origin, centre, radius, glm::vec2((i + 0.5f) / kGrid, (j + 0.5f) / kGrid),
                        sample));
                    irradiance += radiance *
                                  std::max(glm::dot(glm::dvec3(sample.direction), normal), 0.0) *
                                  sample.solid_angle;
                }
            }
            irradiance /= kGrid * kGrid;
            const glm::dvec3 to_light = glm::dvec3(centre - origin);
            const double d2 = glm::dot(to_light, to_light);
            const double point = kIntensity * glm::dot(to_light, normal) / std::sqrt(d2) / d2;
            EXPECT_NEAR(irradiance, point, 1e-3 * point)
                << "centre " << centre.x << " " << centre.y << " " << centre.z << ", r " << r;
        }
    }
}

TEST(SphereLight, NoSphereToSampleIsSaid) {
    SphereSample sample;
    const glm::vec3 centre(0.0f, 1.0f, 0.0f);
    EXPECT_FALSE(sample_sphere_light(glm::vec3(0.0f), centre, 0.0f, glm::vec2(0.5f), sample));
    EXPECT_FALSE(sample_sphere_light(glm::vec3(0.0f), centre, -1.0f, glm::vec2(0.5f), sample));
    // On and inside the sphere: the caller takes the light as a point.
    EXPECT_FALSE(sample_sphere_light(glm::vec3(0.0f), centre, 1.0f, glm::vec2(0.5f), sample));
    EXPECT_FALSE(sample_sphere_light(centre, centre, 0.5f, glm::vec2(0.5f), sample));
    // Far and tiny: the cone's solid angle keeps its digits (1 - cos would be 0 in float).
    ASSERT_TRUE(sample_sphere_light(glm::vec3(0.0f), glm::vec3(0.0f, 1000.0f, 0.0f), 1e-3f,
                                    glm::vec2(0.5f), sample));
    const double expected = glm::pi<double>() * 1e-6 / 1e6;
    EXPECT_NEAR(sample.solid_angle, expected, 1e-3 * expected);
}

}  // namespace
