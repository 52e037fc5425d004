#include "luxel/lighting/core/photon_tracer.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "luxel/lighting/core/halton.hpp"
#include "luxel/lighting/core/optics.hpp"
#include "luxel/scene/volume.hpp"

namespace luxel::lighting {
namespace {

/// SplitMix64's finaliser: a well-mixed 64-bit hash.
std::uint64_t mix(std::uint64_t x) {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

double unit_from_bits(std::uint64_t bits) {
    return static_cast<double>(bits >> 11) * 0x1.0p-53;
}

}  // namespace

double photon_sample(std::uint64_t index, std::uint32_t dim, std::uint32_t seed) {
    if (dim < kHaltonPrimes.size()) {
        const double value = radical_inverse_in_dimension(dim, index);
        if (dim < 4) {
            return value;
        }
        const double shifted =
            value + unit_from_bits(mix((static_cast<std::uint64_t>(seed) << 32) ^ dim));
        return shifted >= 1.0 ? shifted - 1.0 : shifted;
    }
    return unit_from_bits(mix(mix(index ^ (static_cast<std::uint64_t>(seed) << 40)) + dim));
}

TraceCounters& TraceCounters::operator+=(const TraceCounters& other) {
    photons += other.photons;
    segments += other.segments;
    diffuse_hits += other.diffuse_hits;
    absorbed_back_faces += other.absorbed_back_faces;
    truncated += other.truncated;
    return *this;
}

FacingNormals facing_normals(const RayHit& hit, const glm::vec3& direction) {
    FacingNormals normals;
    normals.front = glm::dot(hit.geometric_normal, direction) < 0.0f;
    normals.geometric = normals.front ? hit.geometric_normal : -hit.geometric_normal;
    normals.shading = normals.front ? hit.shading_normal : -hit.shading_normal;
    if (glm::dot(normals.shading, normals.geometric) <= 0.0f) {
        normals.shading = normals.geometric;  // interpolated normal bent past the face
    }
    return normals;
}

bool scatter_specular(const TraceMaterial& material, const RayHit& hit,
                      const FacingNormals& normals, double xi, glm::vec3& origin,
                      glm::vec3& direction, glm::vec3& power) {
    const float cos_incident = std::clamp(-glm::dot(direction, normals.shading), 0.0f, 1.0f);
    if (material.scattering == Scattering::Mirror) {
        power *= optics::fresnel_conductor(cos_incident, material.tint);
        direction = optics::reflect(direction, normals.shading);
        origin = offset_ray_origin(hit.position, normals.geometric);
        return false;
    }
    if (!normals.front && material.attenuation_distance < std::numeric_limits<float>::infinity()) {
        power *= scene::beer_lambert(material.attenuation_color, material.attenuation_distance,
                                     hit.distance);
    }
    // Arriving on the front face means going from air into the medium.
    const float eta_from = normals.front ? 1.0f : material.ior;
    const float eta_to = normals.front ? material.ior : 1.0f;
    const float reflectance = optics::fresnel_dielectric(cos_incident, eta_from, eta_to);
    const auto refracted = optics::refract(direction, normals.shading, eta_from, eta_to);
    if (!refracted || xi < static_cast<double>(reflectance)) {
        direction = optics::reflect(direction, normals.shading);
        origin = offset_ray_origin(hit.position, normals.geometric);
        return false;
    }
    direction = *refracted;
    power *= material.tint;
    origin = offset_ray_origin(hit.position, normals.geometric, -1.0f);
    return true;
}

void ClosedMedium::update(const TraceMaterial& material, bool front, bool refracted) {
    if (material.scattering != Scattering::Dielectric || !material.closed) {
        return;
    }
    // Refracted through the front: now inside; through the back: out. Reflected off the back
    // (total internal reflection, or Fresnel's share): still inside. Off the front: as before.
    if (refracted || !front) {
        inside_ = refracted ? front : true;
        attenuation_color_ = material.attenuation_color;
        attenuation_distance_ = material.attenuation_distance;
    }
}

void ClosedMedium::absorb(float distance, glm::vec3& power) const {
    if (inside_ && attenuation_distance_ < std::numeric_limits<float>::infinity()) {
        power *= scene::beer_lambert(attenuation_color_, attenuation_distance_, distance);
    }
}

float refracted_radiance_scale(const TraceMaterial& material, bool front) {
    // A non-positive or non-finite index is no medium (scene::Material clamps it; this guards
    // a hand-made TraceMaterial): nothing to scale.
    const float ior = material.ior;
    if (material.scattering != Scattering::Dielectric || !material.closed || !(ior > 0.0f) ||
        !std::isfinite(ior)) {
        return 1.0f;
    }
    return front ? 1.0f / (ior * ior) : ior * ior;
}

void trace_photon(const RayScene& scene, std::span<const TraceMaterial> materials,
                  const EmittedPhoton& photon, std::uint64_t index, std::uint32_t seed,
                  const TraceLimits& limits, std::vector<TracedHop>& hops,
                  TraceCounters& counters) {
    ++counters.photons;
    glm::vec3 origin = photon.origin;
    glm::vec3 direction = photon.direction;
    glm::vec3 power = photon.power;
    std::uint32_t bounces = 0;
    std::uint32_t dim = 4;  // 0-3 were spent on emission
    ClosedMedium medium;
    if (!(power.r > 0.0f || power.g > 0.0f || power.b > 0.0f)) {
        return;
    }
    // A photon from a portal carries the sky seen through it: none where the level itself (the
    // room behind a photon sent outwards, a building outside) hides the sky.
    if (photon.from_portal &&
        scene.occluded(origin, -direction, std::numeric_limits<float>::infinity())) {
        return;
    }
    for (std::uint32_t interaction = 0;; ++interaction) {
        if (interaction >= limits.max_interactions) {
            ++counters.truncated;
            return;
        }
        ++counters.segments;
        const auto hit = scene.intersect(origin, direction);
        if (!hit) {
            return;  // left the scene
        }
        const TraceMaterial fallback{};
        const TraceMaterial& material =
            hit->material < materials.size() ? materials[hit->material] : fallback;
        const FacingNormals normals = facing_normals(*hit, direction);
        const bool front = normals.front;
        const glm::vec3& facing_geometric = normals.geometric;
        const glm::vec3& facing_shading = normals.shading;

        if (material.scattering == Scattering::Diffuse) {
            if (!front) {
                ++counters.absorbed_back_faces;
                return;
            }
            ++counters.diffuse_hits;
            medium.absorb(hit->distance, power);
            hops.push_back({hit->position, power, hit->surface, hit->object, bounces});
            // Russian roulette (docs/METHOD.md §4.3): survive with p = max albedo channel, and
            // keep the expected power by dividing by p.
            const float survival =
                std::max(material.albedo.r, std::max(material.albedo.g, material.albedo.b));
            const double xi = photon_sample(index, dim++, seed);
            if (!(survival > 0.0f) || xi >= static_cast<double>(survival)) {
                return;
            }
            power *= material.albedo / survival;
            const glm::dvec2 u(photon_sample(index, dim, seed),
                               photon_sample(index, dim + 1, seed));
            dim += 2;
            direction = cosine_direction(facing_shading, u);
            // The shading normal can send a direction below the geometric surface (more often
            // the coarser the mesh). Absorbing it loses energy on every bounce: 3e-4 of the
            // hops on the furnace sphere, 28% of the light at albedo 0.999. Mirroring it back
            // across the surface's plane keeps the energy and the direction's spread.
            const float below = glm::dot(direction, facing_geometric);
            if (below <= 0.0f) {
                direction = glm::normalize(direction - 2.0f * below * facing_geometric);
                if (!(glm::dot(direction, facing_geometric) > 0.0f)) {
                    direction = facing_geometric;  // exactly tangent: leave straight up
                }
            }
            origin = offset_ray_origin(hit->position, facing_geometric);
            ++bounces;
            continue;
        }

        // Specular: follow it, and note the hop so probes notice when the object moves.
        hops.push_back({hit->position, power, -1, hit->object, bounces});
        const double xi =
            material.scattering == Scattering::Dielectric ? photon_sample(index, dim++, seed) : 0.0;
        medium.update(material, front,
                      scatter_specular(material, *hit, normals, xi, origin, direction, power));
        if (!(power.r > 0.0f || power.g > 0.0f || power.b > 0.0f)) {
            return;
        }
    }
}

}  // namespace luxel::lighting
