// Materials, images, lights, cameras and the node hierarchy.

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include <tiny_gltf.h>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "gltf_internal.hpp"

namespace luxel::scene::gltf_detail {
namespace {

/// A JSON double as float; values beyond float's range (or infinite) fail instead of becoming
/// infinities or undefined conversions.
float to_float(const ImportContext& context, double value, const std::string& what) {
    if (!std::isfinite(value) || std::fabs(value) > std::numeric_limits<float>::max()) {
        context.fail(what + " is not a finite number");
    }
    return static_cast<float>(value);
}

/// A factor the specification keeps in [0, 1]: clamped with a warning when outside.
float unit_factor(const ImportContext& context, double value, const std::string& what) {
    const float factor = to_float(context, value, what);
    if (factor < 0.0f || factor > 1.0f) {
        context.warn(what + " " + std::to_string(factor) + " is outside [0, 1]; clamped");
        return std::clamp(factor, 0.0f, 1.0f);
    }
    return factor;
}

/// A fixed-size number array (baseColorFactor, translation, ...): empty means the default.
template <std::size_t N>
std::array<float, N> numbers(const ImportContext& context, const std::vector<double>& values,
                             const std::array<float, N>& fallback, const std::string& what) {
    if (values.empty()) {
        return fallback;
    }
    if (values.size() != N) {
        context.fail(what + " has " + std::to_string(values.size()) + " numbers, expected " +
                     std::to_string(N));
    }
    std::array<float, N> out{};
    for (std::size_t i = 0; i < N; ++i) {
        out[i] = to_float(context, values[i], what);
    }
    return out;
}

/// A number inside an extension object; absent keeps `fallback`, a wrong type fails.
float extension_number(const ImportContext& context, const nlohmann::json& extension,
                       const char* key, float fallback, const std::string& what) {
    if (!extension.is_object() || !extension.contains(key)) {
        return fallback;
    }
    const nlohmann::json& value = extension.at(key);
    if (!value.is_number()) {
        context.fail(what + "." + key + " is not a number");
    }
    return to_float(context, value.get<double>(), what + "." + key);
}

/// KHR_materials_volume: the thickness and what the inside absorbs. thicknessTexture is not
/// read (the factor holds everywhere), which the author is told.
void import_volume(const ImportContext& context, const nlohmann::json& volume,
                   const std::string& where, Material& material) {
    if (volume.is_null()) {
        return;
    }
    if (!volume.is_object()) {
        context.fail(where + ": KHR_materials_volume is not an object");
    }
    material.thickness =
        extension_number(context, volume, "thicknessFactor", 0.0f, where + " volume");
    if (material.thickness < 0.0f) {
        context.fail(where + ": volume thicknessFactor must not be negative");
    }
    if (volume.contains("attenuationDistance")) {
        material.attenuation_distance =
            extension_number(context, volume, "attenuationDistance", 1.0f, where + " volume");
        if (!(material.attenuation_distance > 0.0f)) {
            context.fail(where + ": volume attenuationDistance must be positive");
        }
    }
    if (volume.contains("attenuationColor")) {
        const nlohmann::json& colour = volume.at("attenuationColor");
        if (!colour.is_array() || colour.size() != 3) {
            context.fail(where + ": volume attenuationColor must be an array of three numbers");
        }
        for (std::size_t c = 0; c < 3; ++c) {
            if (!colour[c].is_number()) {
                context.fail(where + ": volume attenuationColor must be an array of three numbers");
            }
            material.attenuation_color[static_cast<glm::length_t>(c)] =
                unit_factor(context, colour[c].get<double>(), where + " volume attenuationColor");
        }
    }
    if (volume.contains("thicknessTexture")) {
        context.warn(where + ": the volume's thicknessTexture is not read; its thicknessFactor " +
                     std::to_string(material.thickness) + " holds everywhere");
    }
}

bool is_png(const std::vector<unsigned char>& bytes) {
    static constexpr unsigned char kSignature[] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
    return bytes.size() >= sizeof(kSignature) &&
           std::equal(std::begin(kSignature), std::end(kSignature), bytes.begin());
}

bool is_jpeg(const std::vector<unsigned char>& bytes) {
    return bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF;
}

/// The scene image a material's texture slot samples, or -1 (none, or no PNG/JPEG source).
/// `slot` names it in messages ("baseColorTexture", "emissiveTexture").
int import_texture(ImportContext& context, const tinygltf::TextureInfo& info, const char* slot,
                   const std::string& where) {
    const tinygltf::Model& model = context.model();
    if (info.index < 0) {
        return -1;
    }
    if (static_cast<std::size_t>(info.index) >= model.textures.size()) {
        context.fail(where + ": " + slot + " " + std::to_string(info.index) + " out of range");
    }
    if (info.texCoord != 0) {
        context.warn(where + ": " + slot + " uses TEXCOORD_" + std::to_string(info.texCoord) +
                     "; luxel samples it with TEXCOORD_0");
    }
    const tinygltf::Texture& texture = model.textures[static_cast<std::size_t>(info.index)];
    if (texture.source < 0) {
        context.warn(where + ": texture " + std::to_string(info.index) +
                     " has no PNG or JPEG source; ignored");
        return -1;
    }
    return context.scene_image(texture.source, where);
}

Light convert_light(const ImportContext& context, const tinygltf::Light& source,
                    const std::string& where) {
    Light light;
    light.name = source.name;
    if (source.type == "point") {
        light.type = LightType::Point;
    } else if (source.type == "spot") {
        light.type = LightType::Spot;
    } else if (source.type == "directional") {
        light.type = LightType::Directional;
    } else {
        context.fail(where + ": unknown type '" + source.type + "'");
    }
    const auto color = numbers<3>(context, source.color, {1.0f, 1.0f, 1.0f}, where + " color");
    light.color = glm::vec3(color[0], color[1], color[2]);
    light.intensity = to_float(context, source.intensity, where + " intensity");
    light.range = to_float(context, source.range, where + " range");
    if (light.color.r < 0.0f || light.color.g < 0.0f || light.color.b < 0.0f ||
        light.intensity < 0.0f || light.range < 0.0f) {
        context.fail(where + ": colour, intensity and range must not be negative");
    }
    if (light.type == LightType::Spot) {
        light.inner_cone_angle =
            to_float(context, source.spot.innerConeAngle, where + " innerConeAngle");
        light.outer_cone_angle =
            to_float(context, source.spot.outerConeAngle, where + " outerConeAngle");
        if (!(light.inner_cone_angle >= 0.0f && light.inner_cone_angle < light.outer_cone_angle &&
              light.outer_cone_angle <= std::numbers::pi_v<float> / 2.0f)) {
            context.fail(where + ": spot cone angles must satisfy 0 <= inner < outer <= pi/2");
        }
    }
    return light;
}

Camera convert_camera(const ImportContext& context, const tinygltf::Camera& source,
                      const std::string& where) {
    Camera camera;
    camera.name = source.name;
    if (source.type == "perspective") {
        const tinygltf::PerspectiveCamera& p = source.perspective;
        camera.perspective = true;
        camera.yfov = to_float(context, p.yfov, where + " yfov");
        camera.znear = to_float(context, p.znear, where + " znear");
        // tinygltf reads an absent zfar or aspectRatio as 0.
        if (p.zfar != 0.0) {
            camera.zfar = to_float(context, p.zfar, where + " zfar");
        }
        if (p.aspectRatio != 0.0) {
            camera.aspect_ratio = to_float(context, p.aspectRatio, where + " aspectRatio");
        }
    } else if (source.type == "orthographic") {
        const tinygltf::OrthographicCamera& o = source.orthographic;
        camera.perspective = false;
        camera.xmag = to_float(context, o.xmag, where + " xmag");
        camera.ymag = to_float(context, o.ymag, where + " ymag");
        camera.znear = to_float(context, o.znear, where + " znear");
        camera.zfar = to_float(context, o.zfar, where + " zfar");
    } else {
        context.fail(where + ": unknown type '" + source.type + "'");
    }
    return camera;
}

/// Splits a node matrix into T, R, S. glTF requires node matrices to be decomposable
/// (no shear, no projection); a projective one fails, a sheared one is approximated.
void decompose_matrix(const ImportContext& context, const std::array<float, 16>& values, Node& node,
                      const std::string& where) {
    const glm::mat4 m = glm::make_mat4(values.data());  // glTF stores columns, as GLM does
    constexpr float kTolerance = 1e-5f;
    if (std::fabs(m[0][3]) > kTolerance || std::fabs(m[1][3]) > kTolerance ||
        std::fabs(m[2][3]) > kTolerance || std::fabs(m[3][3] - 1.0f) > kTolerance) {
        context.fail(where + ": matrix is not affine (its last row is not 0 0 0 1)");
    }
    node.translation = glm::vec3(m[3]);
    glm::vec3 columns[3] = {glm::vec3(m[0]), glm::vec3(m[1]), glm::vec3(m[2])};
    glm::vec3 scale(glm::length(columns[0]), glm::length(columns[1]), glm::length(columns[2]));
    if (glm::determinant(glm::mat3(m)) < 0.0f) {
        scale.x = -scale.x;  // a mirror: one negative scale and a proper rotation
    }
    node.scale = scale;
    if (scale.x == 0.0f || scale.y == 0.0f || scale.z == 0.0f) {
        return;  // a collapsed axis leaves the rotation undefined; identity is as good as any
    }
    for (int axis = 0; axis < 3; ++axis) {
        columns[axis] /= scale[axis];
    }
    if (std::fabs(glm::dot(columns[0], columns[1])) > 1e-3f ||
        std::fabs(glm::dot(columns[1], columns[2])) > 1e-3f ||
        std::fabs(glm::dot(columns[0], columns[2])) > 1e-3f) {
        context.warn(where + ": matrix has shear, which TRS cannot hold; approximated");
    }
    node.rotation = glm::normalize(glm::quat_cast(glm::mat3(columns[0], columns[1], columns[2])));
}

void import_transform(const ImportContext& context, const tinygltf::Node& source, Node& node,
                      const std::string& where) {
    if (!source.matrix.empty()) {
        decompose_matrix(context, numbers<16>(context, source.matrix, {}, where + " matrix"), node,
                         where);
        return;
    }
    const auto t = numbers<3>(context, source.translation, {0, 0, 0}, where + " translation");
    const auto r = numbers<4>(context, source.rotation, {0, 0, 0, 1}, where + " rotation");
    const auto s = numbers<3>(context, source.scale, {1, 1, 1}, where + " scale");
    node.translation = glm::vec3(t[0], t[1], t[2]);
    node.scale = glm::vec3(s[0], s[1], s[2]);
    const glm::quat rotation(r[3], r[0], r[1], r[2]);
    const float length = glm::length(rotation);
    if (!(length > 1e-6f) || !std::isfinite(length)) {
        context.fail(where + ": rotation is not a unit quaternion");
    }
    node.rotation = rotation / length;
}

/// Checks the types of the `extras.luxel` keys luxel reads (docs/LEVELS.md), so that the
/// systems that read them later (switches, bounces, waves) never meet a string where a number
/// belongs: a wrong type here names the file, the node and the key.
/// A boolean flag of extras.luxel: true or false, or the integer 1 or 0, which is how Blender 3
/// keeps a boolean custom property and how its glTF exporter writes it. Absent: nullopt.
/// Anything else fails the load naming the node and the key.
std::optional<bool> flag(const ImportContext& context, const nlohmann::json& luxel, const char* key,
                         const std::string& where) {
    const auto found = luxel.find(key);
    if (found == luxel.end()) {
        return std::nullopt;
    }
    if (found->is_boolean()) {
        return found->get<bool>();
    }
    if (found->is_number_integer() && (*found == 0 || *found == 1)) {
        return *found == 1;
    }
    context.fail(where + ": extras.luxel." + key + " must be true or false (or 1 or 0), got " +
                 found->dump());
}

/// The ranges of extras.luxel.wave (world/vertex_wave.hpp) beyond its types: a wave the vertex
/// system could not draw is a mistake in the file, named here rather than shown as a flat or
/// torn surface. Called after the types are checked.
void check_wave(const ImportContext& context, const nlohmann::json& wave,
                const std::string& where) {
    const std::string name = where + ": extras.luxel.wave";
    const auto number = [&](const char* key, double fallback) {
        const auto found = wave.find(key);
        return found != wave.end() ? found->get<double>() : fallback;
    };
    // Defaults as WaveParameters': 2 cm, 0.5 m.
    const double wavelength = number("wavelength", 0.5);
    const double amplitude = number("amplitude", 0.02);
    if (!(wavelength > 0.0) || wavelength > 1e4) {
        context.fail(name + ".wavelength must be more than 0 and at most 10 km, got " +
                     std::to_string(wavelength));
    }
    // Higher than its length the surface folds over itself: not water.
    if (!(amplitude >= 0.0) || amplitude > wavelength) {
        context.fail(name + ".amplitude must be from 0 to the wavelength (" +
                     std::to_string(wavelength) + " m), got " + std::to_string(amplitude));
    }
    if (const auto direction = wave.find("direction"); direction != wave.end()) {
        if (!direction->is_array() || direction->size() != 2 || !(*direction)[0].is_number() ||
            !(*direction)[1].is_number() || !std::isfinite((*direction)[0].get<double>()) ||
            !std::isfinite((*direction)[1].get<double>())) {
            context.fail(name + ".direction must be two numbers [x, z]");
        }
        if (std::hypot((*direction)[0].get<double>(), (*direction)[1].get<double>()) < 1e-6) {
            context.fail(name + ".direction must not be [0, 0]: the wave needs a way to travel");
        }
    }
}

void check_extras_types(const ImportContext& context, const nlohmann::json& luxel,
                        const std::string& where) {
    struct Shape {
        const char* key;
        std::initializer_list<const char*> numbers;  ///< finite numbers inside the object
    };
    static const Shape kObjects[] = {
        {"switch", {"period", "on", "phase"}},
        {"bounce", {"height", "period"}},
        {"wave", {"amplitude", "wavelength", "speed"}},
    };
    for (const Shape& shape : kObjects) {
        const auto found = luxel.find(shape.key);
        if (found == luxel.end()) {
            continue;
        }
        const std::string name = where + ": extras.luxel." + shape.key;
        if (!found->is_object()) {
            context.fail(name + " must be a JSON object, got " + found->type_name());
        }
        for (const char* field : shape.numbers) {
            const auto value = found->find(field);
            if (value != found->end() &&
                (!value->is_number() || !std::isfinite(value->get<double>()))) {
                context.fail(name + "." + field + " must be a finite number, got " + value->dump());
            }
        }
    }
    if (const auto wave = luxel.find("wave"); wave != luxel.end()) {
        check_wave(context, *wave, where);
    }
    for (const char* key : {"portal", "furnace"}) {
        (void)flag(context, luxel, key, where);
    }
    if (const auto lightmap = luxel.find("lightmap");
        lightmap != luxel.end() && !lightmap->is_object()) {
        context.fail(where +
                     ": extras.luxel.lightmap must be a JSON object (luxel-prep writes it)");
    }
}

/// The largest light radius a level may give: a sphere wider than a stadium is a unit mistake
/// (centimetres written as metres), not a lamp.
constexpr double kMaxLightRadius = 100.0;

/// extras.luxel.light_radius (docs/LEVELS.md): metres, from 0 (a point) to kMaxLightRadius.
/// Absent: 0.
float light_radius(const ImportContext& context, const nlohmann::json& luxel,
                   const std::string& where) {
    const auto found = luxel.find("light_radius");
    if (found == luxel.end()) {
        return 0.0f;
    }
    if (!found->is_number() || !std::isfinite(found->get<double>()) || found->get<double>() < 0.0 ||
        found->get<double>() > kMaxLightRadius) {
        context.fail(where + ": extras.luxel.light_radius must be a number of metres from 0 to " +
                     std::to_string(static_cast<int>(kMaxLightRadius)) + ", got " + found->dump());
    }
    return static_cast<float>(found->get<double>());
}

/// Reads `extras.luxel` into NodeFlags. Wrong types fail: a misspelt flag silently ignored
/// would light a level wrongly with no hint why.
void import_flags(const ImportContext& context, const tinygltf::Node& source, Node& node,
                  const std::string& where) {
    const nlohmann::json extras = parse_kept_json(source.extras_json_string);
    if (!extras.is_object() || !extras.contains("luxel")) {
        return;
    }
    const nlohmann::json& luxel = extras.at("luxel");
    if (!luxel.is_object()) {
        context.fail(where + ": extras.luxel must be a JSON object");
    }
    if (const std::optional<bool> dynamic = flag(context, luxel, "dynamic", where)) {
        node.flags.dynamic = *dynamic;
    }
    if (const std::optional<bool> enabled = flag(context, luxel, "enabled", where)) {
        node.flags.light_enabled = *enabled;
    }
    check_extras_types(context, luxel, where);
    node.flags.light_radius = light_radius(context, luxel, where);
    node.flags.raw = luxel;
}

int node_light(const ImportContext& context, const tinygltf::Node& source,
               const std::string& where) {
    const nlohmann::json extensions = parse_kept_json(source.extensions_json_string);
    if (!extensions.is_object() || !extensions.contains("KHR_lights_punctual")) {
        return -1;
    }
    const nlohmann::json& reference = extensions.at("KHR_lights_punctual");
    if (!reference.is_object() || !reference.contains("light") ||
        !reference.at("light").is_number_integer()) {
        context.fail(where + ": KHR_lights_punctual.light must be an integer");
    }
    const auto light = reference.at("light").get<std::int64_t>();
    if (light < 0 || static_cast<std::uint64_t>(light) >= context.scene().lights.size()) {
        context.fail(where + ": light " + std::to_string(light) + " out of range");
    }
    return static_cast<int>(light);
}

/// Checks the hierarchy is a forest within the depth limit: walking down from the
/// parentless nodes must reach every node (a node it misses sits on a cycle).
void check_hierarchy(const ImportContext& context) {
    const std::vector<Node>& nodes = context.scene().nodes;
    std::vector<std::size_t> depth(nodes.size(), 0);
    std::vector<bool> reached(nodes.size(), false);
    std::vector<std::size_t> pending;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        if (nodes[i].parent < 0) {
            pending.push_back(i);
            reached[i] = true;
        }
    }
    while (!pending.empty()) {
        const std::size_t current = pending.back();
        pending.pop_back();
        if (depth[current] >= context.options().max_node_depth) {
            context.fail("node " + std::to_string(current) +
                         " is nested deeper than the limit of " +
                         std::to_string(context.options().max_node_depth) + " levels");
        }
        for (const int child : nodes[current].children) {
            const auto c = static_cast<std::size_t>(child);
            depth[c] = depth[current] + 1;
            reached[c] = true;
            pending.push_back(c);
        }
    }
    const auto unreached = std::find(reached.begin(), reached.end(), false);
    if (unreached != reached.end()) {
        context.fail("node " + std::to_string(unreached - reached.begin()) +
                     " is part of a cycle in the node hierarchy");
    }
}

}  // namespace

