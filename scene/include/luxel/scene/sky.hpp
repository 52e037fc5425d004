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
    /// Map: the OpenEXR file. From --sky, as given; from a level's extras, named relative to
    /// the level's folder and, once loaded, its real path there (the loader refuses one outside).
    std::filesystem::path map;
    float scale = 1.0f;  ///< every kind: multiplies the radiance
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
/// {"kind": "daylight", "irradiance": E, "turbidity": T}, {"kind": "map", "file": "F.exr"};
/// optional "scale", and for uniform and daylight "ground" (an albedo: a number or [R, G, B],
/// each at most 1). A map's file is returned as written: the loader resolves it in the level's
/// folder. Throws luxel::Error naming the field for a wrong type, an unknown kind, a value that
/// is negative or not finite, or a map that is not an .exr file.
[[nodiscard]] SkySpec read_sky_extras(const nlohmann::json& sky);

/// extras.luxel.sky for a level file: null for None, and for a Map whose file is absolute (from
/// --sky, or resolved at load): a level names its map relative to its own folder only.
[[nodiscard]] nlohmann::json sky_extras(const SkySpec& sky);

/// What --sky and the level's extras write: "uniform:R,G,B", "daylight:E,T", the map's path.
[[nodiscard]] std::string describe(const SkySpec& sky);

}  // namespace luxel::scene
