#include "luxel/lighting/core/cpu_gather.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <optional>
#include <span>
#include <vector>

#include <glm/gtc/constants.hpp>

#include "luxel/lighting/core/halton.hpp"
#include "luxel/lighting/core/light_source.hpp"
#include "luxel/lighting/core/photon_tracer.hpp"
#include "luxel/runtime/jobs.hpp"

namespace luxel::lighting {
namespace {

/// A per-texel rotation of the Halton pattern, from the texel's position bits: deterministic,
/// and different for neighbouring texels.
glm::dvec2 rotation_for(const glm::vec3& position) {
    std::uint32_t hash = 2166136261u;
    for (int axis = 0; axis < 3; ++axis) {
        std::uint32_t bits = 0;
        const float value = position[axis];
        static_assert(sizeof(bits) == sizeof(value));
        std::memcpy(&bits, &value, sizeof(bits));
        hash = (hash ^ bits) * 16777619u;
    }
    hash ^= hash >> 16;
    hash *= 0x7feb352du;
    hash ^= hash >> 15;
    return {static_cast<double>(hash & 0xFFFFu) / 65536.0,
            static_cast<double>(hash >> 16) / 65536.0};
}

constexpr double kTwoPi = 6.283185307179586476925286766559;

/// Halton point i of the gather pattern before the per-texel rotation: u.x (the squared radius
/// of the cosine mapping) and the unit vector (cos, sin) of the azimuth 2 pi u.y.
struct PatternPoint {
    double radius_squared;
    double cos_phi;
    double sin_phi;
};

PatternPoint pattern_point(std::uint32_t i) {
    const glm::dvec2 h = halton2(i);
    const double phi = kTwoPi * h.y;
    return {h.x, std::cos(phi), std::sin(phi)};
}

/// Pattern points are the same for every texel: each thread tabulates them once (up to this
/// many; beyond, they are computed per ray) instead of computing Halton digits and a sincos
/// per ray.
constexpr std::uint32_t kMaxTabulated = 1u << 16;

const std::vector<PatternPoint>& tabulated_pattern(std::uint32_t rays) {
    thread_local std::vector<PatternPoint> points;
    const std::uint32_t wanted = std::min(rays, kMaxTabulated);
    if (points.size() < wanted) {
        points.reserve(wanted);
        for (auto i = static_cast<std::uint32_t>(points.size()); i < wanted; ++i) {
            points.push_back(pattern_point(i));
        }
    }
    return points;
}

bool finite_vector(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// Traces `directions` from `origin` in bundles of 64 that leave together (one Embree stream
/// each, RayScene::intersect_from) and calls visit(i, first hit of ray i) for each, in order.
template <class Visit>
void for_each_first_hit(const RayScene& scene, float max_distance, const glm::vec3& origin,
                        std::span<const glm::vec3> directions, const Visit& visit) {
    constexpr std::size_t kBundle = 64;
    std::array<std::optional<RayHit>, kBundle> hits;
    for (std::size_t first = 0; first < directions.size(); first += kBundle) {
        const std::size_t bundle = std::min(kBundle, directions.size() - first);
        scene.intersect_from(origin, directions.subspan(first, bundle), max_distance,
                             std::span(hits.data(), bundle));
        for (std::size_t k = 0; k < bundle; ++k) {
            visit(first + k, hits[k]);
        }
    }
}

}  // namespace

CpuGatherer::CpuGatherer(const RayScene& scene, const RadianceAtlas& atlas,
                         CpuGatherSettings settings, JobSystem* jobs)
    : scene_(&scene), atlas_(&atlas), settings_(settings), jobs_(jobs) {}

glm::vec3 CpuGatherer::gather_one(const GatherTexel& texel) const {
    const std::uint32_t rays = settings_.rays_per_texel;
    const float normal_length = glm::length(texel.normal);
    if (rays == 0 || !(normal_length > 0.0f) || !finite_vector(texel.position) ||
        !std::isfinite(normal_length)) {
        return glm::vec3(0.0f);
    }
    const glm::vec3 normal = texel.normal / normal_length;
    const glm::vec3 origin = offset_ray_origin(texel.position, normal);
    // A new rotation per pass (the R2 sequence's irrational steps): averaged passes sample
    // the hemisphere where earlier ones did not.
    glm::dvec2 rotation = rotation_for(texel.position);
    rotation +=
        static_cast<double>(texel.pass) * glm::dvec2(0.7548776662466927, 0.5698402909980532);
    rotation -= glm::floor(rotation);
    // cosine_direction(normal, frac(halton2(i) + rotation)), with the tangent frame built once
    // per texel and the azimuth's rotation applied to the tabulated (cos, sin) by the angle
    // sum (exact: the azimuth is periodic, so its wrap-around changes nothing).
    glm::vec3 tangent;
    glm::vec3 bitangent;
    orthonormal_basis(normal, tangent, bitangent);
    const double cos_rotation = std::cos(kTwoPi * rotation.y);
    const double sin_rotation = std::sin(kTwoPi * rotation.y);
    const std::vector<PatternPoint>& pattern = tabulated_pattern(rays);
    const auto seed = static_cast<std::uint32_t>(rotation.x * 4294967295.0);
    // Summed in double: thousands of rays per texel, and the mean must not depend on order.
    glm::dvec3 sum(0.0);
    // The rays leave in bundles from the texel: one stream each (intersect_from).
    constexpr std::uint32_t kBundle = 64;
    std::array<glm::vec3, kBundle> directions;
    std::array<std::optional<RayHit>, kBundle> hits;
    for (std::uint32_t first = 0; first < rays; first += kBundle) {
        const std::uint32_t count = std::min(kBundle, rays - first);
        for (std::uint32_t k = 0; k < count; ++k) {
            const std::uint32_t i = first + k;
            const PatternPoint point = i < pattern.size() ? pattern[i] : pattern_point(i);
            double u = point.radius_squared + rotation.x;
            u -= std::floor(u);
            const double r = std::sqrt(u);
            const auto x = static_cast<float>(
                r * (point.cos_phi * cos_rotation - point.sin_phi * sin_rotation));
            const auto y = static_cast<float>(
                r * (point.sin_phi * cos_rotation + point.cos_phi * sin_rotation));
            const auto z = static_cast<float>(std::sqrt(std::max(0.0, 1.0 - u)));
            directions[k] = glm::normalize(x * tangent + y * bitangent + z * normal);
        }
        scene_->intersect_from(origin, std::span(directions.data(), count), settings_.max_distance,
                               std::span(hits.data(), count));
        for (std::uint32_t k = 0; k < count; ++k) {
            const glm::vec3 radiance = trace(origin, directions[k], hits[k], first + k, seed);
            if (finite_vector(radiance)) {
                sum += glm::dvec3(glm::max(radiance, glm::vec3(0.0f)));
            }
        }
    }
    return glm::vec3(sum * (glm::pi<double>() / static_cast<double>(rays)));
}

glm::vec3 CpuGatherer::trace(glm::vec3 origin, glm::vec3 direction, std::optional<RayHit> hit,
                             std::uint32_t ray, std::uint32_t seed) const {
    glm::vec3 weight(1.0f);
    ClosedMedium medium;
    for (std::uint32_t interaction = 0; interaction <= settings_.max_specular; ++interaction) {
        if (interaction > 0) {
            hit = scene_->intersect(origin, direction, settings_.max_distance);
        }
        if (!hit) {
            // Left the level: the sky (black without one).
            return atlas_->skies.empty() ? glm::vec3(0.0f) : weight * atlas_->sky(direction);
        }
        const TraceMaterial* material = materials_ != nullptr && hit->material < materials_->size()
                                            ? &(*materials_)[hit->material]
                                            : nullptr;
        if (material == nullptr || material->scattering == Scattering::Diffuse) {
            // The AIM holds the radiance leaving a surface's front; a back face is the inside
            // of a wall or object and sends nothing.
            if (glm::dot(hit->geometric_normal, direction) >= 0.0f) {
                return glm::vec3(0.0f);
            }
            medium.absorb(hit->distance, weight);
            if (unmapped_ != nullptr && settings_.unmapped_radiance && !has_light_map(*hit) &&
                !emits(*hit)) {
                // No AIM here: the surface's own estimate (UnmappedRadiance), not black.
                // Its light pick: a sample dimension past those the specular scatters use.
                return weight *
                       unmapped_->exitant(
                           hit->position, facing_normals(*hit, direction).shading,
                           material != nullptr ? material->albedo : TraceMaterial{}.albedo,
                           glm::dvec2(photon_sample(ray, 5 + settings_.max_specular, seed),
                                      photon_sample(ray, 6 + settings_.max_specular, seed)));
            }
            return weight * atlas_->sample(hit->surface, hit->lightmap_uv);
        }
        // A mirror or glass has no AIM of its own: it shows what it reflects or refracts (the
        // room seen through a glass sphere, and the light that focuses through it after a
        // diffuse bounce). Fresnel picks one branch per ray, as photons do. Radiance changes by
        // the indices' ratio squared across a closed solid's surface, which photons (carrying
        // power) never see: a texel under a glass block resting on it gathers from inside the
        // block, and without the factor read the light through it 1 / ior^2 too dark
        // (tinted-glass's floor under the block: 0.43 of luxel-ref's indirect).
        const FacingNormals normals = facing_normals(*hit, direction);
        const bool refracted =
            scatter_specular(*material, *hit, normals, photon_sample(ray, 4 + interaction, seed),
                             origin, direction, weight);
        if (refracted) {
            weight *= refracted_radiance_scale(*material, normals.front);
        }
        medium.update(*material, normals.front, refracted);
        if (!(weight.r > 0.0f || weight.g > 0.0f || weight.b > 0.0f)) {
            return glm::vec3(0.0f);
        }
    }
    return glm::vec3(0.0f);  // trapped between specular surfaces
}

bool CpuGatherer::has_light_map(const RayHit& hit) const {
    return hit.surface >= 0 &&
           static_cast<std::size_t>(hit.surface) < atlas_->surface_page.size() &&
           atlas_->surface_page[static_cast<std::size_t>(hit.surface)] >= 0;
}

bool CpuGatherer::emits(const RayHit& hit) const {
    return hit.surface >= 0 &&
           static_cast<std::size_t>(hit.surface) < atlas_->surface_emission.size() &&
           glm::any(glm::greaterThan(
               atlas_->surface_emission[static_cast<std::size_t>(hit.surface)], glm::vec3(0.0f)));
}

bool CpuGatherer::see_through(const RayHit& hit) const {
    const bool mapped = has_light_map(hit);
    const bool emits = this->emits(hit);
    const TraceMaterial* material = materials_ != nullptr && hit.material < materials_->size()
                                        ? &(*materials_)[hit.material]
                                        : nullptr;
    const bool diffuse = material == nullptr || material->scattering == Scattering::Diffuse;
    return diffuse && !mapped && !emits;
}

void CpuGatherer::trace_gather_rays(const glm::vec3& origin, std::span<const glm::vec3> directions,
                                    std::span<glm::vec3> radiance, std::uint32_t seed,
                                    std::span<std::uint8_t> specular) const {
    const std::size_t count = std::min(directions.size(), radiance.size());
    for_each_first_hit(
        *scene_, settings_.max_distance, origin, directions.first(count),
        [&](std::size_t i, const std::optional<RayHit>& hit) {
            if (i < specular.size()) {
                specular[i] = hit && materials_ != nullptr && hit->material < materials_->size() &&
                                      (*materials_)[hit->material].scattering != Scattering::Diffuse
                                  ? 1
                                  : 0;
            }
            const glm::vec3 l =
                trace(origin, directions[i], hit, static_cast<std::uint32_t>(i), seed);
            radiance[i] = finite_vector(l) ? glm::max(l, glm::vec3(0.0f)) : glm::vec3(0.0f);
        });
}

void CpuGatherer::trace_probe_rays(const glm::vec3& origin, std::span<const glm::vec3> directions,
                                   std::span<ProbeRay> rays, std::uint32_t seed) const {
    const std::size_t count = std::min(directions.size(), rays.size());
    // Geometry a ray may pass through before it gives up (a crowd of props in a row).
    constexpr int kMaxSeeThrough = 8;
    for_each_first_hit(
        *scene_, settings_.max_distance, origin, directions.first(count),
        [&](std::size_t i, const std::optional<RayHit>& first_hit) {
            const glm::vec3 direction = directions[i];
            std::optional<RayHit> hit = first_hit;
            glm::vec3 from = origin;
            float travelled = 0.0f;
            for (int pass = 0; pass < kMaxSeeThrough && hit && see_through(*hit); ++pass) {
                travelled += hit->distance;
                const float side = glm::dot(hit->geometric_normal, direction) > 0.0f ? 1.0f : -1.0f;
                from = offset_ray_origin(hit->position, hit->geometric_normal, side);
                hit = scene_->intersect(from, direction,
                                        std::max(settings_.max_distance - travelled, 0.0f));
            }
            ProbeRay& out = rays[i];
            out.distance = hit ? travelled + hit->distance : settings_.max_distance;
            out.hit = hit.has_value();
            const TraceMaterial* material =
                hit && materials_ != nullptr && hit->material < materials_->size()
                    ? &(*materials_)[hit->material]
                    : nullptr;
            const bool diffuse = material == nullptr || material->scattering == Scattering::Diffuse;
            out.back_face =
                hit.has_value() && diffuse && glm::dot(hit->geometric_normal, direction) >= 0.0f;
            const glm::vec3 radiance =
                trace(from, direction, hit, static_cast<std::uint32_t>(i), seed);
            out.radiance =
                finite_vector(radiance) ? glm::max(radiance, glm::vec3(0.0f)) : glm::vec3(0.0f);
        });
}

void CpuGatherer::gather(std::span<const GatherTexel> texels, std::span<glm::vec3> irradiance) {
    const std::size_t count = std::min(texels.size(), irradiance.size());
    if (jobs_ != nullptr && count > 1) {
        jobs_->parallel_for(0, count,
                            [&](std::size_t i) { irradiance[i] = gather_one(texels[i]); });
    } else {
        for (std::size_t i = 0; i < count; ++i) {
            irradiance[i] = gather_one(texels[i]);
        }
    }
    rays_traced_ += static_cast<std::uint64_t>(count) * settings_.rays_per_texel;
}

}  // namespace luxel::lighting
