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

/// The density per steradian with which a point chosen uniformly by area on `portals` lies in
/// direction `w` (unit) from `origin`: over every portal triangle the ray meets, its distance
/// squared over the total area times the cosine there (0 when it meets none).
double portal_density(const TriangleSampler& portals, const glm::vec3& origin, const glm::vec3& w) {
    if (portals.size() == 0 || !(portals.area() > 0.0)) {
        return 0.0;
    }
    double density = 0.0;
    const std::vector<glm::vec3>& v = portals.vertices();
    for (std::size_t t = 0; t < portals.size(); ++t) {
        // Moller-Trumbore, in double: the portals are few.
        const glm::dvec3 a(v[3 * t]);
        const glm::dvec3 e1 = glm::dvec3(v[3 * t + 1]) - a;
        const glm::dvec3 e2 = glm::dvec3(v[3 * t + 2]) - a;
        const glm::dvec3 dir(w);
        const glm::dvec3 p = glm::cross(dir, e2);
        const double det = glm::dot(e1, p);
        if (!(std::abs(det) > 1e-18)) {
            continue;
        }
        const glm::dvec3 s = glm::dvec3(origin) - a;
        const double u = glm::dot(s, p) / det;
        const glm::dvec3 q = glm::cross(s, e1);
        const double vv = glm::dot(dir, q) / det;
        const double distance = glm::dot(e2, q) / det;
        if (u < 0.0 || vv < 0.0 || u + vv > 1.0 || !(distance > 0.0)) {
            continue;
        }
        const double cosine = std::abs(glm::dot(glm::normalize(glm::cross(e1, e2)), dir));
        if (cosine > 0.0) {
            density += distance * distance / (portals.area() * cosine);
        }
    }
    return density;
}

void add(Components& out, Component component, const glm::dvec3& value, PathCounters& counters) {
    if (finite(value)) {
        out[component] += value;
    } else {
        ++counters.non_finite;
    }
}

}  // namespace

glm::dvec3 PathEstimator::sphere_light(const ReferenceLight& light, const SphereSample& sphere,
                                       const glm::vec3& origin, const glm::vec3& normal,
                                       const glm::vec3& geometric, PathCounters& counters) const {
    const LightSource& source = light.source;
    const double cosine = glm::dot(normal, sphere.direction);
    if (cosine <= 0.0 || glm::dot(geometric, sphere.direction) <= 0.0f) {
        return glm::dvec3(0.0);
    }
    // A spot's falloff is the centre's: the cone does not change across its sphere.
    double intensity_scale = 1.0;
    if (source.kind == LightKind::Spot) {
        const glm::vec3 to_centre = glm::normalize(source.position - origin);
        intensity_scale = spot_falloff(source, -glm::dot(to_centre, source.direction));
    }
    if (intensity_scale <= 0.0) {
        return glm::dvec3(0.0);
    }
    ++counters.rays;
    if (scene_->rays().occluded(origin, sphere.direction * sphere.distance, 1.0f)) {
        return glm::dvec3(0.0);
    }
    const double r = static_cast<double>(source.radius);
    const double radiance_scale = intensity_scale / (glm::pi<double>() * r * r);  // L / I
    return glm::dvec3(light.intensity) * (radiance_scale * cosine * sphere.solid_angle);
}

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
                if (source.radius > 0.0f) {
                    SphereSample sphere;
                    if (sample_sphere_light(origin, source.position, source.radius, random.next2(),
                                            sphere)) {
                        irradiance +=
                            sphere_light(light, sphere, origin, normal, geometric, counters);
                        break;
                    }
                }
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
            case LightKind::Sky:
                gathered += sky_light(light, origin, normal, geometric, random, counters);
                break;
        }
    }
    return out;
}

