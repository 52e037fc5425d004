// Scene -> glTF: one binary buffer, one bufferView per accessor or image, and every value
// inside the ranges the Khronos validator checks (unit quaternions and normals, colour
// factors in [0, 1] with the excess moved into intensities).

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>

#include "gltf_internal.hpp"

namespace luxel::scene::gltf_detail {
namespace {

using nlohmann::json;

constexpr int kFloat = 5126;
constexpr int kUnsignedShort = 5123;
constexpr int kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;

/// The binary buffer and the bufferViews and accessors that describe it.
class BufferBuilder {
  public:
    /// Appends bytes as a new bufferView starting on a 4-byte boundary (every component type
    /// luxel writes is at most 4 bytes, so every accessor is aligned).
    int add_view(const void* data, std::size_t size, std::optional<int> target) {
        bin_.resize((bin_.size() + 3) / 4 * 4, 0);
        json view = {{"buffer", 0}, {"byteOffset", bin_.size()}, {"byteLength", size}};
        if (target) {
            view["target"] = *target;
        }
        const auto* bytes = static_cast<const std::uint8_t*>(data);
        bin_.insert(bin_.end(), bytes, bytes + size);
        views_.push_back(std::move(view));
        return static_cast<int>(views_.size() - 1);
    }

    /// A float accessor of `components` per element; min/max when asked (POSITION and
    /// animation inputs require them).
    int add_floats(const float* data, std::size_t count, int components, bool bounds,
                   std::optional<int> target) {
        const auto n = static_cast<std::size_t>(components);
        const int view = add_view(data, count * n * sizeof(float), target);
        json accessor = {{"bufferView", view},
                         {"componentType", kFloat},
                         {"count", count},
                         {"type", type_name(components)}};
        if (bounds) {
            std::vector<float> low(data, data + n);
            std::vector<float> high(data, data + n);
            for (std::size_t e = 1; e < count; ++e) {
                for (std::size_t c = 0; c < n; ++c) {
                    low[c] = std::min(low[c], data[e * n + c]);
                    high[c] = std::max(high[c], data[e * n + c]);
                }
            }
            accessor["min"] = low;
            accessor["max"] = high;
        }
        accessors_.push_back(std::move(accessor));
        return static_cast<int>(accessors_.size() - 1);
    }

    /// Triangle indices as UNSIGNED_SHORT when every index fits below 65535 (the primitive
    /// restart value glTF forbids), UNSIGNED_INT otherwise.
    int add_indices(const std::vector<std::uint32_t>& indices, std::size_t vertex_count) {
        int view = 0;
        int component_type = kUnsignedInt;
        if (vertex_count <= 65535) {
            std::vector<std::uint16_t> narrow(indices.begin(), indices.end());
            view =
                add_view(narrow.data(), narrow.size() * sizeof(std::uint16_t), kElementArrayBuffer);
            component_type = kUnsignedShort;
        } else {
            view = add_view(indices.data(), indices.size() * sizeof(std::uint32_t),
                            kElementArrayBuffer);
        }
        accessors_.push_back({{"bufferView", view},
                              {"componentType", component_type},
                              {"count", indices.size()},
                              {"type", "SCALAR"}});
        return static_cast<int>(accessors_.size() - 1);
    }

    /// JOINTS_0 as UNSIGNED_SHORT VEC4 (what every joint index luxel keeps fits).
    int add_joints(const std::vector<glm::u16vec4>& joints) {
        static_assert(sizeof(glm::u16vec4) == 4 * sizeof(std::uint16_t));
        const int view =
            add_view(joints.data(), joints.size() * sizeof(glm::u16vec4), kArrayBuffer);
        accessors_.push_back({{"bufferView", view},
                              {"componentType", kUnsignedShort},
                              {"count", joints.size()},
                              {"type", "VEC4"}});
        return static_cast<int>(accessors_.size() - 1);
    }

    [[nodiscard]] json& views() { return views_; }
    [[nodiscard]] json& accessors() { return accessors_; }
    [[nodiscard]] std::vector<std::uint8_t>& bin() { return bin_; }

  private:
    static const char* type_name(int components) {
        switch (components) {
            case 1:
                return "SCALAR";
            case 2:
                return "VEC2";
            case 3:
                return "VEC3";
            case 16:
                return "MAT4";
            default:
                return "VEC4";
        }
    }