int ImportContext::scene_image(int gltf_image, const std::string& where) {
    const tinygltf::Model& source = model();
    if (gltf_image < 0 || static_cast<std::size_t>(gltf_image) >= source.images.size()) {
        fail(where + ": image " + std::to_string(gltf_image) + " out of range");
    }
    image_map_.resize(source.images.size(), -2);  // -2: not imported yet
    int& mapped = image_map_[static_cast<std::size_t>(gltf_image)];
    if (mapped != -2) {
        return mapped;
    }
    const tinygltf::Image& image = source.images[static_cast<std::size_t>(gltf_image)];
    const std::string image_where = label("image", static_cast<std::size_t>(gltf_image),
                                          image.name.empty() ? image.uri : image.name);
    if (image.image.empty()) {
        fail(image_where + ": cannot read its data" +
             (image.uri.empty() ? std::string() : " from '" + image.uri + "'"));
    }
    Image out;
    out.name = image.name;
    // The bytes decide, not the declared mime type: a wrong declaration is common and harmless.
    if (is_png(image.image)) {
        out.mime_type = "image/png";
    } else if (is_jpeg(image.image)) {
        out.mime_type = "image/jpeg";
    } else {
        warn(image_where + " is neither PNG nor JPEG; textures using it are ignored");
        mapped = -1;
        return mapped;
    }
    out.encoded.assign(image.image.begin(), image.image.end());
    scene().images.push_back(std::move(out));
    mapped = static_cast<int>(scene().images.size() - 1);
    return mapped;
}