glm::dvec3 PathEstimator::sky_light(const ReferenceLight& light, const glm::vec3& origin,
                                    const glm::vec3& normal, const glm::vec3& geometric,
                                    SampleStream& random, PathCounters& counters) const {
    const LightSource& source = light.source;
    if (source.sky == nullptr) {
        return glm::dvec3(0.0);
    }
    const RayScene& rays = scene_->rays();
    glm::dvec3 gathered(0.0);
    // One sample of a strategy with density `pdf` at `w`, weighed against the others.
    auto add_sample = [&](const glm::vec3& w, double pdf, bool by_sky) {
        const double cosine = glm::dot(normal, w);
        if (!(pdf > 0.0) || cosine <= 0.0 || glm::dot(geometric, w) <= 0.0f) {
            return;
        }
        const double pdf_sky = by_sky ? pdf : source.sky->pdf(w);
        const double pdf_portal = by_sky ? portal_density(light.portals, origin, w) : pdf;
        const double pdf_bsdf = cosine / kPi;
        const double sum = pdf_sky * pdf_sky + pdf_portal * pdf_portal + pdf_bsdf * pdf_bsdf;
        ++counters.rays;
        if (rays.occluded(origin, w, std::numeric_limits<float>::infinity())) {
            return;
        }
        gathered += glm::dvec3(sky_radiance(source, w)) * (cosine / pdf * (pdf * pdf / sum));
    };
    // The sky's own distribution: its bright regions, wherever the openings are.
    const SkyRadiance::Sample from = source.sky->sample(random.next2());
    add_sample(from.direction, from.pdf, true);
    // Towards a point on the portals: the openings, whatever the sky there.
    if (light.portals.size() > 0) {
        const TriangleSampler::Sample at = light.portals.sample(random.next2());
        const glm::vec3 to = at.point - origin;
        const float length = glm::length(to);
        if (length > 0.0f && std::isfinite(length)) {
            const glm::vec3 w = to / length;
            add_sample(w, portal_density(light.portals, origin, w), false);
        }
    }
    return gathered;
}

glm::dvec3 PathEstimator::escaped(const glm::vec3& origin, const glm::vec3& direction,
                                  double pdf) const {
    glm::dvec3 radiance(0.0);
    for (const ReferenceLight& light : scene_->lights()) {
        if (light.source.kind != LightKind::Sky || light.source.sky == nullptr) {
            continue;
        }
        const glm::dvec3 sky(sky_radiance(light.source, direction));
        // After a diffuse vertex its next-event estimates also sampled this sky (and its
        // portals): weigh them.
        double weight = 1.0;
        if (pdf > 0.0) {
            const double pdf_sky = light.source.sky->pdf(direction);
            const double pdf_portal = portal_density(light.portals, origin, direction);
            const double sum = pdf * pdf + pdf_sky * pdf_sky + pdf_portal * pdf_portal;
            weight = sum > 0.0 ? pdf * pdf / sum : 1.0;
        }
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
    ClosedMedium medium;
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
            add(out, component, beta * escaped(origin, direction, pdf), counters);
            return;
        }
        const FacingNormals normals = facing_normals(*hit, direction);
        const TraceMaterial& material = materials[hit->material];
        if (material.scattering == Scattering::Diffuse) {
            // The segment ends inside a closed solid (a bulb in a glass globe, a floor under a
            // block): its absorption, which scatter_specular takes only at the solid's faces.
            glm::vec3 kept(beta);
            medium.absorb(hit->distance, kept);
            beta = glm::dvec3(kept);
        }
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
        if (material.scattering != Scattering::Diffuse) {
            glm::vec3 power(beta);
            // A path carries radiance (importance), which changes by the indices' ratio squared
            // across a closed solid's surface: the photon estimates keep power and need nothing.
            const bool refracted =
                scatter_specular(material, *hit, normals, random.next(), origin, direction, power);
            if (refracted) {
                power *= refracted_radiance_scale(material, normals.front);
            }
            medium.update(material, normals.front, refracted);
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
        const glm::dvec3 albedo(scene_->diffuse_albedo(*hit, material));
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