    json views_ = json::array();
    json accessors_ = json::array();
    std::vector<std::uint8_t> bin_;
};

template <typename Vec>
const float* flat(const std::vector<Vec>& values) {
    static_assert(sizeof(Vec) == sizeof(float) * static_cast<std::size_t>(Vec::length()));
    return reinterpret_cast<const float*>(values.data());
}

json vec_json(const float* values, int n) {
    return std::vector<float>(values, values + n);
}

/// KHR_materials_volume's object for `material`, empty when it has the defaults (a thin wall
/// that absorbs nothing). An infinite attenuation distance is the extension's default and has
/// no JSON number: it is left out.
json volume_json(const Material& material) {
    json volume = json::object();
    if (material.thickness != 0.0f) {
        volume["thicknessFactor"] = material.thickness;
    }
    if (std::isfinite(material.attenuation_distance)) {
        volume["attenuationDistance"] = material.attenuation_distance;
    }
    if (material.attenuation_color != glm::vec3(1.0f)) {
        volume["attenuationColor"] = vec_json(&material.attenuation_color.x, 3);
    }
    return volume;
}

/// Splits a colour that may exceed 1 into glTF's [0, 1] factor and a multiplier for the
/// intensity that goes with it.
float normalise_colour(glm::vec3& colour) {
    const float largest = std::max({colour.r, colour.g, colour.b});
    if (largest <= 1.0f) {
        return 1.0f;
    }
    colour /= largest;
    return largest;
}

class DocumentWriter {
  public:
    explicit DocumentWriter(const Scene& scene) : scene_(scene) {}

    EncodedGltf write() {
        document_["asset"] = {{"version", "2.0"}, {"generator", "luxel"}};
        write_images();
        write_materials();
        write_meshes();
        write_lights();
        write_cameras();
        write_nodes();
        write_skins();
        write_animations();
        json scene = json::object();
        if (!scene_.name.empty()) {
            scene["name"] = scene_.name;
        }
        if (!scene_.roots.empty()) {
            scene["nodes"] = scene_.roots;
        }
        if (json sky = sky_extras(scene_.sky); !sky.is_null()) {
            scene["extras"]["luxel"]["sky"] = std::move(sky);
        }
        document_["scenes"] = json::array({scene});
        document_["scene"] = 0;
        if (!buffer_.views().empty()) {
            document_["bufferViews"] = buffer_.views();
        }
        if (!buffer_.accessors().empty()) {
            document_["accessors"] = buffer_.accessors();
        }
        if (!buffer_.bin().empty()) {
            document_["buffers"] = json::array({{{"byteLength", buffer_.bin().size()}}});
        }
        if (!extensions_used_.empty()) {
            document_["extensionsUsed"] = extensions_used_;
        }
        return {std::move(document_), std::move(buffer_.bin())};
    }

  private:
    void use_extension(const std::string& name) {
        if (std::find(extensions_used_.begin(), extensions_used_.end(), name) ==
            extensions_used_.end()) {
            extensions_used_.push_back(name);
        }
    }

    void write_images() {
        json images = json::array();
        json textures = json::array();
        for (std::size_t i = 0; i < scene_.images.size(); ++i) {
            const Image& image = scene_.images[i];
            json entry = {
                {"bufferView", buffer_.add_view(image.encoded.data(), image.encoded.size(), {})},
                {"mimeType", image.mime_type}};
            if (!image.name.empty()) {
                entry["name"] = image.name;
            }
            images.push_back(std::move(entry));
            textures.push_back({{"source", i}});  // one texture per image, default sampling
        }
        if (!images.empty()) {
            document_["images"] = std::move(images);
            document_["textures"] = std::move(textures);
        }
    }

