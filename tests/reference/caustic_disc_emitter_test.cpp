// The reference's caustic emitter (CausticDiscEmitter) against closed forms, and against the
// real-time CausticEmitter: two constructions of one integral, the power a light sends into a
// sphere, which must agree.

#include <cmath>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "luxel/lighting/core/caustic_emitter.hpp"
#include "luxel/lighting/reference/caustic_disc_emitter.hpp"

namespace {

using namespace luxel::lighting;
using luxel::lighting::reference::CausticDiscEmitter;
using luxel::lighting::reference::ReferenceLight;

constexpr int kSide = 128;  // a kSide x kSide stratified grid of samples

glm::dvec2 grid_sample(int i, int j) {
    return {(i + 0.5) / kSide, (j + 0.5) / kSide};
}

ReferenceLight point_light(const glm::vec3& position, double flux) {
    ReferenceLight light;
    light.source.kind = LightKind::Point;
    light.source.position = position;
    light.source.power = glm::vec3(static_cast<float>(flux));
    light.intensity = glm::vec3(static_cast<float>(flux / (4.0 * glm::pi<double>())));
    return light;
}

/// Whether the ray from `origin` along unit `direction` meets the sphere (allowing for float
/// rounding at its rim).
bool meets(const glm::vec3& origin, const glm::vec3& direction, const BoundingSphere& sphere) {
    const glm::dvec3 to_centre = glm::dvec3(sphere.centre) - glm::dvec3(origin);
    const double along = glm::dot(to_centre, glm::dvec3(direction));
    const double miss2 = glm::dot(to_centre, to_centre) - along * along;
    const double r = static_cast<double>(sphere.radius) * (1.0 + 1e-4);
    return along > 0.0 && miss2 <= r * r;
}

struct Totals {
    double power = 0.0;    ///< summed over photons, one channel
    bool all_meet = true;  ///< every photon with power heads into the sphere
};

Totals emit_all(const CausticDiscEmitter& emitter, const BoundingSphere& sphere) {
    Totals totals;
    const double n = static_cast<double>(kSide) * kSide;
    for (int i = 0; i < kSide; ++i) {
        for (int j = 0; j < kSide; ++j) {
            const EmittedPhoton photon = emitter.emit(grid_sample(i, j), n);
            totals.power += static_cast<double>(photon.power.x);
            if (photon.power.x > 0.0f && !meets(photon.origin, photon.direction, sphere)) {
                totals.all_meet = false;
            }
        }
    }
    return totals;
}

double realtime_total(const LightSource& light, const BoundingSphere& sphere,
                      const BoundingSphere& scene) {
    const CausticEmitter emitter(light, sphere, scene);
    const auto n = static_cast<std::uint64_t>(kSide) * kSide;
    double total = 0.0;
    for (int i = 0; i < kSide; ++i) {
        for (int j = 0; j < kSide; ++j) {
            total +=
                static_cast<double>(emitter.emit(grid_sample(i, j), grid_sample(j, i), n).power.x);
        }
    }
    return total;
}

const BoundingSphere kScene{glm::vec3(0.0f), 10.0f};

TEST(CausticDiscEmitter, APointLightSendsIntensityTimesTheConesSolidAngle) {
    const BoundingSphere sphere{glm::vec3(0.0f, 0.0f, -3.0f), 0.5f};
    const ReferenceLight light = point_light(glm::vec3(0.0f), 100.0);
    const CausticDiscEmitter emitter(light, sphere, kScene);
    ASSERT_TRUE(emitter.reaches_generator());
    const Totals totals = emit_all(emitter, sphere);
    const double d = 3.0;
    const double r = 0.5;
    const double solid_angle = 2.0 * glm::pi<double>() * (1.0 - std::sqrt(1.0 - r * r / (d * d)));
    const double expected = 100.0 / (4.0 * glm::pi<double>()) * solid_angle;
    EXPECT_NEAR(totals.power, expected, 1e-3 * expected);
    EXPECT_TRUE(totals.all_meet);
    // The real-time emitter, sampling the cone directly, agrees.
    EXPECT_NEAR(realtime_total(light.source, sphere, kScene), expected, 2e-3 * expected);
}

TEST(CausticDiscEmitter, AnApexInsideTheSphereSendsTheWholeFlux) {
    const BoundingSphere sphere{glm::vec3(0.2f, 0.0f, 0.0f), 1.0f};
    const CausticDiscEmitter emitter(point_light(glm::vec3(0.0f), 50.0), sphere, kScene);
    ASSERT_TRUE(emitter.reaches_generator());
    EXPECT_NEAR(emit_all(emitter, sphere).power, 50.0, 1e-6 * 50.0);
}

TEST(CausticDiscEmitter, ASpotAgreesWithTheRealTimeEmitterAndMissesWhenAimedAway) {
    const BoundingSphere sphere{glm::vec3(0.4f, 0.0f, -2.0f), 0.6f};
    ReferenceLight spot;
    spot.source.kind = LightKind::Spot;
    spot.source.position = glm::vec3(0.0f);
    spot.source.direction = glm::vec3(0.0f, 0.0f, -1.0f);
    spot.source.power = glm::vec3(30.0f);
    spot.source.inner_cone = 0.15f;
    spot.source.outer_cone = 0.35f;  // the sphere's edge lies in the falloff
    const double cos_outer = std::cos(0.35);
    spot.intensity =
        glm::vec3(static_cast<float>(30.0 / (2.0 * glm::pi<double>() * (1.0 - cos_outer))));
    const CausticDiscEmitter emitter(spot, sphere, kScene);
    ASSERT_TRUE(emitter.reaches_generator());
    const Totals totals = emit_all(emitter, sphere);
    const double realtime = realtime_total(spot.source, sphere, kScene);
    ASSERT_GT(realtime, 0.0);
    EXPECT_NEAR(totals.power, realtime, 5e-3 * realtime);
    EXPECT_TRUE(totals.all_meet);

    ReferenceLight away = spot;
    away.source.direction = glm::vec3(0.0f, 0.0f, 1.0f);
    EXPECT_FALSE(CausticDiscEmitter(away, sphere, kScene).reaches_generator());
}

TEST(CausticDiscEmitter, ADirectionalBeamCoversTheDiscFromOutsideTheScene) {
    const BoundingSphere sphere{glm::vec3(1.0f, 2.0f, -1.0f), 0.75f};
    ReferenceLight sun;
    sun.source.kind = LightKind::Directional;
    sun.source.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    sun.source.power = glm::vec3(4.0f);  // W/m^2
    const CausticDiscEmitter emitter(sun, sphere, kScene);
    ASSERT_TRUE(emitter.reaches_generator());
    const Totals totals = emit_all(emitter, sphere);
    const double expected = 4.0 * glm::pi<double>() * 0.75 * 0.75;
    EXPECT_NEAR(totals.power, expected, 1e-4 * expected);
    EXPECT_TRUE(totals.all_meet);
    const EmittedPhoton photon = emitter.emit({0.3, 0.7}, 1.0);
    EXPECT_GT(glm::length(photon.origin - kScene.centre), kScene.radius);
    EXPECT_NEAR(realtime_total(sun.source, sphere, kScene), expected, 1e-3 * expected);
}

TEST(CausticDiscEmitter, BlackLightsAreaLightsAndEmptySpheresEmitNothing) {
    const BoundingSphere sphere{glm::vec3(0.0f, 0.0f, -3.0f), 0.5f};
    EXPECT_FALSE(
        CausticDiscEmitter(point_light(glm::vec3(0.0f), 0.0), sphere, kScene).reaches_generator());
    ReferenceLight area = point_light(glm::vec3(0.0f), 10.0);
    area.source.kind = LightKind::Area;
    EXPECT_FALSE(CausticDiscEmitter(area, sphere, kScene).reaches_generator());
    const CausticDiscEmitter empty(point_light(glm::vec3(0.0f), 10.0), {sphere.centre, 0.0f},
                                   kScene);
    EXPECT_FALSE(empty.reaches_generator());
    EXPECT_EQ(empty.emit({0.5, 0.5}, 1.0).power, glm::vec3(0.0f));
}

}  // namespace
