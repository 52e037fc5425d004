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

/// A daylight sky for a sun towards `towards_sun` (unit), with the ground `albedo` lit by it
/// and by the sun's `sun_irradiance` when the albedo is not 0.
lighting::SkyRadiance daylight_with_ground(const glm::vec3& towards_sun, float turbidity,
                                           float irradiance, const glm::vec3& albedo,
                                           const glm::vec3& sun_irradiance) {
    lighting::SkyRadiance sky = lighting::daylight_sky(towards_sun, turbidity, irradiance);
    if (albedo == glm::vec3(0.0f)) {
        return sky;
    }
    return lighting::with_ground(sky, albedo, sun_irradiance * std::max(towards_sun.y, 0.0f));
}

}  // namespace

std::shared_ptr<const lighting::SkyRadiance> make_sky_radiance(const scene::SkySpec& spec,
                                                               const glm::vec3& towards_sun,
                                                               const glm::vec3& sun_irradiance) {
    switch (spec.kind) {
        case scene::SkySpec::Kind::None:
            return nullptr;
        case scene::SkySpec::Kind::Uniform: {
            const lighting::SkyRadiance sky = lighting::SkyRadiance::uniform(spec.radiance);
            return std::make_shared<const lighting::SkyRadiance>(
                spec.ground == glm::vec3(0.0f)
                    ? sky
                    : lighting::with_ground(sky, spec.ground, glm::vec3(0.0f)));
        }
        case scene::SkySpec::Kind::Daylight:
            return std::make_shared<const lighting::SkyRadiance>(daylight_with_ground(
                towards_sun, spec.turbidity, spec.irradiance, spec.ground, sun_irradiance));
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

namespace {

/// The irradiance of `scene`'s sun facing it, W/m^2 (0 without a sun).
glm::vec3 scene_sun_irradiance(const scene::Scene& scene) {
    const int sun = sun_node(scene);
    if (sun < 0) {
        return glm::vec3(0.0f);
    }
    const scene::Node& node = scene.nodes.at(static_cast<std::size_t>(sun));
    return scene.lights.at(static_cast<std::size_t>(node.light)).irradiance();
}

/// The irradiance the sun entity gives now: its DirectionalLight's, 0 while it is off; a
/// negative or non-finite channel reads 0 (a NaN would never compare equal, and rebuild the sky
/// every frame).
glm::vec3 sun_light_now(const ecs::Registry& registry, ecs::Entity sun) {
    const auto* light = registry.try_get<lighting::DirectionalLight>(sun);
    if (light == nullptr || !light->enabled) {
        return glm::vec3(0.0f);
    }
    glm::vec3 out(0.0f);
    for (int c = 0; c < 3; ++c) {
        const float v = light->irradiance[c];
        out[c] = std::isfinite(v) && v > 0.0f ? v : 0.0f;
    }
    return out;
}

}  // namespace

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
    std::shared_ptr<const lighting::SkyRadiance> radiance = make_sky_radiance(
        spec, towards_sun, daylight ? scene_sun_irradiance(scene) : glm::vec3(0.0f));
    if (radiance == nullptr) {
        return ecs::null_entity;
    }
    const ecs::Entity entity = registry.create();
    registry.emplace<scene::Name>(entity, "sky");
    registry.emplace<lighting::SkyLight>(entity, std::move(radiance), spec.scale, true);
    if (daylight && registry.valid(sun)) {
        registry.emplace<DaylightSun>(
            entity, DaylightSun{sun, spec.turbidity, spec.irradiance, towards_sun, spec.ground,
                                sun_light_now(registry, sun)});
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
        const glm::vec3 sun_irradiance = sun_light_now(registry, daylight.sun);
        const bool ground_changed =
            daylight.ground != glm::vec3(0.0f) && sun_irradiance != daylight.sun_irradiance;
        if (glm::dot(towards_sun, daylight.towards_sun) >= turned && !ground_changed) {
            continue;
        }
        daylight.towards_sun = towards_sun;
        daylight.sun_irradiance = sun_irradiance;
        auto radiance = std::make_shared<const lighting::SkyRadiance>(daylight_with_ground(
            towards_sun, daylight.turbidity, daylight.irradiance, daylight.ground, sun_irradiance));
        registry.patch<lighting::SkyLight>(
            entity, [&](lighting::SkyLight& sky) { sky.radiance = std::move(radiance); });
        ++rebuilt;
    }
    return rebuilt;
}

}  // namespace luxel::world