void import_materials(ImportContext& context) {
    const tinygltf::Model& model = context.model();
    for (std::size_t i = 0; i < model.materials.size(); ++i) {
        const tinygltf::Material& source = model.materials[i];
        const std::string where = label("material", i, source.name);
        const tinygltf::PbrMetallicRoughness& pbr = source.pbrMetallicRoughness;
        Material material;
        material.name = source.name;
        const auto base =
            numbers<4>(context, pbr.baseColorFactor, {1, 1, 1, 1}, where + " baseColorFactor");
        for (int c = 0; c < 4; ++c) {
            material.base_color[c] =
                unit_factor(context, base[static_cast<std::size_t>(c)], where + " baseColorFactor");
        }
        material.metallic = unit_factor(context, pbr.metallicFactor, where + " metallicFactor");
        material.roughness = unit_factor(context, pbr.roughnessFactor, where + " roughnessFactor");
        const auto emissive =
            numbers<3>(context, source.emissiveFactor, {0, 0, 0}, where + " emissiveFactor");
        for (int c = 0; c < 3; ++c) {
            material.emissive[c] = unit_factor(context, emissive[static_cast<std::size_t>(c)],
                                               where + " emissiveFactor");
        }
        material.double_sided = source.doubleSided;
        material.base_color_image =
            import_texture(context, pbr.baseColorTexture, "baseColorTexture", where);
        material.emissive_image =
            import_texture(context, source.emissiveTexture, "emissiveTexture", where);

        const nlohmann::json extensions = parse_kept_json(source.extensions_json_string);
        if (extensions.is_object()) {
            const auto extension = [&extensions](const char* name) {
                return extensions.contains(name) ? extensions.at(name) : nlohmann::json();
            };
            material.emissive_strength =
                extension_number(context, extension("KHR_materials_emissive_strength"),
                                 "emissiveStrength", 1.0f, where + " emissive strength");
            if (material.emissive_strength < 0.0f) {
                context.fail(where + ": emissiveStrength must not be negative");
            }
            material.transmission =
                unit_factor(context,
                            extension_number(context, extension("KHR_materials_transmission"),
                                             "transmissionFactor", 0.0f, where + " transmission"),
                            where + " transmissionFactor");
            material.ior = extension_number(context, extension("KHR_materials_ior"), "ior", 1.5f,
                                            where + " ior");
            if (material.ior != 0.0f && material.ior < 1.0f) {
                context.fail(where + ": ior " + std::to_string(material.ior) +
                             " must be 0 or at least 1");
            }
            import_volume(context, extension("KHR_materials_volume"), where, material);
        }
        context.scene().materials.push_back(std::move(material));
    }
}

