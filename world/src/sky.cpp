#include "luxel/world/sky.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "luxel/ecs/hierarchy.hpp"
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

int sun_node(const scene::Scene& scene) {
    const std::vector<glm::mat4> world = scene.world_matrices();
    int sun = -1;
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
        const float length = glm::length(glm::vec3(world[i][2]));
        if (strength > brightest && length > 0.0f && std::isfinite(length)) {
            brightest = strength;
            sun = static_cast<int>(i);
        }
    }
    return sun;
}

glm::vec3 sun_direction(const scene::Scene& scene) {
    const int sun = sun_node(scene);
    if (sun < 0) {
        return {0.5f, std::sqrt(0.5f), 0.5f};
    }
    // The light travels down -z: the sun lies up +z.
    return glm::normalize(glm::vec3(scene.world_matrices()[static_cast<std::size_t>(sun)][2]));
}

ecs::Entity add_sky(ecs::Registry& registry, const scene::Scene& scene, const scene::SkySpec& spec,
                    ecs::Entity sun) {
    const bool daylight = spec.kind == scene::SkySpec::Kind::Daylight;
    const glm::vec3 towards_sun = daylight ? sun_direction(scene) : glm::vec3(0.0f, 1.0f, 0.0f);
    std::shared_ptr<const lighting::SkyRadiance> radiance = make_sky_radiance(spec, towards_sun);
    if (radiance == nullptr) {
        return ecs::null_entity;
    }
    const ecs::Entity entity = registry.create();
    registry.emplace<scene::Name>(entity, "sky");
    registry.emplace<lighting::SkyLight>(entity, std::move(radiance), spec.scale, true);
    if (daylight && registry.valid(sun)) {
        registry.emplace<DaylightSun>(
            entity, DaylightSun{sun, spec.turbidity, spec.irradiance, towards_sun});
    }
    return entity;
}

std::size_t update_sky(ecs::Registry& registry) {
    const float turned = std::cos(glm::radians(DaylightSun::kTurnDegrees));
    std::vector<ecs::Entity> skies;
    for (auto [entity, daylight, sky] : registry.view<DaylightSun, lighting::SkyLight>()) {
        if (registry.valid(daylight.sun)) {
            skies.push_back(entity);
        }
    }
    std::size_t rebuilt = 0;
    for (const ecs::Entity entity : skies) {
        DaylightSun& daylight = registry.get<DaylightSun>(entity);
        const glm::vec3 axis(ecs::compute_world_matrix(registry, daylight.sun)[2]);
        const float length = glm::length(axis);
        if (!(length > 0.0f) || !std::isfinite(length)) {
            continue;
        }
        const glm::vec3 towards_sun = axis / length;
        if (glm::dot(towards_sun, daylight.towards_sun) >= turned) {
            continue;
        }
        daylight.towards_sun = towards_sun;
        auto radiance = std::make_shared<const lighting::SkyRadiance>(
            lighting::daylight_sky(towards_sun, daylight.turbidity, daylight.irradiance));
        registry.patch<lighting::SkyLight>(
            entity, [&](lighting::SkyLight& sky) { sky.radiance = std::move(radiance); });
        ++rebuilt;
    }
    return rebuilt;
}

}  // namespace luxel::world
