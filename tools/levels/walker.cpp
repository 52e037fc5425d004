#include "walker.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>

#include "mesh_builders.hpp"

namespace luxel::levels {
namespace {

using scene::AnimatedProperty;
using scene::Interpolation;

constexpr float kStrideSeconds = 1.0f;  // one full gait cycle: two steps of 0.6 m at 1.2 m/s
const float kLegSwing = glm::radians(28.0f);
const float kArmSwing = glm::radians(20.0f);
constexpr float kEaseSeconds = 0.25f;  // limbs ease into and out of the swing
constexpr float kTurnSeconds = 0.2f;   // half the time a turn at a corner takes
constexpr float kLimbKeySeconds = 0.125f;

// The skeleton in the bind pose, the figure at the origin facing +x (its left on -z).
const glm::vec3 kLeftHip(0.0f, 0.85f, -0.1f);
const glm::vec3 kRightHip(0.0f, 0.85f, 0.1f);
const glm::vec3 kLeftShoulder(0.0f, 1.41f, -0.27f);
const glm::vec3 kRightShoulder(0.0f, 1.41f, 0.27f);
enum Joint : std::uint16_t { kRoot, kLeftLeg, kRightLeg, kLeftArm, kRightArm };

struct Part {
    glm::vec3 size;
    glm::vec3 centre;
    Joint joint;
};

// Torso and head ride on the root; each leg hangs from its hip, each arm from its shoulder.
const Part kParts[] = {
    {{0.22f, 0.60f, 0.40f}, {0.0f, 1.15f, 0.0f}, kRoot},
    {{0.22f, 0.24f, 0.20f}, {0.0f, 1.60f, 0.0f}, kRoot},
    {{0.16f, 0.85f, 0.16f}, {0.0f, 0.425f, -0.1f}, kLeftLeg},
    {{0.16f, 0.85f, 0.16f}, {0.0f, 0.425f, 0.1f}, kRightLeg},
    {{0.12f, 0.62f, 0.12f}, {0.0f, 1.41f - 0.31f, -0.27f}, kLeftArm},
    {{0.12f, 0.62f, 0.12f}, {0.0f, 1.41f - 0.31f, 0.27f}, kRightArm},
};

glm::quat heading(glm::vec2 direction) {
    // A yaw turns +x towards -z for a positive angle, so facing (x, z) is atan2(-z, x).
    return glm::angleAxis(std::atan2(-direction.y, direction.x), glm::vec3(0.0f, 1.0f, 0.0f));
}

bool moving(const WalkKey& a, const WalkKey& b) {
    return a.position != b.position;
}

/// 0 standing, 1 walking, ramped over kEaseSeconds at either end of a leg.
float gait(const std::vector<WalkKey>& path, float t) {
    for (std::size_t k = 0; k + 1 < path.size(); ++k) {
        const WalkKey& a = path[k];
        const WalkKey& b = path[k + 1];
        if (t >= a.time && t <= b.time && moving(a, b)) {
            return std::clamp(std::min(t - a.time, b.time - t) / kEaseSeconds, 0.0f, 1.0f);
        }
    }
    return 0.0f;
}

void check_path(const std::vector<WalkKey>& path) {
    if (path.size() < 2 || path.front().time != 0.0f ||
        path.back().position != path.front().position) {
        throw std::invalid_argument(
            "add_walker: the path needs two keys or more, from time 0, and must end where it "
            "starts (it loops)");
    }
    bool any_move = false;
    for (std::size_t k = 0; k + 1 < path.size(); ++k) {
        if (!(path[k + 1].time > path[k].time)) {
            throw std::invalid_argument("add_walker: key times must increase");
        }
        any_move = any_move || moving(path[k], path[k + 1]);
    }
    if (!any_move) {
        throw std::invalid_argument("add_walker: the path never moves");
    }
}

scene::Primitive figure_mesh() {
    scene::Primitive figure;
    for (const Part& part : kParts) {
        scene::Primitive box = make_box(part.size);
        for (glm::vec3& p : box.positions) {
            p += part.centre;
        }
        append(figure, box);
        figure.joints.resize(figure.positions.size(), glm::u16vec4(part.joint, 0, 0, 0));
        figure.weights.resize(figure.positions.size(), glm::vec4(1.0f, 0.0f, 0.0f, 0.0f));
    }
    return figure;
}

/// Yaw keys: each leg's heading held from kTurnSeconds after its start to kTurnSeconds before
/// its end, so the figure turns round its corners and while it stands; the loop's first and
/// last keys face the first leg.
void heading_keys(const std::vector<WalkKey>& path, std::vector<float>& times,
                  std::vector<glm::vec4>& values) {
    glm::quat first(1.0f, 0.0f, 0.0f, 0.0f);
    for (std::size_t k = 0; k + 1 < path.size(); ++k) {
        if (moving(path[k], path[k + 1])) {
            first = heading(path[k + 1].position - path[k].position);
            break;
        }
    }
    times.push_back(0.0f);
    values.push_back(as_key(first));
    for (std::size_t k = 0; k + 1 < path.size(); ++k) {
        const WalkKey& a = path[k];
        const WalkKey& b = path[k + 1];
        if (!moving(a, b)) {
            continue;
        }
        const float turn = std::min(kTurnSeconds, 0.25f * (b.time - a.time));
        const glm::quat q = heading(b.position - a.position);
        for (const float t : {a.time + turn, b.time - turn}) {
            if (t > times.back()) {
                times.push_back(t);
                values.push_back(as_key(q));
            }
        }
    }
    if (path.back().time > times.back()) {
        times.push_back(path.back().time);
        values.push_back(as_key(first));
    }
}

}  // namespace

int add_walker(LevelBuilder& level, const std::string& name, int material,
               const std::vector<WalkKey>& path) {
    check_path(path);
    const int root = level.add_node(name + " root");
    const int left_hip = level.add_node(name + " left hip", root, kLeftHip);
    const int right_hip = level.add_node(name + " right hip", root, kRightHip);
    const int left_shoulder = level.add_node(name + " left shoulder", root, kLeftShoulder);
    const int right_shoulder = level.add_node(name + " right shoulder", root, kRightShoulder);
    // Bound with the figure at the origin; then its root moves to where the walk starts (the
    // pose a viewer that plays no animation shows).
    const int skin =
        level.add_skin(name, {root, left_hip, right_hip, left_shoulder, right_shoulder});
    const int body = level.add_skinned_mesh_node(name, figure_mesh(), material, skin);

    const std::string walk = name + " walk";
    std::vector<float> times;
    std::vector<glm::vec4> places;
    for (const WalkKey& key : path) {
        times.push_back(key.time);
        places.push_back(as_key(glm::vec3(key.position.x, 0.0f, key.position.y)));
    }
    level.node(root).translation = glm::vec3(places.front());
    level.animate(walk, root, AnimatedProperty::Translation, Interpolation::Linear, times, places);
    std::vector<glm::vec4> headings;
    times.clear();
    heading_keys(path, times, headings);
    level.node(root).rotation =
        glm::quat(headings.front().w, headings.front().x, headings.front().y, headings.front().z);
    level.animate(walk, root, AnimatedProperty::Rotation, Interpolation::Linear, times, headings);

    // The limbs swing about the figure's sideways axis (+z), legs against arms.
    const float loop = path.back().time;
    const auto keys = static_cast<int>(std::ceil(loop / kLimbKeySeconds));
    std::vector<float> limb_times;
    std::vector<float> swing;
    for (int i = 0; i <= keys; ++i) {
        const float t = loop * static_cast<float>(i) / static_cast<float>(keys);
        limb_times.push_back(t);
        swing.push_back(gait(path, t) * std::sin(glm::two_pi<float>() * t / kStrideSeconds));
    }
    auto swing_keys = [&](float amplitude) {
        std::vector<glm::vec4> values;
        for (const float s : swing) {
            values.push_back(as_key(glm::angleAxis(amplitude * s, glm::vec3(0.0f, 0.0f, 1.0f))));
        }
        return values;
    };
    level.animate(walk, left_hip, AnimatedProperty::Rotation, Interpolation::Linear, limb_times,
                  swing_keys(kLegSwing));
    level.animate(walk, right_hip, AnimatedProperty::Rotation, Interpolation::Linear, limb_times,
                  swing_keys(-kLegSwing));
    level.animate(walk, left_shoulder, AnimatedProperty::Rotation, Interpolation::Linear,
                  limb_times, swing_keys(-kArmSwing));
    level.animate(walk, right_shoulder, AnimatedProperty::Rotation, Interpolation::Linear,
                  limb_times, swing_keys(kArmSwing));
    return body;
}

}  // namespace luxel::levels
