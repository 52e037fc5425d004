#include "luxel/scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "luxel/runtime/error.hpp"
#include "scene_checks.hpp"

namespace luxel::scene {
namespace {

using detail::in_range;
using detail::invalid;
using detail::quoted_name;

bool finite(float v) {
    return std::isfinite(v);
}
bool finite(const glm::vec2& v) {
    return finite(v.x) && finite(v.y);
}
bool finite(const glm::vec3& v) {
    return finite(v.x) && finite(v.y) && finite(v.z);
}
bool finite(const glm::vec4& v) {
    return finite(v.x) && finite(v.y) && finite(v.z) && finite(v.w);
}

bool optional_in_range(int index, std::size_t size) {
    return index == -1 || in_range(index, size);
}
bool in_unit_interval(float v) {
    return v >= 0.0f && v <= 1.0f;
}

void validate_nodes(const Scene& scene) {
    const std::size_t count = scene.nodes.size();
    for (std::size_t i = 0; i < count; ++i) {
        const Node& node = scene.nodes[i];
        const std::string where = "node " + std::to_string(i) + quoted_name(node.name);
        if (!optional_in_range(node.parent, count)) {
            invalid(where + ": parent " + std::to_string(node.parent) + " out of range");
        }
        if (node.parent == static_cast<int>(i)) {
            invalid(where + ": is its own parent");
        }
        if (node.parent >= 0) {
            const auto& siblings = scene.nodes[static_cast<std::size_t>(node.parent)].children;
            if (std::count(siblings.begin(), siblings.end(), static_cast<int>(i)) != 1) {
                invalid(where + ": parent " + std::to_string(node.parent) +
                        " does not list it exactly once among its children");
            }
        }
        for (const int child : node.children) {
            if (!in_range(child, count) ||
                scene.nodes[static_cast<std::size_t>(child)].parent != static_cast<int>(i)) {
                invalid(where + ": child " + std::to_string(child) +
                        " is out of range or names another parent");
            }
        }
        if (!optional_in_range(node.mesh, scene.meshes.size())) {
            invalid(where + ": mesh " + std::to_string(node.mesh) + " out of range");
        }
        if (!optional_in_range(node.light, scene.lights.size())) {
            invalid(where + ": light " + std::to_string(node.light) + " out of range");
        }
        if (!optional_in_range(node.camera, scene.cameras.size())) {
            invalid(where + ": camera " + std::to_string(node.camera) + " out of range");
        }
        const glm::vec4 rotation(node.rotation.x, node.rotation.y, node.rotation.z,
                                 node.rotation.w);
        if (!finite(node.translation) || !finite(node.scale) || !finite(rotation)) {
            invalid(where + ": translation, rotation or scale is not finite");
        }
        if (glm::dot(rotation, rotation) < 1e-12f) {
            invalid(where + ": rotation is a zero quaternion");
        }
        if (!node.flags.raw.is_object()) {
            invalid(where + ": extras.luxel is not a JSON object");
        }
    }
    // With one parent per node (checked above), a node is in a cycle exactly when walking up
    // from it takes more steps than there are nodes.
    for (std::size_t i = 0; i < count; ++i) {
        int current = scene.nodes[i].parent;
        for (std::size_t steps = 0; current >= 0; ++steps) {
            if (steps > count) {
                invalid("node " + std::to_string(i) + " is part of a cycle of parents");
            }
            current = scene.nodes[static_cast<std::size_t>(current)].parent;
        }
    }
    std::set<int> seen_roots;
    for (const int root : scene.roots) {
        if (!in_range(root, count) || scene.nodes[static_cast<std::size_t>(root)].parent != -1 ||
            !seen_roots.insert(root).second) {
            invalid("root " + std::to_string(root) +
                    " is out of range, has a parent or is listed twice");
        }
    }
}

void validate_meshes(const Scene& scene) {
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
            const Primitive& primitive = mesh.primitives[p];
            const std::string where = "mesh " + std::to_string(m) + quoted_name(mesh.name) +
                                      " primitive " + std::to_string(p);
            const std::size_t vertices = primitive.positions.size();
            const auto sized = [vertices](std::size_t n) { return n == 0 || n == vertices; };
            if (!sized(primitive.normals.size()) || !sized(primitive.texcoords0.size()) ||
                !sized(primitive.texcoords1.size())) {
                invalid(where + ": normals or texture coordinates do not match the " +
                        std::to_string(vertices) + " positions");
            }
            if (primitive.indices.size() % 3 != 0) {
                invalid(where + ": index count " + std::to_string(primitive.indices.size()) +
                        " is not a multiple of 3");
            }
            for (const std::uint32_t index : primitive.indices) {
                if (index >= vertices) {
                    invalid(where + ": index " + std::to_string(index) + " out of range (" +
                            std::to_string(vertices) + " vertices)");
                }
            }
            const auto all_finite = [](const auto& values) {
                return std::all_of(values.begin(), values.end(),
                                   [](const auto& v) { return finite(v); });
            };
            if (!all_finite(primitive.positions) || !all_finite(primitive.normals) ||
                !all_finite(primitive.texcoords0) || !all_finite(primitive.texcoords1)) {
                invalid(where + ": a vertex attribute is not finite");
            }
            if (!optional_in_range(primitive.material, scene.materials.size())) {
                invalid(where + ": material " + std::to_string(primitive.material) +
                        " out of range");
            }
        }
    }
}