void import_lights(ImportContext& context) {
    const tinygltf::Model& model = context.model();
    for (std::size_t i = 0; i < model.lights.size(); ++i) {
        context.scene().lights.push_back(
            convert_light(context, model.lights[i], label("light", i, model.lights[i].name)));
    }
}

void import_cameras(ImportContext& context) {
    const tinygltf::Model& model = context.model();
    for (std::size_t i = 0; i < model.cameras.size(); ++i) {
        context.scene().cameras.push_back(
            convert_camera(context, model.cameras[i], label("camera", i, model.cameras[i].name)));
    }
    // The projection rules live in one place: Scene::validate's camera checks. Its message
    // says which ranges apply; the node holding the camera is what an author looks for.
    for (std::size_t i = 0; i < context.scene().cameras.size(); ++i) {
        Scene probe;
        probe.cameras.push_back(context.scene().cameras[i]);
        try {
            probe.validate();
        } catch (const std::exception& e) {
            const std::string message = e.what();
            const std::size_t ranges = message.find(": projection parameters");
            std::string where = label("camera", i, model.cameras[i].name);
            for (std::size_t n = 0; n < model.nodes.size(); ++n) {
                if (model.nodes[n].camera == static_cast<int>(i)) {
                    where += " (on " + label("node", n, model.nodes[n].name) + ")";
                    break;
                }
            }
            context.fail(where +
                         (ranges == std::string::npos ? ": " + message : message.substr(ranges)));
        }
    }
}

