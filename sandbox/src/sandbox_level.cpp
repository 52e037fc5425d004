#include "sandbox_level.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "luxel/ecs/transform.hpp"
#include "luxel/lighting/components.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/scene/level_check.hpp"

namespace luxel::sandbox {

const std::vector<std::string>& level_names() {
    static const std::vector<std::string> names = {"sandbox",      "cornell",   "cornell-13k",
                                                   "cornell-133k", "two-rooms", "caustics",
                                                   "sky-room",     "furnace"};
    return names;
}

std::filesystem::path resolve_level(const std::string& name_or_path) {
    const auto& names = level_names();
    if (std::find(names.begin(), names.end(), name_or_path) != names.end()) {
        const std::filesystem::path relative =
            std::filesystem::path("assets") / "levels" / "prepared" / (name_or_path + ".glb");
        const std::vector<std::filesystem::path> roots = {std::filesystem::current_path(),
                                                          std::filesystem::path(LUXEL_SOURCE_DIR)};
        std::string looked;
        for (const auto& root : roots) {
            const auto candidate = root / relative;
            if (std::filesystem::is_regular_file(candidate)) {
                return candidate;
            }
            looked += (looked.empty() ? "" : ", ") + candidate.string();
        }
        throw Error("level '" + name_or_path + "': its file is missing (looked in " + looked + ")");
    }
    const std::filesystem::path path(name_or_path);
    if (!std::filesystem::is_regular_file(path)) {
        std::string known;
        for (const auto& name : names) {
            known += (known.empty() ? "" : ", ") + name;
        }
        throw Error("level '" + name_or_path + "' is neither a built-in level (" + known +
                    ") nor an existing file");
    }
    return path;
}

std::size_t add_bounces(ecs::Registry& registry, const world::SceneInstance& instance,
                        const scene::Scene& scene) {
    std::size_t added = 0;
    for (std::size_t node = 0; node < instance.nodes.size() && node < scene.nodes.size(); ++node) {
        const auto& raw = scene.nodes[node].flags.raw;
        const ecs::Entity entity = instance.nodes[node];
        if (!raw.is_object() || !raw.contains("bounce") || entity.is_null() ||
            !registry.has<ecs::Transform>(entity)) {
            continue;
        }
        const auto& settings = raw["bounce"];
        Bounce bounce;
        bounce.rest = registry.get<ecs::Transform>(entity).translation;
        bounce.height = settings.value("height", 1.0f);
        bounce.period = settings.value("period", 1.0f);
        if (!(bounce.period > 0.0f) || !std::isfinite(bounce.height)) {
            throw Error(scene.in_file(
                "node '" + scene.nodes[node].name +
                "': extras.luxel.bounce needs a positive period and a finite height"));
        }
        registry.emplace<Bounce>(entity, bounce);
        if (!registry.has<scene::Dynamic>(entity)) {
            registry.emplace<scene::Dynamic>(entity);
        }
        ++added;
    }
    return added;
}

void update_bounces(ecs::Registry& registry, double seconds) {
    registry.view<Bounce>().each([&](ecs::Entity entity, const Bounce& bounce) {
        // The period is one hop: |sin| touches the floor once per period.
        const double phase = std::numbers::pi * seconds / static_cast<double>(bounce.period);
        const auto lift = static_cast<float>(bounce.height * std::abs(std::sin(phase)));
        registry.patch<ecs::Transform>(entity, [&](ecs::Transform& transform) {
            transform.translation = bounce.rest + glm::vec3(0.0f, lift, 0.0f);
        });
    });
}

CameraPath::CameraPath(std::vector<Key> keys, float vertical_fov)
    : keys_(std::move(keys)), vertical_fov_(vertical_fov) {
    if (keys_.empty()) {
        const scene::DefaultView view;
        keys_.push_back({0.0, view.eye, view.target});
    }
}

CameraPose CameraPath::at(double seconds) const {
    CameraPose pose;
    pose.vertical_fov = vertical_fov_;
    if (keys_.size() == 1 || !(duration() > 0.0)) {
        pose.eye = keys_.front().eye;
        pose.target = keys_.front().target;
        return pose;
    }
    const double t = std::fmod(std::max(seconds, 0.0), duration());
    std::size_t k = 0;
    while (k + 2 < keys_.size() && keys_[k + 1].time <= t) {
        ++k;
    }
    const Key& a = keys_[k];
    const Key& b = keys_[k + 1];
    const double span = b.time - a.time;
    const auto w = static_cast<float>(span > 0.0 ? std::clamp((t - a.time) / span, 0.0, 1.0) : 0.0);
    // Smoothstep: the camera eases in and out of each key instead of turning corners.
    const float s = w * w * (3.0f - 2.0f * w);
    pose.eye = glm::mix(a.eye, b.eye, s);
    pose.target = glm::mix(a.target, b.target, s);
    return pose;
}

CameraPath camera_path_for(const std::string& level_name, const scene::Scene& scene) {
    if (level_name == "sandbox") {
        // West room, past the ball and the swinging lamp, through the corridor into the east
        // room to the glass sculpture, and back.
        return CameraPath({{0.0, {-3.5f, 1.6f, 1.6f}, {-0.5f, 1.1f, -0.4f}},
                           {3.0, {-2.8f, 1.5f, 1.2f}, {0.5f, 1.0f, 0.0f}},
                           {6.0, {-0.8f, 1.5f, 0.0f}, {3.0f, 1.2f, 0.0f}},
                           {9.0, {2.5f, 1.5f, 0.0f}, {5.0f, 0.8f, 0.0f}},
                           {12.0, {3.8f, 1.8f, 1.5f}, {5.0f, 0.8f, 0.0f}},
                           {15.0, {6.3f, 1.7f, 1.6f}, {5.0f, 0.8f, 0.0f}},
                           {18.0, {-3.5f, 1.6f, 1.6f}, {-0.5f, 1.1f, -0.4f}}},
                          glm::radians(65.0f));
    }
    // The level's own camera, swaying a little sideways.
    const auto matrices = scene.world_matrices();
    for (std::size_t n = 0; n < scene.nodes.size(); ++n) {
        const int camera = scene.nodes[n].camera;
        if (camera < 0 || static_cast<std::size_t>(camera) >= scene.cameras.size()) {
            continue;
        }
        const glm::mat4& world = matrices[n];
        const glm::vec3 eye(world[3]);
        const glm::vec3 forward = -glm::normalize(glm::vec3(world[2]));
        const glm::vec3 right = glm::normalize(glm::vec3(world[0]));
        const glm::vec3 target = eye + 2.5f * forward;
        const float fov = scene.cameras[static_cast<std::size_t>(camera)].yfov;
        return CameraPath({{0.0, eye, target},
                           {4.0, eye + 0.3f * right, target},
                           {8.0, eye - 0.3f * right, target},
                           {12.0, eye, target}},
                          fov);
    }
    // No camera: the default view every tool uses, which scene::check_level names.
    return CameraPath({}, glm::radians(scene::DefaultView{}.vertical_fov_degrees));
}

}  // namespace luxel::sandbox
