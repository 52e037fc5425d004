// glTF animation sampling against the specification (glTF 2.0, Appendix C).

#include <cmath>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>

#include "luxel/scene/animation.hpp"

namespace {

using luxel::scene::AnimatedProperty;
using luxel::scene::AnimationSampler;
using luxel::scene::Interpolation;

glm::vec4 xyzw(const glm::quat& q) {
    return {q.x, q.y, q.z, q.w};
}

void expect_near(const glm::vec4& actual, const glm::vec4& expected, float tolerance = 1e-5f) {
    for (int i = 0; i < 4; ++i) {
        EXPECT_NEAR(actual[i], expected[i], tolerance) << "component " << i;
    }
}

TEST(AnimationSampling, StepHoldsEachKeyUntilTheNext) {
    const AnimationSampler sampler{{0.0f, 1.0f, 3.0f},
                                   {glm::vec4(1.0f), glm::vec4(2.0f), glm::vec4(5.0f)},
                                   Interpolation::Step};
    expect_near(sampler.sample(0.0f, AnimatedProperty::Translation), glm::vec4(1.0f));
    expect_near(sampler.sample(0.999f, AnimatedProperty::Translation), glm::vec4(1.0f));
    expect_near(sampler.sample(1.0f, AnimatedProperty::Translation), glm::vec4(2.0f));
    expect_near(sampler.sample(2.9f, AnimatedProperty::Translation), glm::vec4(2.0f));
    expect_near(sampler.sample(3.0f, AnimatedProperty::Translation), glm::vec4(5.0f));
}

TEST(AnimationSampling, LinearInterpolatesAndClampsOutsideTheKeys) {
    const AnimationSampler sampler{
        {1.0f, 3.0f},
        {glm::vec4(0.0f, 2.0f, -4.0f, 0.0f), glm::vec4(4.0f, 2.0f, 0.0f, 0.0f)},
        Interpolation::Linear};
    expect_near(sampler.sample(2.0f, AnimatedProperty::Translation), {2.0f, 2.0f, -2.0f, 0.0f});
    expect_near(sampler.sample(2.5f, AnimatedProperty::Scale), {3.0f, 2.0f, -1.0f, 0.0f});
    expect_near(sampler.sample(-10.0f, AnimatedProperty::Translation), {0.0f, 2.0f, -4.0f, 0.0f});
    expect_near(sampler.sample(10.0f, AnimatedProperty::Translation), {4.0f, 2.0f, 0.0f, 0.0f});
    expect_near(sampler.sample(std::nanf(""), AnimatedProperty::Translation),
                {0.0f, 2.0f, -4.0f, 0.0f});
}

TEST(AnimationSampling, LinearRotationIsSlerpAlongTheShorterArc) {
    const glm::vec3 up(0.0f, 1.0f, 0.0f);
    const glm::quat start = glm::angleAxis(0.0f, up);
    const glm::quat end = glm::angleAxis(glm::half_pi<float>(), up);
    const AnimationSampler sampler{{0.0f, 1.0f}, {xyzw(start), xyzw(end)}, Interpolation::Linear};
    // Slerp moves at constant angular speed: a quarter of the way is 22.5 degrees.
    for (float s : {0.25f, 0.5f, 0.75f}) {
        const glm::quat expected = glm::angleAxis(s * glm::half_pi<float>(), up);
        expect_near(sampler.sample(s, AnimatedProperty::Rotation), xyzw(expected));
    }
    // The same end rotation written as -q must take the short way too (not a 270-degree swing).
    const AnimationSampler flipped{{0.0f, 1.0f}, {xyzw(start), -xyzw(end)}, Interpolation::Linear};
    const glm::vec4 half = flipped.sample(0.5f, AnimatedProperty::Rotation);
    const glm::quat expected = glm::angleAxis(glm::quarter_pi<float>(), up);
    EXPECT_NEAR(std::abs(glm::dot(half, xyzw(expected))), 1.0f, 1e-5f);
}

TEST(AnimationSampling, CubicSplineIsTheSpecsHermiteWithIntervalScaledTangents) {
    // Keys at t = 0, 2, 3 (intervals of different length) with tangents (in, value, out).
    const std::vector<float> times = {0.0f, 2.0f, 3.0f};
    const std::vector<glm::vec4> values = {
        glm::vec4(0.0f),           glm::vec4(1.0f, 0, 0, 0), glm::vec4(0.5f, 0, 0, 0),  // key 0
        glm::vec4(-1.0f, 0, 0, 0), glm::vec4(3.0f, 0, 0, 0), glm::vec4(2.0f, 0, 0, 0),  // key 1
        glm::vec4(4.0f, 0, 0, 0),  glm::vec4(2.0f, 0, 0, 0), glm::vec4(0.0f)};          // key 2
    const AnimationSampler sampler{times, values, Interpolation::CubicSpline};

    auto reference = [&](float t) {
        // Written independently from the spec's formula.
        const int k = t < 2.0f ? 0 : 1;
        const float t0 = times[static_cast<std::size_t>(k)];
        const float td = times[static_cast<std::size_t>(k) + 1] - t0;
        const float s = (t - t0) / td;
        const float vk = values[static_cast<std::size_t>(3 * k + 1)].x;
        const float bk = values[static_cast<std::size_t>(3 * k + 2)].x;
        const float vk1 = values[static_cast<std::size_t>(3 * k + 4)].x;
        const float ak1 = values[static_cast<std::size_t>(3 * k + 3)].x;
        return (2 * s * s * s - 3 * s * s + 1) * vk + td * (s * s * s - 2 * s * s + s) * bk +
               (-2 * s * s * s + 3 * s * s) * vk1 + td * (s * s * s - s * s) * ak1;
    };
    for (float t = 0.0f; t <= 3.0f; t += 0.125f) {
        EXPECT_NEAR(sampler.sample(t, AnimatedProperty::Translation).x, reference(t), 1e-5f)
            << "t = " << t;
    }
    // The curve passes through every key value, and its time derivative at a key equals the
    // key's out-tangent (right side) and in-tangent (left side).
    EXPECT_NEAR(sampler.sample(2.0f, AnimatedProperty::Translation).x, 3.0f, 1e-6f);
    const float h = 1e-3f;
    const float right = (sampler.sample(2.0f + h, AnimatedProperty::Translation).x - 3.0f) / h;
    const float left = (3.0f - sampler.sample(2.0f - h, AnimatedProperty::Translation).x) / h;
    EXPECT_NEAR(right, 2.0f, 2e-2f);
    EXPECT_NEAR(left, -1.0f, 2e-2f);
}

TEST(AnimationSampling, CubicSplineRotationIsNormalised) {
    const glm::vec3 axis = glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f));
    const glm::vec4 q0 = xyzw(glm::angleAxis(0.0f, axis));
    const glm::vec4 q1 = xyzw(glm::angleAxis(2.0f, axis));
    const AnimationSampler sampler{
        {0.0f, 1.0f},
        {glm::vec4(0.0f), q0, glm::vec4(0.3f), glm::vec4(-0.2f), q1, glm::vec4(0.0f)},
        Interpolation::CubicSpline};
    for (float t = 0.0f; t <= 1.0f; t += 0.1f) {
        const glm::vec4 q = sampler.sample(t, AnimatedProperty::Rotation);
        EXPECT_NEAR(glm::dot(q, q), 1.0f, 1e-5f);
    }
}

TEST(AnimationSampling, DegenerateSamplersGiveNeutralValues) {
    const AnimationSampler empty{};
    expect_near(empty.sample(1.0f, AnimatedProperty::Scale), glm::vec4(1.0f));
    expect_near(empty.sample(1.0f, AnimatedProperty::Rotation), {0, 0, 0, 1});
    const AnimationSampler single{{0.5f}, {glm::vec4(7.0f)}, Interpolation::Linear};
    expect_near(single.sample(0.0f, AnimatedProperty::Translation), glm::vec4(7.0f));
    expect_near(single.sample(9.0f, AnimatedProperty::Translation), glm::vec4(7.0f));
    const AnimationSampler zero_quaternion{{0.0f}, {glm::vec4(0.0f)}, Interpolation::Step};
    expect_near(zero_quaternion.sample(0.0f, AnimatedProperty::Rotation), {0, 0, 0, 1});

    luxel::scene::Animation animation;
    EXPECT_EQ(animation.duration(), 0.0f);
    animation.samplers = {single, {{0.0f, 4.0f}, {glm::vec4(0.0f), glm::vec4(1.0f)}}};
    EXPECT_EQ(animation.duration(), 4.0f);
}

}  // namespace
