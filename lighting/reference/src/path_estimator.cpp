#include "luxel/lighting/reference/path_estimator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/constants.hpp>

namespace luxel::lighting::reference {
namespace {

constexpr double kPi = glm::pi<double>();

bool finite(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// Power-heuristic weight of a strategy of density `mine` against one of density `other`.
double power_heuristic(double mine, double other) {
    const double a = mine * mine;
    const double b = other * other;
    return a + b > 0.0 ? a / (a + b) : 0.0;
}

void add(Components& out, Component component, const glm::dvec3& value, PathCounters& counters) {
    if (finite(value)) {
        out[component] += value;
    } else {
        ++counters.non_finite;
    }
}

}  // namespace

const char* component_name(Component component) {
    switch (component) {
        case Component::Direct:
            return "direct";
        case Component::Indirect:
            return "indirect";
        case Component::Caustic:
            return "caustic";
    }
    return "unknown";
}

PathEstimator::PathEstimator(const ReferenceScene& scene, PathSettings settings,
                             std::span<const glm::dvec3> caustic_irradiance)
    : scene_(&scene), settings_(settings), caustics_(caustic_irradiance) {}

PathEstimator::DirectLight PathEstimator::direct_light(const glm::vec3& point,
                                                       const glm::vec3& normal,
                                                       const glm::vec3& geometric,
                                                       SampleStream& random,
                                                       PathCounters& counters) const {
    const RayScene& rays = scene_->rays();
    const glm::vec3 origin = offset_ray_origin(point, geometric);
    DirectLight out;
    glm::dvec3& irradiance = out.delta;
    glm::dvec3& gathered = out.gathered;
    for (const ReferenceLight& light : scene_->lights()) {
        const LightSource& source = light.source;
        switch (source.kind) {
            case LightKind::Point:
            case LightKind::Spot: {
                const glm::vec3 to_light = source.position - origin;
                const double distance2 = glm::dot(glm::dvec3(to_light), glm::dvec3(to_light));
                if (!(distance2 > 0.0)) {
                    break;
                }
                const glm::vec3 w = glm::normalize(to_light);
                const double cosine = glm::dot(normal, w);
                if (cosine <= 0.0 || glm::dot(geometric, w) <= 0.0f) {
                    break;
                }
                double intensity_scale = 1.0;
                if (source.kind == LightKind::Spot) {
                    intensity_scale = spot_falloff(source, -glm::dot(w, source.direction));
                }
                if (intensity_scale <= 0.0) {
                    break;
                }
                ++counters.rays;
                if (rays.occluded(origin, to_light, 1.0f)) {
                    break;
                }
                irradiance += glm::dvec3(light.intensity) * (intensity_scale * cosine / distance2);
                break;
            }
            case LightKind::Directional: {
                const glm::vec3 w = -glm::normalize(source.direction);
                const double cosine = glm::dot(normal, w);
                if (cosine <= 0.0 || glm::dot(geometric, w) <= 0.0f) {
                    break;
                }
                ++counters.rays;
                if (rays.occluded(origin, w, std::numeric_limits<float>::infinity())) {
                    break;
                }
                irradiance += glm::dvec3(source.power) * cosine;
                break;
            }
            case LightKind::Area: {
                const TriangleSampler::Sample sample = light.triangles.sample(random.next2());
                if (!(sample.density > 0.0)) {
                    break;
                }
                const glm::vec3 to_light = sample.point - origin;
                const double distance2 = glm::dot(glm::dvec3(to_light), glm::dvec3(to_light));
                if (!(distance2 > 0.0)) {
                    break;
                }
                const glm::vec3 w = glm::normalize(to_light);
                const double cos_light = -glm::dot(sample.normal, w);
                const double cosine = glm::dot(normal, w);
                if (cos_light <= 0.0 || cosine <= 0.0 || glm::dot(geometric, w) <= 0.0f) {
                    break;
                }
                // Aim at the sample moved off the light toward its emitting side, so the
                // light's own triangle does not occlude it.
                const glm::vec3 target = offset_ray_origin(sample.point, sample.normal);
                ++counters.rays;
                if (rays.occluded(origin, target - origin, 1.0f)) {
                    break;
                }
                const double pdf_light = distance2 * sample.density / cos_light;  // per sr
                const double pdf_bsdf = cosine / kPi;
                gathered += glm::dvec3(area_radiance(source, sample.triangle, sample.piece)) *
                            (cosine / pdf_light * power_heuristic(pdf_light, pdf_bsdf));
                break;
            }
            case LightKind::Sky: {
                // A direction by the sky's distribution, weighed against the cosine-sampled
                // continuation that may leave the scene the same way (trace()'s escape).
                if (source.sky == nullptr) {
                    break;
                }
                const SkyRadiance::Sample from = source.sky->sample(random.next2());
                const glm::vec3& w = from.direction;
                const double cosine = glm::dot(normal, w);
                if (!(from.pdf > 0.0) || cosine <= 0.0 || glm::dot(geometric, w) <= 0.0f) {
                    break;
                }
                ++counters.rays;
                if (rays.occluded(origin, w, std::numeric_limits<float>::infinity())) {
                    break;
                }
                gathered += glm::dvec3(from.radiance) *
                            (static_cast<double>(source.sky_scale) * cosine / from.pdf *
                             power_heuristic(from.pdf, cosine / kPi));
                break;
            }
        }
    }
    return out;
}

glm::dvec3 PathEstimator::escaped(const glm::vec3& direction, double pdf) const {
    glm::dvec3 radiance(0.0);
    for (const ReferenceLight& light : scene_->lights()) {
        if (light.source.kind != LightKind::Sky || light.source.sky == nullptr) {
            continue;
        }
        const glm::dvec3 sky(sky_radiance(light.source, direction));
        // After a diffuse vertex its next-event estimate also sampled this sky: weigh the two.
        const double weight =
            pdf > 0.0 ? power_heuristic(pdf, light.source.sky->pdf(direction)) : 1.0;
        radiance += sky * weight;
    }
    return radiance;
}

void PathEstimator::trace(glm::vec3 origin, glm::vec3 direction, glm::dvec3 beta, double pdf,
                          bool from_texel, SampleStream& random, Components& out,
                          PathCounters& counters) const {
    const RayScene& rays = scene_->rays();
    const auto materials = scene_->materials();
    bool first_segment = from_texel;
    bool any_diffuse = false;
    for (std::uint32_t vertex = 0;; ++vertex) {
        if (vertex >= settings_.max_vertices) {
            ++counters.truncated;
            return;
        }
        ++counters.rays;
        const auto hit = rays.intersect(origin, direction);
        const Component component = first_segment ? gathered_direct()
                                    : any_diffuse ? Component::Indirect
                                                  : Component::Caustic;
        if (!hit) {
            // Left the scene: the sky, if it has one.
            add(out, component, beta * escaped(direction, pdf), counters);
            return;
        }
        const FacingNormals normals = facing_normals(*hit, direction);
        if (normals.front) {
            if (const EmitterHit emitter = scene_->emitter_of(*hit); emitter.light >= 0) {
                const ReferenceScene::Emission emission =
                    scene_->emission_at(emitter, hit->position);
                double weight = 1.0;
                if (pdf > 0.0) {
                    // The previous diffuse vertex also sampled this light: weigh the two.
                    const double cos_light = -glm::dot(hit->geometric_normal, direction);
                    const double distance = hit->distance;
                    const double pdf_light =
                        cos_light > 0.0 && emission.density > 0.0
                            ? distance * distance * emission.density / cos_light
                            : std::numeric_limits<double>::infinity();
                    weight = std::isinf(pdf_light) ? 1.0 : power_heuristic(pdf, pdf_light);
                }
                add(out, component, beta * glm::dvec3(emission.radiance) * weight, counters);
            }
        }
        const TraceMaterial& material = materials[hit->material];
        if (material.scattering != Scattering::Diffuse) {
            glm::vec3 power(beta);
            scatter_specular(material, *hit, normals, random.next(), origin, direction, power);
            beta = glm::dvec3(power);
            pdf = 0.0;
            first_segment = false;
            if (!(glm::max(beta.x, glm::max(beta.y, beta.z)) > 0.0)) {
                return;
            }
            continue;
        }
        if (!normals.front) {
            return;  // one-sided: the back of a diffuse surface absorbs
        }
        if (!settings_.indirect) {
            return;
        }
        first_segment = false;
        any_diffuse = true;
        const glm::dvec3 albedo(material.albedo);
        const glm::vec3& n = normals.geometric;
        const glm::dvec3 reflect = beta * albedo / kPi;
        if (settings_.caustic_bounce && !caustics_.empty() && hit->surface >= 0) {
            const std::int64_t t = scene_->texel_at(hit->surface, hit->lightmap_uv);
            if (t >= 0 && static_cast<std::size_t>(t) < caustics_.size()) {
                add(out, Component::Indirect, reflect * caustics_[static_cast<std::size_t>(t)],
                    counters);
            }
        }
        const DirectLight next = direct_light(hit->position, n, n, random, counters);
        add(out, Component::Indirect, reflect * (next.delta + next.gathered), counters);
        const double survival = std::min(glm::max(albedo.x, glm::max(albedo.y, albedo.z)), 1.0);
        if (!(survival > 0.0) || random.next() >= survival) {
            return;
        }
        beta *= albedo / survival;
        direction = cosine_direction(n, random.next2());
        pdf = glm::dot(n, direction) / kPi;
        if (!(pdf > 0.0)) {
            return;
        }
        origin = offset_ray_origin(hit->position, n);
    }
}

Components PathEstimator::irradiance(const ReferenceTexel& texel, SampleStream& random,
                                     PathCounters& counters) const {
    Components out;
    const DirectLight direct =
        direct_light(texel.position, texel.normal, texel.geometric, random, counters);
    add(out, Component::Direct, direct.delta, counters);
    add(out, gathered_direct(), direct.gathered, counters);
    const glm::vec3 direction = cosine_direction(texel.normal, random.next2());
    const double cosine = glm::dot(texel.normal, direction);
    // A direction below the face would leave through the surface: it carries nothing (its
    // share of the hemisphere is (tilt)^2 / 4, under 1e-3 for a 3.6 degree tilt).
    if (cosine > 0.0 && glm::dot(texel.geometric, direction) > 0.0f) {
        // Cosine sampling: E = integral L cos dw is estimated by pi L(w).
        trace(offset_ray_origin(texel.position, texel.geometric), direction, glm::dvec3(kPi),
              cosine / kPi, true, random, out, counters);
    }
    return out;
}

glm::dvec3 PathEstimator::radiance(const glm::vec3& origin, const glm::vec3& direction,
                                   SampleStream& random, PathCounters& counters) const {
    Components out;
    trace(origin, direction, glm::dvec3(1.0), 0.0, false, random, out, counters);
    return out.total();
}

}  // namespace luxel::lighting::reference
