// Animations: channels targeting node translation, rotation and scale, and their samplers with
// keyframe times and values checked as the glTF specification requires.

#include <cmath>
#include <map>
#include <set>

#include <tiny_gltf.h>

#include "gltf_internal.hpp"

namespace luxel::scene::gltf_detail {
namespace {

int components_of(AnimatedProperty property) {
    return property == AnimatedProperty::Rotation ? 4 : 3;
}

AnimationSampler import_sampler(const ImportContext& context,
                                const tinygltf::AnimationSampler& source, AnimatedProperty property,
                                const std::string& where) {
    AnimationSampler sampler;
    if (source.interpolation == "LINEAR") {
        sampler.interpolation = Interpolation::Linear;
    } else if (source.interpolation == "STEP") {
        sampler.interpolation = Interpolation::Step;
    } else if (source.interpolation == "CUBICSPLINE") {
        sampler.interpolation = Interpolation::CubicSpline;
    } else {
        context.fail(where + ": unknown interpolation '" + source.interpolation + "'");
    }

    sampler.times = read_floats(context, source.input, 1, false, "input of " + where);
    for (std::size_t k = 0; k < sampler.times.size(); ++k) {
        if (k == 0 && sampler.times[0] < 0.0f) {
            context.fail(where + ": keyframe time 0 is negative (" +
                         std::to_string(sampler.times[0]) + ")");
        }
        if (k > 0 && !(sampler.times[k] > sampler.times[k - 1])) {
            context.fail(where + ": keyframe times must increase strictly, but time " +
                         std::to_string(k) + " is " + std::to_string(sampler.times[k]) + " after " +
                         std::to_string(sampler.times[k - 1]));
        }
    }

    const int components = components_of(property);
    // Rotations may be stored as normalized integers (glTF 3.11, animation samplers).
    const std::vector<float> flat =
        read_floats(context, source.output, components, property == AnimatedProperty::Rotation,
                    "output of " + where);
    const std::size_t count = flat.size() / static_cast<std::size_t>(components);
    const bool cubic = sampler.interpolation == Interpolation::CubicSpline;
    const std::size_t expected = sampler.times.size() * (cubic ? 3 : 1);
    if (count != expected) {
        context.fail(where + ": output has " + std::to_string(count) + " values for " +
                     std::to_string(sampler.times.size()) + " keyframes, expected " +
                     std::to_string(expected) + (cubic ? " (in-tangent, value, out-tangent)" : ""));
    }
    sampler.values.resize(count, glm::vec4(0.0f));
    for (std::size_t v = 0; v < count; ++v) {
        for (int c = 0; c < components; ++c) {
            sampler.values[v][c] =
                flat[v * static_cast<std::size_t>(components) + static_cast<std::size_t>(c)];
        }
    }
    if (property == AnimatedProperty::Rotation) {
        // Keyframe rotations are unit quaternions; cubic-spline tangents are not.
        for (std::size_t v = cubic ? 1 : 0; v < count; v += cubic ? 3 : 1) {
            const float length = glm::length(sampler.values[v]);
            if (!(length > 1e-6f)) {
                context.fail(where + ": rotation keyframe " + std::to_string(cubic ? v / 3 : v) +
                             " is a zero quaternion");
            }
            sampler.values[v] /= length;
        }
    }
    return sampler;
}

}  // namespace

void import_animations(ImportContext& context) {
    const tinygltf::Model& model = context.model();
    Scene& scene = context.scene();
    for (std::size_t a = 0; a < model.animations.size(); ++a) {
        const tinygltf::Animation& source = model.animations[a];
        const std::string name = label("animation", a, source.name);
        Animation animation;
        animation.name = source.name;
        // glTF sampler index -> (index in `animation`, the property it was read for).
        std::map<int, std::pair<int, AnimatedProperty>> imported;
        std::set<std::pair<int, AnimatedProperty>> targets;
        for (std::size_t c = 0; c < source.channels.size(); ++c) {
            const tinygltf::AnimationChannel& channel = source.channels[c];
            const std::string where = name + " channel " + std::to_string(c);
            if (channel.sampler < 0 ||
                static_cast<std::size_t>(channel.sampler) >= source.samplers.size()) {
                context.fail(where + ": sampler " + std::to_string(channel.sampler) +
                             " out of range");
            }
            AnimatedProperty property{};
            if (channel.target_path == "translation") {
                property = AnimatedProperty::Translation;
            } else if (channel.target_path == "rotation") {
                property = AnimatedProperty::Rotation;
            } else if (channel.target_path == "scale") {
                property = AnimatedProperty::Scale;
            } else {
                context.warn(where + ": animating '" + channel.target_path +
                             "' is not supported; channel skipped");
                continue;
            }
            if (channel.target_node < 0) {
                context.warn(where + ": has no target node; channel skipped");
                continue;
            }
            if (static_cast<std::size_t>(channel.target_node) >= scene.nodes.size()) {
                context.fail(where + ": target node " + std::to_string(channel.target_node) +
                             " out of range");
            }
            if (!targets.emplace(channel.target_node, property).second) {
                context.fail(where + ": node " + std::to_string(channel.target_node) + " " +
                             channel.target_path + " is already animated by another channel");
            }
            auto found = imported.find(channel.sampler);
            if (found == imported.end()) {
                const std::string sampler_where =
                    name + " sampler " + std::to_string(channel.sampler);
                animation.samplers.push_back(import_sampler(
                    context, source.samplers[static_cast<std::size_t>(channel.sampler)], property,
                    sampler_where));
                found = imported
                            .emplace(channel.sampler,
                                     std::make_pair(static_cast<int>(animation.samplers.size() - 1),
                                                    property))
                            .first;
            } else if (components_of(found->second.second) != components_of(property)) {
                context.fail(where + ": sampler " + std::to_string(channel.sampler) +
                             " drives both a rotation and a translation or scale");
            }
            animation.channels.push_back({channel.target_node, property, found->second.first});
        }
        if (!animation.channels.empty()) {
            scene.animations.push_back(std::move(animation));
        }
    }
}

}  // namespace luxel::scene::gltf_detail