/// The largest colour x intensity (or emission x strength) a scene may hold. Each factor can be
/// finite while their product, and the powers and sums derived from it (x 4 pi, x photons,
/// x texels), overflow float; 1e20 leaves 18 orders of magnitude of headroom and is still far
/// beyond any physical source (the Sun's luminous intensity is about 3e27 cd, seen from 1 AU
/// as a directional light of 1.3e5 lx).
constexpr double kMaxRadiometric = 1e20;
constexpr const char* kMaxRadiometricText = "1e20";

bool below_radiometric_limit(const glm::vec3& color, float scale) {
    const double largest = std::max(
        {static_cast<double>(color.r), static_cast<double>(color.g), static_cast<double>(color.b)});
    return largest * static_cast<double>(scale) <= kMaxRadiometric;
}

void validate_materials(const Scene& scene) {
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        const Material& material = scene.materials[i];
        const std::string where = "material " + std::to_string(i) + quoted_name(material.name);
        const bool factors_valid =
            in_unit_interval(material.base_color.r) && in_unit_interval(material.base_color.g) &&
            in_unit_interval(material.base_color.b) && in_unit_interval(material.base_color.a) &&
            in_unit_interval(material.metallic) && in_unit_interval(material.roughness) &&
            in_unit_interval(material.transmission);
        if (!factors_valid) {
            invalid(where +
                    ": base colour, metallic, roughness and transmission must be in [0, 1]");
        }
        if (!finite(material.emissive) || !finite(material.emissive_strength) ||
            material.emissive.r < 0.0f || material.emissive.g < 0.0f ||
            material.emissive.b < 0.0f || material.emissive_strength < 0.0f) {
            invalid(where + ": emission must be finite and not negative");
        }
        if (!below_radiometric_limit(material.emissive, material.emissive_strength)) {
            invalid(where + ": emissive factor times emissive strength exceeds " +
                    kMaxRadiometricText + " W/(m^2 sr)");
        }
        // KHR_materials_ior allows 0 (a perfect mirror's limit) or any value from 1 up.
        if (!finite(material.ior) || (material.ior != 0.0f && material.ior < 1.0f)) {
            invalid(where + ": ior must be 0 or at least 1");
        }
        // KHR_materials_volume: an infinite attenuation distance is its default (no absorption).
        if (!finite(material.thickness) || material.thickness < 0.0f ||
            !(material.attenuation_distance > 0.0f) ||
            !in_unit_interval(material.attenuation_color.r) ||
            !in_unit_interval(material.attenuation_color.g) ||
            !in_unit_interval(material.attenuation_color.b)) {
            invalid(where +
                    ": volume thickness must be finite and not negative, attenuation distance "
                    "positive, attenuation colour in [0, 1]");
        }
        if (!optional_in_range(material.base_color_image, scene.images.size())) {
            invalid(where + ": base colour image " + std::to_string(material.base_color_image) +
                    " out of range");
        }
        if (!optional_in_range(material.emissive_image, scene.images.size())) {
            invalid(where + ": emissive image " + std::to_string(material.emissive_image) +
                    " out of range");
        }
    }
    for (std::size_t i = 0; i < scene.images.size(); ++i) {
        const Image& image = scene.images[i];
        // The first bytes must match the declared type (the validator checks the same).
        const auto& bytes = image.encoded;
        const bool png = image.mime_type == "image/png" && bytes.size() >= 8 && bytes[0] == 0x89 &&
                         bytes[1] == 'P' && bytes[2] == 'N' && bytes[3] == 'G';
        const bool jpeg = image.mime_type == "image/jpeg" && bytes.size() >= 3 &&
                          bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF;
        if (!png && !jpeg) {
            invalid("image " + std::to_string(i) + quoted_name(image.name) +
                    ": must hold PNG or JPEG bytes with a matching mime type");
        }
    }
}

