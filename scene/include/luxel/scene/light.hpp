#pragma once

#include <string>

#include <glm/glm.hpp>

/// Punctual lights as glTF's KHR_lights_punctual describes them, and their conversion from
/// photometric glTF units to the radiometric units luxel computes in (docs/UNITS.md).
namespace luxel::scene {

enum class LightType { Point, Spot, Directional };

/// Luminous efficacy used to turn lumens into watts: 683 lm/W, the maximum (555 nm) value that
/// defines the candela. glTF stores photometric quantities; luxel treats the light's colour as
/// the radiometric spectrum's linear RGB, so each channel converts with the same constant.
inline constexpr float kLumensPerWatt = 683.0f;

struct Light {
    std::string name;
    LightType type = LightType::Point;
    glm::vec3 color{1.0f};  ///< linear RGB
    /// glTF intensity: candela (lm/sr) for point and spot, lux (lm/m^2) for directional.
    float intensity = 1.0f;
    float range = 0.0f;                            ///< 0: infinite
    float inner_cone_angle = 0.0f;                 ///< spot, radians
    float outer_cone_angle = 0.7853981633974483f;  ///< spot, radians (pi/4, glTF default)

    /// Radiant intensity in W/sr per channel (point and spot): color * intensity / 683.
    [[nodiscard]] glm::vec3 radiant_intensity() const { return color * intensity / kLumensPerWatt; }
    /// Radiant flux in W per channel emitted by a point light (4 pi I) or a spot light
    /// (I times the solid angle of its outer cone, 2 pi (1 - cos outer)). Zero for directional.
    [[nodiscard]] glm::vec3 radiant_power() const;
    /// Irradiance in W/m^2 per channel on a surface facing a directional light: color * lux / 683.
    [[nodiscard]] glm::vec3 irradiance() const { return color * intensity / kLumensPerWatt; }

    /// The inverse conversions, used when writing levels built in watts.
    [[nodiscard]] static Light point_from_power(const glm::vec3& watts);
    [[nodiscard]] static Light spot_from_power(const glm::vec3& watts, float inner, float outer);
    [[nodiscard]] static Light directional_from_irradiance(const glm::vec3& watts_per_m2);
};

}  // namespace luxel::scene
