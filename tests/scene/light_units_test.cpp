// glTF photometric light units to radiometric watts and back (docs/UNITS.md).

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "luxel/scene/light.hpp"

namespace {

using luxel::scene::Light;
using luxel::scene::LightType;

constexpr float kPi = std::numbers::pi_v<float>;

void expect_vec3_near(const glm::vec3& a, const glm::vec3& b, float relative) {
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(a[c], b[c], relative * std::max(1.0f, std::abs(b[c]))) << "channel " << c;
    }
}

TEST(LightUnits, PointLightOf683CandelaRadiatesOneWattPerSteradian) {
    Light light;
    light.type = LightType::Point;
    light.intensity = 683.0f;
    expect_vec3_near(light.radiant_intensity(), glm::vec3(1.0f), 1e-6f);
    expect_vec3_near(light.radiant_power(), glm::vec3(4.0f * kPi), 1e-6f);
}

TEST(LightUnits, ColourScalesEachChannel) {
    Light light;
    light.color = {1.0f, 0.5f, 0.25f};
    light.intensity = 68.3f;
    expect_vec3_near(light.radiant_intensity(), {0.1f, 0.05f, 0.025f}, 1e-6f);
}

TEST(LightUnits, SpotPowerUsesTheOuterConeSolidAngle) {
    Light light;
    light.type = LightType::Spot;
    light.intensity = 683.0f;
    light.inner_cone_angle = 0.1f;
    light.outer_cone_angle = kPi / 3.0f;  // solid angle 2 pi (1 - 1/2) = pi
    expect_vec3_near(light.radiant_power(), glm::vec3(kPi), 1e-5f);
}

TEST(LightUnits, DirectionalLuxToIrradiance) {
    Light light;
    light.type = LightType::Directional;
    light.intensity = 100000.0f;  // bright sunlight
    expect_vec3_near(light.irradiance(), glm::vec3(100000.0f / 683.0f), 1e-6f);
    EXPECT_EQ(light.radiant_power(), glm::vec3(0.0f));
}

TEST(LightUnits, WorkedExampleFromUnitsDoc) {
    // docs/UNITS.md: an 800 lm bulb is 800 / (4 pi) = 63.66 cd, 0.09321 W/sr, 1.1713 W.
    Light bulb;
    bulb.intensity = 800.0f / (4.0f * kPi);
    EXPECT_NEAR(bulb.intensity, 63.662f, 1e-3f);
    EXPECT_NEAR(bulb.radiant_intensity().r, 0.093209f, 1e-6f);
    EXPECT_NEAR(bulb.radiant_power().r, 1.17130f, 1e-5f);
}

TEST(LightUnits, InversesRoundTrip) {
    const glm::vec3 watts(100.0f, 50.0f, 25.0f);
    const Light point = Light::point_from_power(watts);
    EXPECT_EQ(point.type, LightType::Point);
    EXPECT_FLOAT_EQ(point.color.r, 1.0f);  // the largest channel carries the intensity
    EXPECT_FLOAT_EQ(point.color.g, 0.5f);
    EXPECT_NEAR(point.intensity, 100.0f * 683.0f / (4.0f * kPi), 1e-2f);
    expect_vec3_near(point.radiant_power(), watts, 1e-5f);

    const Light spot = Light::spot_from_power(watts, 0.2f, 0.7f);
    EXPECT_EQ(spot.type, LightType::Spot);
    EXPECT_FLOAT_EQ(spot.inner_cone_angle, 0.2f);
    EXPECT_FLOAT_EQ(spot.outer_cone_angle, 0.7f);
    expect_vec3_near(spot.radiant_power(), watts, 1e-5f);

    const Light sun = Light::directional_from_irradiance({3.0f, 2.0f, 1.0f});
    EXPECT_EQ(sun.type, LightType::Directional);
    expect_vec3_near(sun.irradiance(), {3.0f, 2.0f, 1.0f}, 1e-6f);
    EXPECT_NEAR(sun.intensity, 3.0f * 683.0f, 1e-2f);

    const Light dark = Light::point_from_power(glm::vec3(0.0f));
    EXPECT_EQ(dark.intensity, 0.0f);
    EXPECT_EQ(dark.radiant_power(), glm::vec3(0.0f));
}

}  // namespace
