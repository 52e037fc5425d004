#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

/// The sky a level asks for: in its glTF scene's extras.luxel.sky, or from --sky on the command
/// line (docs/LEVELS.md, "Sky"). A description only; the lighting system's SkyRadiance is built
/// from it when the level is instantiated (world::instantiate).
namespace luxel::scene {

struct SkySpec {
    enum class Kind : std::uint8_t {
        None,      ///< no sky: what leaves the level is black
        Uniform,   ///< `radiance` from every direction above the horizon
        Daylight,  ///< a clear sky (Preetham) for the level's sun
        Map,       ///< an equirectangular OpenEXR environment map
    };
    Kind kind = Kind::None;
    glm::vec3 radiance{1.0f};  ///< uniform: W/(m^2 sr)
    /// Daylight: W/m^2 the sky alone gives a horizontal surface (its luminance; the sun's
    /// direct light is the level's DirectionalLight's), and the atmosphere's turbidity.
    float irradiance = 1.0f;
    float turbidity = 3.0f;
    std::filesystem::path map;  ///< map: the file (from the command line)
    float scale = 1.0f;         ///< every kind: multiplies the radiance
    /// Uniform and daylight: the albedo of a flat ground below the horizon, lit by the sky (and,
    /// for daylight, its sun), for a level with no ground of its own outside its windows. 0
    /// (the default): below the horizon is black, and a level's own ground bounces the light.
    /// A map keeps its own pixels below the horizon.
    glm::vec3 ground{0.0f};

    friend bool operator==(const SkySpec&, const SkySpec&) = default;
};

/// Parses --sky's value: "none", "uniform:L" or "uniform:R,G,B" (W/(m^2 sr)), "daylight",
/// "daylight:E" or "daylight:E,T" (horizontal irradiance W/m^2, turbidity), or the path of an
/// .exr file. Uniform and daylight take a last ",ground=A" (a grey albedo) or ",ground=R/G/B"
/// ("daylight:ground=0.2" with the default E and T). Throws luxel::Error saying what is wrong.
[[nodiscard]] SkySpec parse_sky(std::string_view text);

/// Reads extras.luxel.sky of a glTF scene: {"kind": "uniform", "radiance": [R, G, B]},
/// {"kind": "daylight", "irradiance": E, "turbidity": T}, optional "scale" and "ground" (an
/// albedo: a number or [R, G, B], each at most 1). Throws
/// luxel::Error naming the field for a wrong type, an unknown kind or a value that is negative
/// or not finite. A level names no files for its sky (an environment map comes from --sky).
[[nodiscard]] SkySpec read_sky_extras(const nlohmann::json& sky);

/// extras.luxel.sky for a level file: null for None and Map (a level names no sky file).
[[nodiscard]] nlohmann::json sky_extras(const SkySpec& sky);

/// What --sky and the level's extras write: "uniform:R,G,B", "daylight:E,T", the map's path.
[[nodiscard]] std::string describe(const SkySpec& sky);

}  // namespace luxel::scene