constexpr float kMinYfov = 1e-4f;   ///< radians (0.006 degrees)
constexpr float kMinZnear = 1e-6f;  ///< metres
constexpr float kMinAspect = 1e-4f;
/// An orthographic half-height or half-width, in metres. The projection divides by it (and by
/// the depth range): 1e-40 passes "!= 0" and then overflows to Inf, 3e38 times an image's
/// aspect ratio overflows itself. The bounds match the world's own (kMaxWorldExtent).
constexpr float kMinMagnification = 1e-6f;
constexpr float kMaxMagnification = 1e6f;

bool magnification_in_range(float mag) {
    const float size = std::abs(mag);
    return finite(mag) && size >= kMinMagnification && size <= kMaxMagnification;
}

/// "camera 0 'name' (on node 3 'eye')": the node is what a level's author finds in an editor.
std::vector<std::string> camera_names(const Scene& scene) {
    std::vector<std::string> names(scene.cameras.size());
    for (std::size_t i = 0; i < names.size(); ++i) {
        names[i] = "camera " + std::to_string(i) + quoted_name(scene.cameras[i].name);
    }
    std::vector<bool> placed(scene.cameras.size(), false);
    for (std::size_t n = 0; n < scene.nodes.size(); ++n) {
        const int camera = scene.nodes[n].camera;
        if (in_range(camera, names.size()) && !placed[static_cast<std::size_t>(camera)]) {
            placed[static_cast<std::size_t>(camera)] = true;
            names[static_cast<std::size_t>(camera)] +=
                " (on node " + std::to_string(n) + quoted_name(scene.nodes[n].name) + ")";
        }
    }
    return names;
}

bool projection_valid(const Camera& camera) {
    const bool far_valid = !camera.zfar || (finite(*camera.zfar) && *camera.zfar > camera.znear);
    if (!finite(camera.znear) || !far_valid) {
        return false;
    }
    if (camera.perspective) {
        // Bounded away from 0 as well: a yfov of 1e-30 or a denormal znear passes "> 0"
        // and then turns the projection's inverse, and every ray made from it, into Inf.
        return finite(camera.yfov) && camera.yfov >= kMinYfov &&
               camera.yfov < std::numbers::pi_v<float> && camera.znear >= kMinZnear &&
               (!camera.aspect_ratio ||
                (finite(*camera.aspect_ratio) && *camera.aspect_ratio >= kMinAspect &&
                 *camera.aspect_ratio <= 1.0f / kMinAspect));
    }
    // The depth range is a divisor too: zfar - znear must not be (nearly) 0.
    return camera.zfar.has_value() && camera.znear >= 0.0f &&
           static_cast<double>(*camera.zfar) - static_cast<double>(camera.znear) >=
               static_cast<double>(kMinZnear) &&
           magnification_in_range(camera.xmag) && magnification_in_range(camera.ymag);
}

