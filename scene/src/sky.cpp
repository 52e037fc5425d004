#include "luxel/scene/sky.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <vector>

#include <nlohmann/json.hpp>

#include "luxel/runtime/error.hpp"

namespace luxel::scene {
namespace {

/// A finite, non-negative number, or an Error naming `what`.
float checked(double value, const std::string& what) {
    if (!std::isfinite(value) || value < 0.0 || value > 3.0e38) {
        throw Error(what + " must be a finite number >= 0 (got " + std::to_string(value) + ")");
    }
    return static_cast<float>(value);
}

std::vector<float> numbers(std::string_view text, const std::string& what) {
    std::vector<float> out;
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t comma = std::min(text.find(',', start), text.size());
        const std::string piece(text.substr(start, comma - start));
        double value = 0.0;
        const auto [end, error] = std::from_chars(piece.data(), piece.data() + piece.size(), value);
        if (piece.empty() || error != std::errc() || end != piece.data() + piece.size()) {
            throw Error(what + ": '" + piece + "' is not a number");
        }
        out.push_back(checked(value, what));
        start = comma + 1;
    }
    return out;
}

std::string number_text(float value) {
    char buffer[32];
    const auto [end, error] = std::to_chars(buffer, buffer + sizeof(buffer), value);
    return error == std::errc() ? std::string(buffer, end) : std::string("?");
}

/// An albedo: finite and in [0, 1], or an Error naming `what`.
float albedo(double value, const std::string& what) {
    if (!std::isfinite(value) || value < 0.0 || value > 1.0) {
        throw Error(what + " must be an albedo from 0 to 1 (got " + std::to_string(value) + ")");
    }
    return static_cast<float>(value);
}

/// Takes a last ",ground=..." (or a whole "ground=...") off `rest` into `sky.ground`.
std::string_view take_ground(std::string_view rest, SkySpec& sky, const std::string& what) {
    const std::string_view key = "ground=";
    const std::size_t at = rest.rfind(key);
    if (at == std::string_view::npos || (at > 0 && rest[at - 1] != ',')) {
        return rest;
    }
    std::string value(rest.substr(at + key.size()));
    for (char& c : value) {
        c = c == '/' ? ',' : c;
    }
    const std::vector<float> values = numbers(value, what + " ground");
    if (values.size() != 1 && values.size() != 3) {
        throw Error(what + ": ground=A or ground=R/G/B, an albedo from 0 to 1");
    }
    for (std::size_t c = 0; c < 3; ++c) {
        sky.ground[static_cast<glm::length_t>(c)] =
            albedo(values[values.size() == 1 ? 0 : c], what + " ground");
    }
    return rest.substr(0, at == 0 ? 0 : at - 1);
}

}  // namespace

SkySpec parse_sky(std::string_view text) {
    SkySpec sky;
    const std::size_t colon = text.find(':');
    const std::string_view head = text.substr(0, colon);
    std::string_view rest =
        colon == std::string_view::npos ? std::string_view() : text.substr(colon + 1);
    if (head == "none" && colon == std::string_view::npos) {
        return sky;
    }
    if (head == "uniform") {
        rest = take_ground(rest, sky, "--sky uniform");
        const std::vector<float> values = numbers(rest, "--sky uniform");
        if (values.size() != 1 && values.size() != 3) {
            throw Error("--sky uniform: give one radiance or three (R,G,B), e.g. uniform:0.5");
        }
        sky.kind = SkySpec::Kind::Uniform;
        sky.radiance =
            values.size() == 1 ? glm::vec3(values[0]) : glm::vec3(values[0], values[1], values[2]);
        return sky;
    }
    if (head == "daylight") {
        sky.kind = SkySpec::Kind::Daylight;
        if (colon == std::string_view::npos) {
            return sky;
        }
        const bool only_ground = rest.starts_with("ground=");
        rest = take_ground(rest, sky, "--sky daylight");
        if (only_ground) {
            return sky;
        }
        const std::vector<float> values = numbers(rest, "--sky daylight");
        if (values.size() > 2) {
            throw Error(
                "--sky daylight: give E (W/m^2) and optionally a turbidity, e.g. "
                "daylight:1.5,3");
        }
        sky.irradiance = values[0];
        if (values.size() == 2) {
            sky.turbidity = values[1];
        }
        return sky;
    }
    const std::filesystem::path path(text);
    if (path.extension() == ".exr") {
        sky.kind = SkySpec::Kind::Map;
        sky.map = path;
        return sky;
    }
    throw Error("--sky: '" + std::string(text) +
                "' is none of none, uniform:R,G,B, daylight[:E[,T]] or a FILE.exr");
}