    void write_materials() {
        json materials = json::array();
        for (const Material& material : scene_.materials) {
            json pbr = json::object();
            if (material.base_color != glm::vec4(1.0f)) {
                pbr["baseColorFactor"] = vec_json(&material.base_color.x, 4);
            }
            if (material.base_color_image >= 0) {
                pbr["baseColorTexture"] = {{"index", material.base_color_image}};
            }
            if (material.metallic != 1.0f) {
                pbr["metallicFactor"] = material.metallic;
            }
            if (material.roughness != 1.0f) {
                pbr["roughnessFactor"] = material.roughness;
            }
            json entry = json::object();
            if (!material.name.empty()) {
                entry["name"] = material.name;
            }
            entry["pbrMetallicRoughness"] = std::move(pbr);
            glm::vec3 emissive = material.emissive;
            const float strength = material.emissive_strength * normalise_colour(emissive);
            if (emissive != glm::vec3(0.0f)) {
                entry["emissiveFactor"] = vec_json(&emissive.x, 3);
            }
            if (material.emissive_image >= 0) {
                entry["emissiveTexture"] = {{"index", material.emissive_image}};
            }
            json extensions = json::object();
            if (strength != 1.0f) {
                extensions["KHR_materials_emissive_strength"] = {{"emissiveStrength", strength}};
            }
            if (material.transmission != 0.0f) {
                extensions["KHR_materials_transmission"] = {
                    {"transmissionFactor", material.transmission}};
            }
            if (material.ior != 1.5f) {
                extensions["KHR_materials_ior"] = {{"ior", material.ior}};
            }
            if (json volume = volume_json(material); !volume.empty()) {
                extensions["KHR_materials_volume"] = std::move(volume);
            }
            for (const auto& [name, value] : extensions.items()) {
                use_extension(name);
            }
            if (!extensions.empty()) {
                entry["extensions"] = std::move(extensions);
            }
            if (material.double_sided) {
                entry["doubleSided"] = true;
            }
            materials.push_back(std::move(entry));
        }
        if (!materials.empty()) {
            document_["materials"] = std::move(materials);
        }
    }

    json write_primitive(const Primitive& primitive) {
        json attributes = {
            {"POSITION", buffer_.add_floats(flat(primitive.positions), primitive.positions.size(),
                                            3, true, kArrayBuffer)}};
        // The validator requires unit normals; a zero one has no direction, so the whole
        // attribute is left out (as the loader does) rather than invented.
        std::vector<glm::vec3> normals = primitive.normals;
        for (glm::vec3& normal : normals) {
            const float length = glm::length(normal);
            if (!(length > 1e-12f)) {
                normals.clear();
                break;
            }
            normal /= length;
        }
        if (!normals.empty()) {
            attributes["NORMAL"] =
                buffer_.add_floats(flat(normals), normals.size(), 3, false, kArrayBuffer);
        }
        if (!primitive.texcoords0.empty()) {
            attributes["TEXCOORD_0"] = buffer_.add_floats(
                flat(primitive.texcoords0), primitive.texcoords0.size(), 2, false, kArrayBuffer);
        }
        if (!primitive.texcoords1.empty()) {
            attributes["TEXCOORD_1"] = buffer_.add_floats(
                flat(primitive.texcoords1), primitive.texcoords1.size(), 2, false, kArrayBuffer);
            if (primitive.texcoords0.empty()) {
                // glTF numbers a primitive's TEXCOORD_n sets from 0 without gaps (the
                // validator's MESH_PRIMITIVE_INDEXED_SEMANTIC_CONTINUITY): a mesh that came
                // without texture coordinates and got light-map UVs from luxel-prep names the
                // same accessor as its set 0, which costs no bytes. Such a mesh had nothing to
                // map a texture with.
                attributes["TEXCOORD_0"] = attributes["TEXCOORD_1"];
            }
        }
        if (!primitive.joints.empty()) {
            attributes["JOINTS_0"] = buffer_.add_joints(primitive.joints);
            attributes["WEIGHTS_0"] = buffer_.add_floats(
                flat(primitive.weights), primitive.weights.size(), 4, false, kArrayBuffer);
        }
        json entry = {
            {"attributes", std::move(attributes)},
            {"indices", buffer_.add_indices(primitive.indices, primitive.positions.size())}};
        if (primitive.material >= 0) {
            entry["material"] = primitive.material;
        }
        return entry;
    }

    void write_meshes() {
        // glTF meshes need at least one primitive, and accessors at least one element: empty
        // ones are left out and the nodes that used them lose their mesh.
        json meshes = json::array();
        mesh_map_.assign(scene_.meshes.size(), -1);
        for (std::size_t m = 0; m < scene_.meshes.size(); ++m) {
            json primitives = json::array();
            for (const Primitive& primitive : scene_.meshes[m].primitives) {
                if (primitive.triangle_count() > 0) {
                    primitives.push_back(write_primitive(primitive));
                }
            }
            if (primitives.empty()) {
                continue;
            }
            json entry = {{"primitives", std::move(primitives)}};
            if (!scene_.meshes[m].name.empty()) {
                entry["name"] = scene_.meshes[m].name;
            }
            mesh_map_[m] = static_cast<int>(meshes.size());
            meshes.push_back(std::move(entry));
        }
        if (!meshes.empty()) {
            document_["meshes"] = std::move(meshes);
        }
    }

