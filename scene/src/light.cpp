#include "luxel/scene/light.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace luxel::scene {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

/// Solid angle of a cone with the given half angle: 2 pi (1 - cos angle).
float cone_solid_angle(float half_angle) {
    return 2.0f * kPi * (1.0f - std::cos(half_angle));
}

/// Splits a per-channel photometric quantity into glTF's colour (largest channel 1) and a
/// scalar intensity, the form KHR_lights_punctual stores.
void split_colour_and_intensity(const glm::vec3& photometric, Light& light) {
    const float largest = std::max({photometric.r, photometric.g, photometric.b});
    if (largest > 0.0f) {
        light.color = photometric / largest;
        light.intensity = largest;
    } else {
        light.color = glm::vec3(1.0f);
        light.intensity = 0.0f;
    }
}

}  // namespace

glm::vec3 Light::radiant_power() const {
    switch (type) {
        case LightType::Point:
            return radiant_intensity() * (4.0f * kPi);
        case LightType::Spot:
            return radiant_intensity() * cone_solid_angle(outer_cone_angle);
        case LightType::Directional:
            break;
    }
    return glm::vec3(0.0f);
}

Light Light::point_from_power(const glm::vec3& watts) {
    Light light;
    light.type = LightType::Point;
    // I [W/sr] = P / (4 pi); candela = W/sr * 683.
    split_colour_and_intensity(watts / (4.0f * kPi) * kLumensPerWatt, light);
    return light;
}

Light Light::spot_from_power(const glm::vec3& watts, float inner, float outer) {
    Light light;
    light.type = LightType::Spot;
    light.inner_cone_angle = inner;
    light.outer_cone_angle = outer;
    const float solid_angle = cone_solid_angle(outer);
    // A zero-width cone emits nothing whatever its intensity; keep the light dark rather than
    // dividing by zero.
    const glm::vec3 radiant = solid_angle > 0.0f ? watts / solid_angle : glm::vec3(0.0f);
    split_colour_and_intensity(radiant * kLumensPerWatt, light);
    return light;
}

Light Light::directional_from_irradiance(const glm::vec3& watts_per_m2) {
    Light light;
    light.type = LightType::Directional;
    split_colour_and_intensity(watts_per_m2 * kLumensPerWatt, light);
    return light;
}

}  // namespace luxel::scene
