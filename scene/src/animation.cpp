#include "luxel/scene/animation.hpp"

#include <algorithm>
#include <cmath>

namespace luxel::scene {
namespace {

glm::vec4 normalised_quaternion(const glm::vec4& q) {
    const float length = std::sqrt(glm::dot(q, q));
    // A degenerate (zero) quaternion cannot be normalised; identity is the only safe answer.
    return length > 0.0f ? q / length : glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
}

/// Spherical linear interpolation of xyzw quaternions along the shorter arc (glTF spec,
/// Appendix C). Falls back to normalised lerp when the two are nearly parallel, where slerp's
/// 1/sin(angle) loses precision.
glm::vec4 slerp(glm::vec4 a, glm::vec4 b, float s) {
    float cos_angle = glm::dot(a, b);
    if (cos_angle < 0.0f) {
        b = -b;
        cos_angle = -cos_angle;
    }
    if (cos_angle > 0.9995f) {
        return normalised_quaternion(a + s * (b - a));
    }
    const float angle = std::acos(std::min(cos_angle, 1.0f));
    const float sin_angle = std::sin(angle);
    const float weight_a = std::sin((1.0f - s) * angle) / sin_angle;
    const float weight_b = std::sin(s * angle) / sin_angle;
    return normalised_quaternion(weight_a * a + weight_b * b);
}

}  // namespace

glm::vec4 AnimationSampler::sample(float t, AnimatedProperty property) const {
    const std::size_t keys = times.size();
    const bool cubic = interpolation == Interpolation::CubicSpline;
    const std::size_t stride = cubic ? 3 : 1;
    if (keys == 0 || values.size() < keys * stride) {
        return property == AnimatedProperty::Scale      ? glm::vec4(1.0f)
               : property == AnimatedProperty::Rotation ? glm::vec4(0.0f, 0.0f, 0.0f, 1.0f)
                                                        : glm::vec4(0.0f);
    }
    // The value of key k; for cubic splines the middle of its (in-tangent, value, out-tangent).
    auto value = [&](std::size_t k) { return values[k * stride + (cubic ? 1 : 0)]; };
    auto finish = [&](const glm::vec4& v) {
        return property == AnimatedProperty::Rotation ? normalised_quaternion(v) : v;
    };

    if (!(t > times.front())) {  // before the first key (or NaN): hold the first value
        return finish(value(0));
    }
    if (t >= times.back()) {
        return finish(value(keys - 1));
    }
    // times[k] <= t < times[k + 1]
    const auto upper = std::upper_bound(times.begin(), times.end(), t);
    const std::size_t k = static_cast<std::size_t>(upper - times.begin()) - 1;
    const float t0 = times[k];
    const float t1 = times[k + 1];
    const float delta = t1 - t0;
    const float s = delta > 0.0f ? (t - t0) / delta : 0.0f;

    switch (interpolation) {
        case Interpolation::Step:
            return finish(value(k));
        case Interpolation::Linear:
            if (property == AnimatedProperty::Rotation) {
                return slerp(value(k), value(k + 1), s);
            }
            return value(k) + s * (value(k + 1) - value(k));
        case Interpolation::CubicSpline: {
            // Hermite spline with tangents scaled by the key interval (glTF spec, Appendix C):
            // p(s) = (2s^3 - 3s^2 + 1) v_k + (s^3 - 2s^2 + s) delta b_k
            //      + (-2s^3 + 3s^2) v_k+1 + (s^3 - s^2) delta a_k+1
            const glm::vec4 out_tangent = values[k * 3 + 2];
            const glm::vec4 in_tangent_next = values[(k + 1) * 3];
            const float s2 = s * s;
            const float s3 = s2 * s;
            const glm::vec4 p =
                (2 * s3 - 3 * s2 + 1) * value(k) + (s3 - 2 * s2 + s) * delta * out_tangent +
                (-2 * s3 + 3 * s2) * value(k + 1) + (s3 - s2) * delta * in_tangent_next;
            return finish(p);
        }
    }
    return finish(value(k));
}

float Animation::duration() const {
    float latest = 0.0f;
    for (const auto& sampler : samplers) {
        latest = std::max(latest, sampler.end_time());
    }
    return latest;
}

}  // namespace luxel::scene