SkySpec read_sky_extras(const nlohmann::json& sky) {
    const std::string where = "extras.luxel.sky";
    if (!sky.is_object()) {
        throw Error(where + " must be a JSON object");
    }
    SkySpec out;
    const auto kind = sky.find("kind");
    if (kind == sky.end() || !kind->is_string()) {
        throw Error(where + ".kind must be \"uniform\", \"daylight\" or \"map\"");
    }
    auto number = [&](const char* key, float fallback) {
        const auto found = sky.find(key);
        if (found == sky.end()) {
            return fallback;
        }
        if (!found->is_number()) {
            throw Error(where + "." + key + " must be a number");
        }
        return checked(found->get<double>(), where + "." + key);
    };
    if (*kind == "uniform") {
        out.kind = SkySpec::Kind::Uniform;
        const auto radiance = sky.find("radiance");
        if (radiance != sky.end()) {
            if (!radiance->is_array() || radiance->size() != 3) {
                throw Error(where + ".radiance must be three numbers [R, G, B]");
            }
            for (int c = 0; c < 3; ++c) {
                const nlohmann::json& value = (*radiance)[static_cast<std::size_t>(c)];
                if (!value.is_number()) {
                    throw Error(where + ".radiance must be three numbers [R, G, B]");
                }
                out.radiance[c] = checked(value.get<double>(), where + ".radiance");
            }
        }
    } else if (*kind == "daylight") {
        out.kind = SkySpec::Kind::Daylight;
        out.irradiance = number("irradiance", out.irradiance);
        out.turbidity = number("turbidity", out.turbidity);
    } else if (*kind == "map") {
        // The file is named relative to the level's folder; the loader resolves it there and
        // refuses one outside (scene/src/gltf_loader.cpp, as for buffers and images).
        out.kind = SkySpec::Kind::Map;
        const auto file = sky.find("file");
        if (file == sky.end() || !file->is_string() || file->get<std::string>().empty()) {
            throw Error(where +
                        ".file must name the environment map, an .exr file in the level's folder");
        }
        out.map = std::filesystem::path(file->get<std::string>());
        if (out.map.extension() != ".exr") {
            throw Error(where + ".file '" + file->get<std::string>() +
                        "' is not an OpenEXR (.exr) file");
        }
    } else {
        throw Error(where + ".kind must be \"uniform\", \"daylight\" or \"map\" (got " +
                    kind->dump() + ")");
    }
    out.scale = number("scale", out.scale);
    if (const auto ground = sky.find("ground"); ground != sky.end()) {
        const std::string field = where + ".ground";
        if (out.kind == SkySpec::Kind::Map) {
            throw Error(field +
                        " is for uniform and daylight skies; a map keeps its own pixels "
                        "below the horizon");
        }
        if (ground->is_number()) {
            out.ground = glm::vec3(albedo(ground->get<double>(), field));
        } else if (ground->is_array() && ground->size() == 3 &&
                   std::all_of(ground->begin(), ground->end(),
                               [](const nlohmann::json& v) { return v.is_number(); })) {
            for (int c = 0; c < 3; ++c) {
                out.ground[c] = albedo((*ground)[static_cast<std::size_t>(c)].get<double>(), field);
            }
        } else {
            throw Error(field + " must be an albedo: a number or [R, G, B], each from 0 to 1");
        }
    }
    return out;
}

nlohmann::json sky_extras(const SkySpec& sky) {
    nlohmann::json out;
    switch (sky.kind) {
        case SkySpec::Kind::None:
            return nullptr;
        case SkySpec::Kind::Map:
            // A level names its map relative to its own folder; a map from the command line or
            // one resolved at load (an absolute path) is the writer's to place (luxel-prep
            // copies it beside the level it writes).
            if (sky.map.empty() || sky.map.is_absolute()) {
                return nullptr;
            }
            out["kind"] = "map";
            out["file"] = sky.map.generic_string();
            break;
        case SkySpec::Kind::Uniform:
            out["kind"] = "uniform";
            out["radiance"] = {sky.radiance.r, sky.radiance.g, sky.radiance.b};
            break;
        case SkySpec::Kind::Daylight:
            out["kind"] = "daylight";
            out["irradiance"] = sky.irradiance;
            out["turbidity"] = sky.turbidity;
            break;
    }
    if (sky.scale != 1.0f) {
        out["scale"] = sky.scale;
    }
    if (sky.ground != glm::vec3(0.0f)) {
        out["ground"] = {sky.ground.r, sky.ground.g, sky.ground.b};
    }
    return out;
}

std::string describe(const SkySpec& sky) {
    const std::string ground = sky.ground == glm::vec3(0.0f) ? std::string()
                               : sky.ground == glm::vec3(sky.ground.r)
                                   ? ",ground=" + number_text(sky.ground.r)
                                   : ",ground=" + number_text(sky.ground.r) + "/" +
                                         number_text(sky.ground.g) + "/" +
                                         number_text(sky.ground.b);
    switch (sky.kind) {
        case SkySpec::Kind::None:
            return "none";
        case SkySpec::Kind::Uniform:
            return "uniform:" + number_text(sky.radiance.r) + "," + number_text(sky.radiance.g) +
                   "," + number_text(sky.radiance.b) + ground;
        case SkySpec::Kind::Daylight:
            return "daylight:" + number_text(sky.irradiance) + "," + number_text(sky.turbidity) +
                   ground;
        case SkySpec::Kind::Map:
            return sky.map.string();
    }
    return "none";
}

}  // namespace luxel::scene