void validate_lights_and_cameras(const Scene& scene) {
    constexpr float kHalfPi = std::numbers::pi_v<float> / 2.0f;
    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
        const Light& light = scene.lights[i];
        const std::string where = "light " + std::to_string(i) + quoted_name(light.name);
        if (!finite(light.color) || light.color.r < 0.0f || light.color.g < 0.0f ||
            light.color.b < 0.0f || !finite(light.intensity) || light.intensity < 0.0f ||
            !finite(light.range) || light.range < 0.0f) {
            invalid(where + ": colour, intensity and range must be finite and not negative");
        }
        if (!below_radiometric_limit(light.color, light.intensity)) {
            invalid(where + ": colour times intensity exceeds " + kMaxRadiometricText +
                    " (each is finite alone, their product would not stay so in the light's "
                    "power)");
        }
        if (light.type == LightType::Spot &&
            !(light.inner_cone_angle >= 0.0f && light.inner_cone_angle < light.outer_cone_angle &&
              light.outer_cone_angle <= kHalfPi)) {
            invalid(where + ": spot cone angles must satisfy 0 <= inner < outer <= pi/2");
        }
    }
    const std::vector<std::string> names = camera_names(scene);
    for (std::size_t i = 0; i < scene.cameras.size(); ++i) {
        if (!projection_valid(scene.cameras[i])) {
            invalid(names[i] + ": projection parameters out of range " +
                    (scene.cameras[i].perspective
                         ? "(perspective: yfov in [1e-4, pi) radians, znear at least 1e-6 m, "
                           "zfar beyond it, aspect ratio in [1e-4, 1e4])"
                         : "(orthographic: xmag and ymag of magnitude in [1e-6, 1e6] m, znear at "
                           "least 0, zfar at least 1e-6 m beyond it)"));
        }
    }
}

void validate_animations(const Scene& scene) {
    for (std::size_t a = 0; a < scene.animations.size(); ++a) {
        const Animation& animation = scene.animations[a];
        const std::string name = "animation " + std::to_string(a) + quoted_name(animation.name);
        for (std::size_t s = 0; s < animation.samplers.size(); ++s) {
            const AnimationSampler& sampler = animation.samplers[s];
            const std::string where = name + " sampler " + std::to_string(s);
            if (sampler.times.empty()) {
                invalid(where + ": has no keyframes");
            }
            for (std::size_t k = 0; k < sampler.times.size(); ++k) {
                const float t = sampler.times[k];
                if (!finite(t) || (k == 0 && t < 0.0f) || (k > 0 && !(t > sampler.times[k - 1]))) {
                    invalid(where +
                            ": keyframe times must be finite, start at 0 or later and "
                            "increase strictly");
                }
            }
            const std::size_t per_key = sampler.interpolation == Interpolation::CubicSpline ? 3 : 1;
            if (sampler.values.size() != per_key * sampler.times.size()) {
                invalid(where + ": " + std::to_string(sampler.values.size()) + " values for " +
                        std::to_string(sampler.times.size()) + " keyframes");
            }
            if (!std::all_of(sampler.values.begin(), sampler.values.end(),
                             [](const glm::vec4& v) { return finite(v); })) {
                invalid(where + ": a keyframe value is not finite");
            }
        }
        std::set<std::pair<int, AnimatedProperty>> targets;
        for (std::size_t c = 0; c < animation.channels.size(); ++c) {
            const AnimationChannel& channel = animation.channels[c];
            const std::string where = name + " channel " + std::to_string(c);
            if (!in_range(channel.node, scene.nodes.size()) ||
                !in_range(channel.sampler, animation.samplers.size())) {
                invalid(where + ": node or sampler out of range");
            }
            if (!targets.emplace(channel.node, channel.property).second) {
                invalid(where + ": animates a property another channel already animates");
            }
        }
    }
}

}  // namespace

bool Material::is_emissive() const {
    const glm::vec3 radiance = emitted_radiance();
    return radiance.r > 0.0f || radiance.g > 0.0f || radiance.b > 0.0f;
}

