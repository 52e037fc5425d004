#include "luxel/lighting/core/unmapped_radiance.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/gtc/constants.hpp>

#include "luxel/lighting/core/irradiance_probes.hpp"
#include "luxel/lighting/core/ray_scene.hpp"
#include "luxel/runtime/tone_map.hpp"

namespace luxel::lighting {
namespace {

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

void UnmappedRadiance::set(const RayScene* scene, std::span<const LightSource* const> lights,
                           const IrradianceProbes* probes) {
    scene_ = scene;
    probes_ = probes;
    lights_.clear();
    for (const LightSource* light : lights) {
        if (light->kind == LightKind::Point || light->kind == LightKind::Spot ||
            light->kind == LightKind::Directional) {
            LightSource& punctual = lights_.emplace_back();
            // The direct light needs no sky, portals or triangles: copied field by field.
            punctual.kind = light->kind;
            punctual.position = light->position;
            punctual.direction = light->direction;
            punctual.power = light->power;
            punctual.inner_cone = light->inner_cone;
            punctual.outer_cone = light->outer_cone;
            punctual.radius = light->radius;
        }
    }
}

glm::vec3 UnmappedRadiance::unshadowed(const LightSource& light, const glm::vec3& origin,
                                       const glm::vec3& normal, glm::vec3& to_light) const {
    if (light.kind == LightKind::Directional) {
        const glm::vec3 w = -glm::normalize(light.direction);
        const float cosine = glm::dot(normal, w);
        to_light = w * 1e6f;  // far beyond the level: the sun's shadow ray
        return cosine > 0.0f ? light.power * cosine : glm::vec3(0.0f);
    }
    to_light = light.position - origin;
    const double distance2 = glm::dot(glm::dvec3(to_light), glm::dvec3(to_light));
    if (!(distance2 > 0.0)) {
        return glm::vec3(0.0f);
    }
    const glm::vec3 w = to_light / static_cast<float>(std::sqrt(distance2));
    const double cosine = glm::dot(normal, w);
    if (cosine <= 0.0) {
        return glm::vec3(0.0f);
    }
    // Radiant intensity as the photon emitter and the frame take it: a point's power over
    // 4 pi, a spot's over its outer cone's solid angle times the falloff.
    double intensity_scale = 1.0 / (4.0 * glm::pi<double>());
    if (light.kind == LightKind::Spot) {
        const double cos_outer =
            std::cos(std::clamp(static_cast<double>(light.outer_cone), 1e-6, glm::pi<double>()));
        const double solid_angle = 2.0 * glm::pi<double>() * (1.0 - cos_outer);
        intensity_scale = solid_angle > 0.0
                              ? spot_falloff(light, -glm::dot(w, light.direction)) / solid_angle
                              : 0.0;
    }
    return glm::vec3(glm::dvec3(light.power) * (intensity_scale * cosine / distance2));
}

glm::vec3 UnmappedRadiance::direct(const glm::vec3& position, const glm::vec3& normal,
                                   double u) const {
    if (scene_ == nullptr || lights_.empty()) {
        return glm::vec3(0.0f);
    }
    // One shadow ray, to one light picked in proportion to what it would deliver unshadowed
    // (and the pick's probability divided out): a level's four or five lights would otherwise
    // cost a ray each for every gather ray that meets such a surface (the sandbox's warm-up:
    // +0.25 s with one per light, docs/PERFORMANCE.md).
    const glm::vec3 origin = offset_ray_origin(position, normal);
    std::array<glm::vec3, kMaxLights> contribution{};
    std::array<glm::vec3, kMaxLights> towards{};
    const std::size_t count = std::min(lights_.size(), kMaxLights);
    double total = 0.0;
    for (std::size_t i = 0; i < count; ++i) {
        contribution[i] = unshadowed(lights_[i], origin, normal, towards[i]);
        total += luminance(glm::dvec3(contribution[i]));
    }
    if (!(total > 0.0)) {
        return glm::vec3(0.0f);
    }
    double pick = u * total;
    std::size_t chosen = count - 1;
    for (std::size_t i = 0; i < count; ++i) {
        const double share = luminance(glm::dvec3(contribution[i]));
        if (pick < share) {
            chosen = i;
            break;
        }
        pick -= share;
    }
    const double probability = luminance(glm::dvec3(contribution[chosen])) / total;
    if (!(probability > 0.0) || scene_->occluded(origin, towards[chosen], 1.0f)) {
        return glm::vec3(0.0f);
    }
    return contribution[chosen] / static_cast<float>(probability);
}

glm::vec3 UnmappedRadiance::exitant(const glm::vec3& position, const glm::vec3& normal,
                                    const glm::vec3& albedo, const glm::dvec2& u) const {
    glm::vec3 irradiance = direct(position, normal, u.x);
    // The probes' lookup (eight probes, each with its visibility test) cost more than the
    // shadow ray: read for one hit in four, weighed four times (the sandbox's warm-up +0.4 s
    // when read at every hit, docs/PERFORMANCE.md). The gathers average many hits.
    if (probes_ != nullptr && u.y < kProbeShare) {
        irradiance += probes_->irradiance(position, normal) / static_cast<float>(kProbeShare);
    }
    const glm::vec3 radiance = albedo * irradiance / glm::pi<float>();
    return finite(radiance) ? glm::max(radiance, glm::vec3(0.0f)) : glm::vec3(0.0f);
}

}  // namespace luxel::lighting
