#include "luxel/world/sky.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "luxel/lighting/components.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/runtime/image.hpp"
#include "luxel/scene/components.hpp"

namespace luxel::world {
namespace {

std::shared_ptr<const lighting::SkyRadiance> read_map(const std::filesystem::path& file) {
    const Image image = read_exr(file);
    const auto width = static_cast<std::size_t>(std::max(image.width, 0));
    const auto height = static_cast<std::size_t>(std::max(image.height, 0));
    if (width == 0 || height == 0 || width > lighting::SkyRadiance::kMaxCells / height) {
        throw Error(file.string() + ": an environment map of " + std::to_string(width) + " x " +
                    std::to_string(height) + " pixels; a sky may have 1 to " +
                    std::to_string(lighting::SkyRadiance::kMaxCells) + " (4096 x 2048)");
    }
    std::vector<glm::vec3> cells(width * height);
    for (std::size_t i = 0; i < cells.size(); ++i) {
        cells[i] = glm::vec3(image.rgba[4 * i], image.rgba[4 * i + 1], image.rgba[4 * i + 2]);
    }
    return std::make_shared<const lighting::SkyRadiance>(image.width, image.height,
                                                         std::move(cells));
}

}  // namespace

std::shared_ptr<const lighting::SkyRadiance> make_sky_radiance(const scene::SkySpec& spec,
                                                               const glm::vec3& towards_sun) {
    switch (spec.kind) {
        case scene::SkySpec::Kind::None:
            return nullptr;
        case scene::SkySpec::Kind::Uniform:
            return std::make_shared<const lighting::SkyRadiance>(
                lighting::SkyRadiance::uniform(spec.radiance));
        case scene::SkySpec::Kind::Daylight:
            return std::make_shared<const lighting::SkyRadiance>(
                lighting::daylight_sky(towards_sun, spec.turbidity, spec.irradiance));
        case scene::SkySpec::Kind::Map:
            return read_map(spec.map);
    }
    return nullptr;
}

glm::vec3 sun_direction(const scene::Scene& scene) {
    const std::vector<glm::mat4> world = scene.world_matrices();
    glm::vec3 towards(0.5f, std::sqrt(0.5f), 0.5f);
    float brightest = 0.0f;
    for (std::size_t i = 0; i < scene.nodes.size() && i < world.size(); ++i) {
        const scene::Node& node = scene.nodes[i];
        if (node.light < 0 || !node.flags.light_enabled) {
            continue;
        }
        const scene::Light& light = scene.lights.at(static_cast<std::size_t>(node.light));
        if (light.type != scene::LightType::Directional) {
            continue;
        }
        const glm::vec3 irradiance = light.irradiance();
        const float strength = irradiance.r + irradiance.g + irradiance.b;
        const glm::vec3 axis(world[i][2]);
        const float length = glm::length(axis);
        if (strength > brightest && length > 0.0f && std::isfinite(length)) {
            brightest = strength;
            towards = axis / length;  // the light travels down -z: the sun lies up +z
        }
    }
    return towards;
}

ecs::Entity add_sky(ecs::Registry& registry, const scene::Scene& scene,
                    const scene::SkySpec& spec) {
    std::shared_ptr<const lighting::SkyRadiance> radiance = make_sky_radiance(
        spec, spec.kind == scene::SkySpec::Kind::Daylight ? sun_direction(scene)
                                                          : glm::vec3(0.0f, 1.0f, 0.0f));
    if (radiance == nullptr) {
        return ecs::null_entity;
    }
    const ecs::Entity entity = registry.create();
    registry.emplace<scene::Name>(entity, "sky");
    registry.emplace<lighting::SkyLight>(entity, std::move(radiance), spec.scale, true);
    return entity;
}

}  // namespace luxel::world
