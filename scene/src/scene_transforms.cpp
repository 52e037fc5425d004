// The transform checks of Scene::validate: every node's world scale and distance over every pose
// its animations can give it stay within bounds, so that nothing built from them (instance
// transforms, cameras, rays) turns non-finite.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene_checks.hpp"

namespace luxel::scene::detail {
namespace {

/// The largest distance from the origin, and the largest scale, any node may reach in any pose,
/// in metres: far beyond a game level (1e6 m is a thousand kilometres), far below float's
/// overflow once multiplied by a vertex and a ray's length.
constexpr double kMaxWorldExtent = 1e6;
constexpr double kMaxWorldScale = 1e6;

/// Largest |component| over a sampler's values. A cubic spline can overshoot its keys: with
/// Hermite basis functions in [0, 1] (and the tangents scaled by the key interval),
/// |p(t)| <= |p0| + |p1| + dt (|m0| + |m1|).
double sampler_reach(const AnimationSampler& sampler) {
    double largest = 0.0;
    for (const glm::vec4& value : sampler.values) {
        largest = std::max({largest, std::abs(static_cast<double>(value.x)),
                            std::abs(static_cast<double>(value.y)),
                            std::abs(static_cast<double>(value.z))});
    }
    if (sampler.interpolation != Interpolation::CubicSpline) {
        return largest;
    }
    double longest_interval = 0.0;
    for (std::size_t k = 1; k < sampler.times.size(); ++k) {
        longest_interval = std::max(longest_interval,
                                    static_cast<double>(sampler.times[k] - sampler.times[k - 1]));
    }
    return largest * (2.0 + 2.0 * longest_interval);
}

/// Bounds every node's world position and scale over every pose its animations can give it,
/// so that no transform, camera or ray built from the scene overflows to Inf (Embree asserts on
/// non-finite rays; GL would draw black). Conservative: each node's largest scale and
/// translation, over its rest pose and its animation values, composed down the hierarchy.
/// Cameras must also not collapse: a zero scale up their chain has no view.
/// The smallest world scale a node the ray tracer places as an instance (a dynamic node with a
/// mesh) may reach in any pose: rays enter the mesh's frame through the inverse transform, and
/// 1e-9 keeps that inverse (1e9, its determinant's inverse 1e27) a finite float.
constexpr double kMinInstanceScale = 1e-9;

std::string short_number(double value) {
    std::array<char, 32> text{};
    std::snprintf(text.data(), text.size(), "%.3g", value);
    return text.data();
}

double smallest_component(const glm::vec4& v) {
    return std::min({std::abs(static_cast<double>(v.x)), std::abs(static_cast<double>(v.y)),
                     std::abs(static_cast<double>(v.z))});
}

/// A lower bound on |component| of an animated scale between its keys, before the playback's
/// clamp to kMinAnimatedScale. A linear or cubic segment whose ends differ in sign passes 0; a
/// cubic one can dip below its ends by at most dt (|m0| + |m1|) 4/27 (the Hermite tangent
/// basis functions stay within 4/27).
double sampler_floor(const AnimationSampler& sampler) {
    const bool cubic = sampler.interpolation == Interpolation::CubicSpline;
    const std::size_t stride = cubic ? 3 : 1;
    const std::size_t keys = std::min(sampler.times.size(), sampler.values.size() / stride);
    double floor = std::numeric_limits<double>::max();
    for (std::size_t k = 0; k < keys; ++k) {
        const glm::vec4& p0 = sampler.values[k * stride + (cubic ? 1 : 0)];
        floor = std::min(floor, smallest_component(p0));
        if (k + 1 == keys || sampler.interpolation == Interpolation::Step) {
            continue;
        }
        const glm::vec4& p1 = sampler.values[(k + 1) * stride + (cubic ? 1 : 0)];
        for (int axis = 0; axis < 3; ++axis) {
            const double a = p0[axis];
            const double b = p1[axis];
            double low = (a > 0.0) == (b > 0.0) ? std::min(std::abs(a), std::abs(b)) : 0.0;
            if (cubic) {
                const double dt = static_cast<double>(sampler.times[k + 1] - sampler.times[k]);
                const double m0 =
                    std::abs(static_cast<double>(sampler.values[k * stride + 2][axis]));
                const double m1 =
                    std::abs(static_cast<double>(sampler.values[(k + 1) * stride][axis]));
                low -= dt * (m0 + m1) * 4.0 / 27.0;
            }
            floor = std::min(floor, std::max(low, 0.0));
        }
    }
    return std::max(floor, static_cast<double>(kMinAnimatedScale));
}

/// Calls visit(node, channel, sampler) for every animation channel whose node and sampler exist
/// (validate_animations names the others).
template <typename Visit>
void for_each_channel(const Scene& scene, Visit&& visit) {
    const std::size_t count = scene.nodes.size();
    for (const Animation& animation : scene.animations) {
        for (const AnimationChannel& channel : animation.channels) {
            if (!in_range(channel.node, count) ||
                !in_range(channel.sampler, animation.samplers.size())) {
                continue;
            }
            visit(static_cast<std::size_t>(channel.node), channel,
                  animation.samplers[static_cast<std::size_t>(channel.sampler)]);
        }
    }
}

}  // namespace

void validate_transform_bounds(const Scene& scene) {
    const std::size_t count = scene.nodes.size();
    std::vector<double> scale(count, 0.0);
    std::vector<double> reach(count, 0.0);
    std::vector<bool> scale_animated(count, false);
    for (std::size_t i = 0; i < count; ++i) {
        const Node& node = scene.nodes[i];
        scale[i] = std::max({std::abs(static_cast<double>(node.scale.x)),
                             std::abs(static_cast<double>(node.scale.y)),
                             std::abs(static_cast<double>(node.scale.z))});
        reach[i] = static_cast<double>(glm::length(node.translation));
    }
    for_each_channel(scene, [&](std::size_t n, const AnimationChannel& channel,
                                const AnimationSampler& sampler) {
        const double value = sampler_reach(sampler);
        if (channel.property == AnimatedProperty::Scale) {
            scale[n] = std::max(scale[n], value);
            scale_animated[n] = true;
        } else if (channel.property == AnimatedProperty::Translation) {
            reach[n] = std::max(reach[n], std::sqrt(3.0) * value);
        }
    });
    std::vector<double> world_scale(count, 1.0);
    std::vector<double> world_reach(count, 0.0);
    for (const std::size_t i : scene.parent_first_order()) {
        const Node& node = scene.nodes[i];
        const bool has_parent = in_range(node.parent, count);
        const auto parent = static_cast<std::size_t>(has_parent ? node.parent : 0);
        const double parent_scale = has_parent ? world_scale[parent] : 1.0;
        world_scale[i] = parent_scale * scale[i];
        world_reach[i] = (has_parent ? world_reach[parent] : 0.0) + parent_scale * reach[i];
        const std::string where = "node " + std::to_string(i) + quoted_name(node.name);
        if (!(world_scale[i] <= kMaxWorldScale) || !(world_reach[i] <= kMaxWorldExtent)) {
            invalid(where + ": its transform, composed with its parents' and animated, can reach " +
                    "a scale of " + std::to_string(world_scale[i]) + " or a distance of " +
                    std::to_string(world_reach[i]) + " m (the limits are 1e6 and 1e6 m)");
        }
    }
    // A camera's view needs its world matrix invertible in the rest pose; an animated scale is
    // checked where the view is built.
    const std::vector<glm::mat4> world = scene.world_matrices();
    for (std::size_t i = 0; i < count; ++i) {
        if (scene.nodes[i].camera < 0) {
            continue;
        }
        const double det = std::abs(static_cast<double>(glm::determinant(glm::mat3(world[i]))));
        if (!(det > 1e-18)) {
            invalid("node " + std::to_string(i) + quoted_name(scene.nodes[i].name) +
                    ": holds a camera but its world transform has no volume (a zero scale on it "
                    "or a parent): the view is undefined");
        }
    }
}

/// Every instanced node's smallest world scale over every pose (its rest pose and each animated
/// scale's floor, composed down the hierarchy) must stay above kMinInstanceScale. Static meshes
/// are baked into world space, so their rest scale may be anything finite.
void validate_instance_scales(const Scene& scene) {
    const std::size_t count = scene.nodes.size();
    std::vector<double> smallest(count);
    std::vector<bool> moves(count, false);  // animated, or flagged dynamic
    for (std::size_t i = 0; i < count; ++i) {
        smallest[i] = smallest_component(glm::vec4(scene.nodes[i].scale, 0.0f));
        moves[i] = scene.nodes[i].flags.dynamic.value_or(false);
    }
    for_each_channel(scene, [&](std::size_t n, const AnimationChannel& channel,
                                const AnimationSampler& sampler) {
        moves[n] = true;
        if (channel.property == AnimatedProperty::Scale) {
            smallest[n] = std::min(smallest[n], sampler_floor(sampler));
        }
    });
    // As Scene::is_dynamic: a node's own flag decides; without one, whatever moves it or an
    // ancestor makes it dynamic.
    std::vector<double> world(count, 1.0);
    std::vector<bool> moved_above(count, false);
    for (const std::size_t i : scene.parent_first_order()) {
        const Node& node = scene.nodes[i];
        const bool has_parent = in_range(node.parent, count);
        const auto parent = static_cast<std::size_t>(has_parent ? node.parent : 0);
        world[i] = (has_parent ? world[parent] : 1.0) * smallest[i];
        moved_above[i] = has_parent && (moves[parent] || moved_above[parent]);
        const bool dynamic = node.flags.dynamic.value_or(moves[i] || moved_above[i]);
        if (node.mesh >= 0 && dynamic && !(world[i] >= kMinInstanceScale)) {
            invalid("node " + std::to_string(i) + quoted_name(node.name) +
                    ": a moving mesh whose transform, composed with its parents' and animated, "
                    "can shrink to a scale of " +
                    short_number(world[i]) +
                    " (the limit is 1e-9; an animated scale is kept at 1e-6 or more)");
        }
    }
}

}  // namespace luxel::scene::detail