    void write_lights() {
        if (scene_.lights.empty()) {
            return;
        }
        json lights = json::array();
        for (const Light& light : scene_.lights) {
            glm::vec3 colour = light.color;
            const float intensity = light.intensity * normalise_colour(colour);
            json entry = {{"color", vec_json(&colour.x, 3)}, {"intensity", intensity}};
            if (!light.name.empty()) {
                entry["name"] = light.name;
            }
            if (light.range > 0.0f) {
                entry["range"] = light.range;
            }
            switch (light.type) {
                case LightType::Point:
                    entry["type"] = "point";
                    break;
                case LightType::Spot:
                    entry["type"] = "spot";
                    entry["spot"] = {{"innerConeAngle", light.inner_cone_angle},
                                     {"outerConeAngle", light.outer_cone_angle}};
                    break;
                case LightType::Directional:
                    entry["type"] = "directional";
                    break;
            }
            lights.push_back(std::move(entry));
        }
        document_["extensions"]["KHR_lights_punctual"] = {{"lights", std::move(lights)}};
        use_extension("KHR_lights_punctual");
    }

    void write_cameras() {
        json cameras = json::array();
        for (const Camera& camera : scene_.cameras) {
            json entry = json::object();
            if (!camera.name.empty()) {
                entry["name"] = camera.name;
            }
            if (camera.perspective) {
                json perspective = {{"yfov", camera.yfov}, {"znear", camera.znear}};
                if (camera.zfar) {
                    perspective["zfar"] = *camera.zfar;
                }
                if (camera.aspect_ratio) {
                    perspective["aspectRatio"] = *camera.aspect_ratio;
                }
                entry["type"] = "perspective";
                entry["perspective"] = std::move(perspective);
            } else {
                entry["type"] = "orthographic";
                entry["orthographic"] = {{"xmag", camera.xmag},
                                         {"ymag", camera.ymag},
                                         {"znear", camera.znear},
                                         {"zfar", camera.zfar.value_or(camera.znear + 1.0f)}};
            }
            cameras.push_back(std::move(entry));
        }
        if (!cameras.empty()) {
            document_["cameras"] = std::move(cameras);
        }
    }

    static json luxel_extras(const NodeFlags& flags) {
        json luxel = flags.raw;
        if (flags.dynamic) {
            luxel["dynamic"] = *flags.dynamic;
        } else {
            luxel.erase("dynamic");
        }
        if (!flags.light_enabled) {
            luxel["enabled"] = false;
        } else {
            luxel.erase("enabled");
        }
        if (flags.light_radius > 0.0f) {
            luxel["light_radius"] = flags.light_radius;
        } else {
            luxel.erase("light_radius");
        }
        return luxel;
    }

    void write_nodes() {
        json nodes = json::array();
        for (const Node& node : scene_.nodes) {
            json entry = json::object();
            if (!node.name.empty()) {
                entry["name"] = node.name;
            }
            if (!node.children.empty()) {
                entry["children"] = node.children;
            }
            if (node.mesh >= 0 && mesh_map_[static_cast<std::size_t>(node.mesh)] >= 0) {
                entry["mesh"] = mesh_map_[static_cast<std::size_t>(node.mesh)];
            }
            if (node.camera >= 0) {
                entry["camera"] = node.camera;
            }
            if (node.skin >= 0 && entry.contains("mesh")) {
                entry["skin"] = node.skin;  // a node that lost its (empty) mesh loses its skin
            }
            if (node.translation != glm::vec3(0.0f)) {
                entry["translation"] = vec_json(&node.translation.x, 3);
            }
            const glm::quat rotation = glm::normalize(node.rotation);
            if (rotation != glm::quat(1.0f, 0.0f, 0.0f, 0.0f)) {
                entry["rotation"] = {rotation.x, rotation.y, rotation.z, rotation.w};
            }
            if (node.scale != glm::vec3(1.0f)) {
                entry["scale"] = vec_json(&node.scale.x, 3);
            }
            if (node.light >= 0) {
                entry["extensions"]["KHR_lights_punctual"] = {{"light", node.light}};
            }
            if (json luxel = luxel_extras(node.flags); !luxel.empty()) {
                entry["extras"]["luxel"] = std::move(luxel);
            }
            nodes.push_back(std::move(entry));
        }
        if (!nodes.empty()) {
            document_["nodes"] = std::move(nodes);
        }
    }

