#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

/// glTF animations: keyframe samplers and the channels that drive node properties, with
/// sampling exactly as the glTF 2.0 specification (Appendix C) defines it.
namespace luxel::scene {

enum class Interpolation { Linear, Step, CubicSpline };
enum class AnimatedProperty { Translation, Rotation, Scale };

/// Keyframes. `times` is strictly increasing (seconds). `values` holds vec4s: xyz for
/// translation and scale (w unused), xyzw quaternions for rotation. For CubicSpline each key
/// has three values (in-tangent, value, out-tangent), so values.size() == 3 * times.size();
/// otherwise values.size() == times.size().
struct AnimationSampler {
    std::vector<float> times;
    std::vector<glm::vec4> values;
    Interpolation interpolation = Interpolation::Linear;

    /// The value at time t (clamped to the keyframe range). Rotations are normalised after
    /// interpolation; Linear rotation uses spherical linear interpolation along the shorter arc.
    [[nodiscard]] glm::vec4 sample(float t, AnimatedProperty property) const;
    [[nodiscard]] float start_time() const { return times.empty() ? 0.0f : times.front(); }
    [[nodiscard]] float end_time() const { return times.empty() ? 0.0f : times.back(); }
};

struct AnimationChannel {
    int node = -1;
    AnimatedProperty property = AnimatedProperty::Translation;
    int sampler = -1;  ///< index into Animation::samplers
};

struct Animation {
    std::string name;
    std::vector<AnimationSampler> samplers;
    std::vector<AnimationChannel> channels;

    /// The latest keyframe time over all samplers (0 for an empty animation).
    [[nodiscard]] float duration() const;
};

/// The smallest magnitude an animated scale component is given (world::update_animations clamps
/// to it, keeping the sign). A mesh that its animation scales to 0 (a pop-in effect) would have
/// no inverse transform, and the ray tracer carries rays into an instance's frame with that
/// inverse: they become non-finite (Embree asserts). 1e-6 hides a mesh as well as 0 does (a
/// kilometre becomes a millimetre); Scene::validate bounds what the parents multiply it by.
inline constexpr float kMinAnimatedScale = 1e-6f;

/// Helpers to turn sampled vec4s into node properties.
[[nodiscard]] inline glm::vec3 as_vec3(const glm::vec4& v) {
    return glm::vec3(v);
}
[[nodiscard]] inline glm::quat as_quat(const glm::vec4& v) {
    return glm::quat(v.w, v.x, v.y, v.z);
}

}  // namespace luxel::scene