void import_nodes(ImportContext& context) {
    const tinygltf::Model& model = context.model();
    Scene& scene = context.scene();
    if (model.nodes.size() > context.options().max_nodes) {
        context.fail("the file has " + std::to_string(model.nodes.size()) +
                     " nodes, more than the limit of " +
                     std::to_string(context.options().max_nodes));
    }
    scene.nodes.resize(model.nodes.size());
    for (std::size_t i = 0; i < model.nodes.size(); ++i) {
        const tinygltf::Node& source = model.nodes[i];
        Node& node = scene.nodes[i];
        const std::string where = label("node", i, source.name);
        node.name = source.name;
        if (source.mesh < -1 || source.mesh >= static_cast<int>(scene.meshes.size())) {
            context.fail(where + ": mesh " + std::to_string(source.mesh) + " out of range");
        }
        if (source.camera < -1 || source.camera >= static_cast<int>(scene.cameras.size())) {
            context.fail(where + ": camera " + std::to_string(source.camera) + " out of range");
        }
        if (source.skin < -1 || source.skin >= static_cast<int>(model.skins.size())) {
            context.fail(where + ": skin " + std::to_string(source.skin) + " out of range");
        }
        if (source.skin >= 0 && source.mesh < 0) {
            context.fail(where + ": has a skin but no mesh");
        }
        node.skin = source.skin;
        node.mesh = source.mesh;
        node.camera = source.camera;
        node.light = node_light(context, source, where);
        import_transform(context, source, node, where);
        import_flags(context, source, node, where);

        for (const int child : source.children) {
            if (child < 0 || static_cast<std::size_t>(child) >= model.nodes.size()) {
                context.fail(where + ": child " + std::to_string(child) + " out of range");
            }
            if (static_cast<std::size_t>(child) == i) {
                context.fail(where + ": is its own child");
            }
            Node& child_node = scene.nodes[static_cast<std::size_t>(child)];
            if (child_node.parent == static_cast<int>(i)) {
                context.fail(where + ": lists child " + std::to_string(child) + " twice");
            }
            if (child_node.parent != -1) {
                context.fail("node " + std::to_string(child) + " has two parents (nodes " +
                             std::to_string(child_node.parent) + " and " + std::to_string(i) + ")");
            }
            child_node.parent = static_cast<int>(i);
            node.children.push_back(child);
        }
    }
    check_hierarchy(context);
}

}  // namespace luxel::scene::gltf_detail