    void write_skins() {
        json skins = json::array();
        for (const Skin& skin : scene_.skins) {
            std::vector<float> matrices;
            matrices.reserve(skin.inverse_bind_matrices.size() * 16);
            for (const glm::mat4& matrix : skin.inverse_bind_matrices) {
                matrices.insert(matrices.end(), &matrix[0][0], &matrix[0][0] + 16);
            }
            json entry = {{"joints", skin.joints},
                          {"inverseBindMatrices",
                           buffer_.add_floats(matrices.data(), skin.inverse_bind_matrices.size(),
                                              16, false, std::nullopt)}};
            if (skin.skeleton >= 0) {
                entry["skeleton"] = skin.skeleton;
            }
            if (!skin.name.empty()) {
                entry["name"] = skin.name;
            }
            skins.push_back(std::move(entry));
        }
        if (!skins.empty()) {
            document_["skins"] = std::move(skins);
        }
    }

    /// One glTF sampler: times with their bounds, and values as VEC3 or VEC4 with rotation
    /// keyframes (not cubic-spline tangents) normalised.
    json write_sampler(const AnimationSampler& sampler, AnimatedProperty property) {
        const bool rotation = property == AnimatedProperty::Rotation;
        const bool cubic = sampler.interpolation == Interpolation::CubicSpline;
        std::vector<float> values;
        values.reserve(sampler.values.size() * 4);
        for (std::size_t v = 0; v < sampler.values.size(); ++v) {
            glm::vec4 value = sampler.values[v];
            const bool keyframe = !cubic || v % 3 == 1;
            if (rotation && keyframe && glm::length(value) > 0.0f) {
                value = glm::normalize(value);
            }
            values.insert(values.end(), &value.x, &value.x + (rotation ? 4 : 3));
        }
        const int input =
            buffer_.add_floats(sampler.times.data(), sampler.times.size(), 1, true, std::nullopt);
        const int output = buffer_.add_floats(values.data(), sampler.values.size(),
                                              rotation ? 4 : 3, false, std::nullopt);
        static constexpr const char* kInterpolation[] = {"LINEAR", "STEP", "CUBICSPLINE"};
        return {{"input", input},
                {"output", output},
                {"interpolation", kInterpolation[static_cast<int>(sampler.interpolation)]}};
    }

    void write_animations() {
        json animations = json::array();
        static constexpr const char* kPath[] = {"translation", "rotation", "scale"};
        for (const Animation& animation : scene_.animations) {
            json samplers = json::array();
            json channels = json::array();
            // Samplers are written as the channels use them, once per (sampler, value width):
            // unused samplers would be flagged, and a sampler's output type follows its target.
            std::map<std::pair<int, bool>, int> written;
            for (const AnimationChannel& channel : animation.channels) {
                const bool rotation = channel.property == AnimatedProperty::Rotation;
                const auto key = std::make_pair(channel.sampler, rotation);
                auto found = written.find(key);
                if (found == written.end()) {
                    samplers.push_back(
                        write_sampler(animation.samplers[static_cast<std::size_t>(channel.sampler)],
                                      channel.property));
                    found = written.emplace(key, static_cast<int>(samplers.size() - 1)).first;
                }
                channels.push_back({{"sampler", found->second},
                                    {"target",
                                     {{"node", channel.node},
                                      {"path", kPath[static_cast<int>(channel.property)]}}}});
            }
            if (channels.empty()) {
                continue;  // glTF animations need at least one channel
            }
            json entry = {{"samplers", std::move(samplers)}, {"channels", std::move(channels)}};
            if (!animation.name.empty()) {
                entry["name"] = animation.name;
            }
            animations.push_back(std::move(entry));
        }
        if (!animations.empty()) {
            document_["animations"] = std::move(animations);
        }
    }

    const Scene& scene_;
    json document_ = json::object();
    BufferBuilder buffer_;
    std::vector<std::string> extensions_used_;
    std::vector<int> mesh_map_;
};

}  // namespace

EncodedGltf encode_scene(const Scene& scene) {
    return DocumentWriter(scene).write();
}

}  // namespace luxel::scene::gltf_detail