bool Material::is_specular() const {
    return transmission > 0.0f || (metallic >= 1.0f && roughness < 0.1f);
}

glm::mat4 Node::local_matrix() const {
    // glTF composes T * R * S.
    return glm::translate(glm::mat4(1.0f), translation) * glm::mat4_cast(rotation) *
           glm::scale(glm::mat4(1.0f), scale);
}

std::vector<std::size_t> Scene::parent_first_order() const {
    const std::size_t count = nodes.size();
    std::vector<std::size_t> order;
    order.reserve(count);
    // 0: not yet placed, 1: waiting for its ancestors, 2: placed. The explicit chain keeps
    // deep hierarchies off the call stack, and a node met again while waiting is a cycle.
    std::vector<unsigned char> state(count, 0);
    std::vector<std::size_t> chain;
    for (std::size_t start = 0; start < count; ++start) {
        std::size_t current = start;
        while (state[current] == 0) {
            state[current] = 1;
            chain.push_back(current);
            const int parent = nodes[current].parent;
            if (parent < 0 || static_cast<std::size_t>(parent) >= count) {
                break;
            }
            current = static_cast<std::size_t>(parent);
            if (state[current] == 1) {
                throw Error("invalid scene: node " + std::to_string(current) +
                            " is part of a cycle of parents");
            }
        }
        for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
            order.push_back(*it);
            state[*it] = 2;
        }
        chain.clear();
    }
    return order;
}

std::vector<glm::mat4> Scene::world_matrices() const {
    std::vector<glm::mat4> world(nodes.size(), glm::mat4(1.0f));
    for (const std::size_t i : parent_first_order()) {
        const Node& node = nodes[i];
        world[i] = in_range(node.parent, nodes.size())
                       ? world[static_cast<std::size_t>(node.parent)] * node.local_matrix()
                       : node.local_matrix();
    }
    return world;
}

bool Scene::is_dynamic(int node) const {
    if (!in_range(node, nodes.size())) {
        return false;
    }
    // A skin or a wave (extras.luxel.wave) deforms the mesh every frame, whatever the flag says.
    if (nodes[static_cast<std::size_t>(node)].skin >= 0 ||
        (nodes[static_cast<std::size_t>(node)].mesh >= 0 &&
         nodes[static_cast<std::size_t>(node)].flags.raw.contains("wave"))) {
        return true;
    }
    if (nodes[static_cast<std::size_t>(node)].flags.dynamic) {
        return *nodes[static_cast<std::size_t>(node)].flags.dynamic;
    }
    const auto animated = [this](int index) {
        return std::any_of(animations.begin(), animations.end(), [index](const Animation& a) {
            return std::any_of(a.channels.begin(), a.channels.end(),
                               [index](const AnimationChannel& c) { return c.node == index; });
        });
    };
    // Walk up the hierarchy: whatever moves an ancestor moves this node too, whether an
    // animation or the game (an ancestor flagged dynamic). The step bound guards against a
    // cyclic scene that was never validated.
    int current = node;
    for (std::size_t steps = 0; in_range(current, nodes.size()) && steps <= nodes.size(); ++steps) {
        const Node& ancestor = nodes[static_cast<std::size_t>(current)];
        if (animated(current) || (current != node && ancestor.flags.dynamic.value_or(false))) {
            return true;
        }
        current = ancestor.parent;
    }
    return false;
}

std::size_t Scene::triangle_count() const {
    std::size_t total = 0;
    for (const Mesh& mesh : meshes) {
        for (const Primitive& primitive : mesh.primitives) {
            total += primitive.triangle_count();
        }
    }
    return total;
}

void Scene::validate() const {
    validate_nodes(*this);
    detail::validate_transform_bounds(*this);
    detail::validate_instance_scales(*this);
    validate_meshes(*this);
    validate_materials(*this);
    validate_lights_and_cameras(*this);
    validate_animations(*this);
    detail::validate_skins(*this);
}

}  // namespace luxel::scene
