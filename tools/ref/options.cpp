#include "options.hpp"

#include <cmath>
#include <sstream>
#include <vector>

#include "luxel/runtime/error.hpp"

namespace luxel::ref {
namespace {

std::vector<std::string> split(const std::string& text, char separator) {
    std::vector<std::string> parts;
    std::stringstream stream(text);
    std::string part;
    while (std::getline(stream, part, separator)) {
        parts.push_back(part);
    }
    if (!text.empty() && text.back() == separator) {
        parts.emplace_back();
    }
    return parts;
}

float parse_number(const std::string& text, const std::string& what) {
    std::size_t used = 0;
    float value = 0.0f;
    try {
        value = std::stof(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used == 0 || used != text.size() || !std::isfinite(value)) {
        throw Error("--camera: " + what + " '" + text + "' is not a number");
    }
    return value;
}

glm::vec3 parse_point(const std::string& text, const std::string& what) {
    const std::vector<std::string> parts = split(text, ',');
    if (parts.size() != 3) {
        throw Error("--camera: " + what + " '" + text + "' needs three numbers x,y,z");
    }
    return {parse_number(parts[0], what), parse_number(parts[1], what),
            parse_number(parts[2], what)};
}

}  // namespace

CameraSpec parse_camera(const std::string& text) {
    const std::vector<std::string> parts = split(text, ':');
    if (parts.size() != 3) {
        throw Error("--camera '" + text + "': expected x,y,z:tx,ty,tz:fov");
    }
    CameraSpec camera;
    camera.eye = parse_point(parts[0], "position");
    camera.target = parse_point(parts[1], "target");
    camera.fov_degrees = parse_number(parts[2], "field of view");
    if (!(camera.fov_degrees > 0.0f && camera.fov_degrees < 180.0f)) {
        throw Error("--camera: field of view " + parts[2] + " is not in (0, 180) degrees");
    }
    if (!(glm::length(camera.target - camera.eye) > 0.0f)) {
        throw Error("--camera: the position and the target coincide");
    }
    return camera;
}

void validate(const Options& options) {
    if (options.image.empty() && options.lightmaps.empty() && options.caustic_pixels.empty()) {
        throw Error(
            "nothing to do: give -o OUT.exr (a frame), --lightmaps OUT.json|.exr and/or "
            "--caustic-pixels OUT.exr");
    }
    if (!options.caustic_pixels.empty() && options.caustic_pixels.extension() != ".exr") {
        throw Error("--caustic-pixels " + options.caustic_pixels.string() +
                    ": the caustic frame is written as OpenEXR (.exr)");
    }
    if (!options.image.empty() && options.image.extension() != ".exr") {
        throw Error("-o " + options.image.string() + ": the frame is written as OpenEXR (.exr)");
    }
    if (!options.preview.empty() && options.image.empty()) {
        throw Error("--png " + options.preview.string() + ": needs a frame (-o OUT.exr)");
    }
    if (!options.lightmaps.empty() && options.lightmaps.extension() != ".json" &&
        options.lightmaps.extension() != ".exr") {
        throw Error("--lightmaps " + options.lightmaps.string() + ": expected .json or .exr");
    }
    if (options.width <= 0 || options.height <= 0 || options.width > 16384 ||
        options.height > 16384) {
        throw Error("--width/--height: " + std::to_string(options.width) + "x" +
                    std::to_string(options.height) + " is not in 1..16384");
    }
    if (options.spp == 0) {
        throw Error("--spp: need at least one sample");
    }
    if (options.indirect != "photons" && options.indirect != "paths") {
        throw Error("--indirect " + options.indirect + ": expected photons or paths");
    }
    if (options.passes == 0) {
        throw Error("--passes: need at least one pass");
    }
    if (!std::isfinite(options.time) || options.time < 0.0) {
        throw Error("--time: " + std::to_string(options.time) + " is not a time >= 0");
    }
}

}  // namespace luxel::ref
