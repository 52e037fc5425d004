#include "level.hpp"

#include <cmath>
#include <cstdlib>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "luxel/ecs/transform.hpp"
#include "luxel/ecs/transform_system.hpp"
#include "luxel/lighting/components.hpp"
#include "luxel/lighting/reference/reference_integrator.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/scene/gltf.hpp"
#include "luxel/scene/level_check.hpp"
#include "luxel/world/animation_system.hpp"
#include "luxel/world/skinning.hpp"
#include "luxel/world/sky.hpp"
#include "luxel/world/vertex_wave.hpp"

namespace luxel::ref {

std::filesystem::path resolve_level(const std::string& level) {
    if (level.empty()) {
        throw Error("--level: empty");
    }
    const std::filesystem::path given(level);
    const auto extension = given.extension();
    if (level.find('/') != std::string::npos || extension == ".glb" || extension == ".gltf") {
        if (!std::filesystem::is_regular_file(given)) {
            throw Error("level file " + given.string() + " does not exist");
        }
        return given;
    }
    std::vector<std::filesystem::path> tried;
    if (const char* dir = std::getenv("LUXEL_LEVEL_DIR"); dir != nullptr && *dir != '\0') {
        tried.push_back(std::filesystem::path(dir) / (level + ".glb"));
    }
    tried.push_back(std::filesystem::path(LUXEL_PREPARED_LEVEL_DIR) / (level + ".glb"));
    tried.push_back(std::filesystem::path("assets") / "levels" / "prepared" / (level + ".glb"));
    std::string list;
    for (const auto& candidate : tried) {
        if (std::filesystem::is_regular_file(candidate)) {
            return candidate;
        }
        list += (list.empty() ? "" : ", ") + candidate.string();
    }
    throw Error("no level named '" + level + "' (looked for " + list + ")");
}

void check_reference_memory(const std::filesystem::path& file, std::uint64_t texels,
                            const scene::LoadOptions& limits) {
    const std::uint64_t per_texel = lighting::reference::ReferenceIntegrator::bytes_per_texel();
    // Compared as texels, so the product cannot overflow.
    if (texels <= limits.max_reference_bytes / per_texel) {
        return;
    }
    const double mib = static_cast<double>(texels) * static_cast<double>(per_texel) / 1048576.0;
    throw Error(file.string() + ": the light maps hold " + std::to_string(texels) +
                " texels; the reference keeps " + std::to_string(per_texel) +
                " bytes for each, about " + std::to_string(static_cast<long long>(std::ceil(mib))) +
                " MiB, more than the reference-bytes limit of " +
                std::to_string(limits.max_reference_bytes) +
                " (--limit reference-bytes=N raises it)");
}

std::unique_ptr<LoadedLevel> load_level(const std::filesystem::path& file, double time,
                                        const std::optional<scene::SkySpec>& sky,
                                        const prep::PlayableLevel& playable, JobSystem& jobs) {
    auto level = std::make_unique<LoadedLevel>();
    const scene::LoadOptions& limits = playable.limits;
    // load_gltf's errors already start with the file's path.
    const std::shared_ptr<const scene::Scene> source = prep::load_playable(file, playable, jobs);
    world::InstantiateOptions options;
    options.play_animations = true;
    options.sky = sky;
    level->instance = world::instantiate(level->registry, source, options);
    // Every animation and light switch at `time` (a zero step still poses time 0).
    world::update_animations(level->registry, time);
    world::update_light_switches(level->registry, time);
    world::update_waves(level->registry, time);
    world::update_sky(level->registry);
    ecs::TransformSystem transforms(level->registry);
    transforms.update();
    world::update_skins(level->registry);  // skinned meshes follow their joints
    lighting::PhotonWorldSettings settings;
    settings.caustics.photons_per_pair = 0;  // the reference traces its own caustics
    level->world = std::make_unique<lighting::PhotonWorld>(level->registry, settings);
    level->world->sync();
    level->maps = std::make_unique<lighting::IlluminationMaps>(level->registry, *level->world);
    level->maps->sync();
    check_reference_memory(file, lighting::reference::ReferenceScene::count_texels(*level->maps),
                           limits);
    level->scene = std::make_unique<lighting::reference::ReferenceScene>(
        lighting::reference::ReferenceScene::from_world(*level->world, *level->maps));
    return level;
}

std::optional<lighting::reference::ReferenceCamera> level_camera(const LoadedLevel& level,
                                                                 int width, int height) {
    return level_camera(level.registry, level.instance, width, height);
}

lighting::reference::ReferenceCamera default_camera(int width, int height) {
    const scene::DefaultView view;
    return lighting::reference::ReferenceCamera::look_at(
        view.eye, view.target, glm::radians(view.vertical_fov_degrees), width, height);
}

std::optional<lighting::reference::ReferenceCamera> level_camera(
    const ecs::Registry& registry, const world::SceneInstance& instance, int width, int height) {
    for (ecs::Entity entity : instance.nodes) {
        const auto* camera = registry.try_get<scene::CameraComponent>(entity);
        const auto* world = registry.try_get<ecs::WorldTransform>(entity);
        if (camera == nullptr || world == nullptr) {
            continue;
        }
        lighting::reference::ReferenceCamera out;
        out.width = width;
        out.height = height;
        // The node's frame, without scale: the camera looks down its -z.
        const glm::vec3 eye(world->matrix[3]);
        const glm::vec3 forward = -glm::normalize(glm::vec3(world->matrix[2]));
        const glm::vec3 up = glm::normalize(glm::vec3(world->matrix[1]));
        out.view = glm::lookAt(eye, eye + forward, up);
        const scene::Camera& c = camera->camera;
        const float aspect = static_cast<float>(width) / static_cast<float>(height);
        if (c.perspective) {
            out.projection = glm::perspective(c.yfov, aspect, c.znear, c.zfar.value_or(1000.0f));
        } else {
            out.projection = glm::ortho(-c.ymag * aspect, c.ymag * aspect, -c.ymag, c.ymag, c.znear,
                                        c.zfar.value_or(1000.0f));
        }
        return out;
    }
    return std::nullopt;
}

}  // namespace luxel::ref
