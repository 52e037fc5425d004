#include "luxel/lighting/reference/caustic_reference.hpp"

#include <algorithm>
#include <cmath>

#include "luxel/lighting/core/photon_tracer.hpp"
#include "luxel/lighting/reference/caustic_disc_emitter.hpp"
#include "luxel/lighting/reference/sample_stream.hpp"

namespace luxel::lighting::reference {
namespace {

/// Photons traced in parallel per chunk before they are binned in order: bounds the deposit
/// buffer (32 bytes a photon) at a few megabytes whatever the pass size.
constexpr std::uint64_t kChunk = 1u << 16;

bool ray_crosses(const glm::vec3& origin, const glm::vec3& direction, const BoundingSphere& s) {
    const glm::dvec3 to_centre = glm::dvec3(s.centre) - glm::dvec3(origin);
    const double r2 = static_cast<double>(s.radius) * static_cast<double>(s.radius);
    const double along = glm::dot(to_centre, glm::dvec3(direction));
    const double distance2 = glm::dot(to_centre, to_centre);
    if (distance2 <= r2) {
        return true;  // starts inside
    }
    return along > 0.0 && distance2 - along * along <= r2;
}

}  // namespace

CausticReference::CausticReference(const ReferenceScene& scene, CausticReferenceSettings settings)
    : scene_(&scene),
      settings_(settings),
      sum_(scene.texel_count(), glm::dvec3(0.0)),
      sum_squares_(scene.texel_count(), glm::dvec3(0.0)) {
    const auto lights = scene.lights();
    const auto spheres = scene.generator_spheres();
    for (std::uint32_t l = 0; l < lights.size(); ++l) {
        if (!lights[l].is_delta()) {
            continue;  // area-light caustics are path traced (PathEstimator)
        }
        for (std::uint32_t s = 0; s < spheres.size(); ++s) {
            CausticDiscEmitter emitter(lights[l], spheres[s], scene.bounds());
            if (!emitter.reaches_generator()) {
                continue;
            }
            const auto seed = static_cast<std::uint32_t>(
                mix64((static_cast<std::uint64_t>(settings.seed) << 32) ^ (l * 65537u + s)));
            pairs_.push_back({l, s, seed, emitter});
        }
    }
}

void CausticReference::trace(const Pair& pair, std::uint64_t index, Deposit& deposit,
                             CausticReferenceCounters& counters) const {
    ++counters.emitted;
    const std::uint64_t halton = index + 1;  // index 0 is the origin of every dimension
    const glm::dvec2 d(photon_sample(halton, 0, pair.seed), photon_sample(halton, 1, pair.seed));
    EmittedPhoton photon = pair.emitter.emit(d, 1.0);
    if (!(glm::max(photon.power.x, glm::max(photon.power.y, photon.power.z)) > 0.0f)) {
        ++counters.absorbed;
        return;
    }
    // Overlapping cones: every pair of this light whose sphere the first ray crosses samples
    // this direction too.
    std::uint32_t sharing = 0;
    const auto spheres = scene_->generator_spheres();
    for (const Pair& other : pairs_) {
        if (other.light == pair.light &&
            ray_crosses(photon.origin, photon.direction, spheres[other.sphere])) {
            ++sharing;
        }
    }
    glm::dvec3 weight(1.0 / static_cast<double>(std::max<std::uint32_t>(sharing, 1)));
    const RayScene& rays = scene_->rays();
    const auto materials = scene_->materials();
    glm::vec3 origin = photon.origin;
    glm::vec3 direction = photon.direction;
    glm::vec3 power = photon.power;
    ClosedMedium medium;
    for (std::uint32_t bounce = 0;; ++bounce) {
        if (bounce > settings_.max_specular) {
            ++counters.truncated;
            return;
        }
        const auto hit = rays.intersect(origin, direction);
        if (!hit) {
            ++counters.escaped;
            return;
        }
        const FacingNormals normals = facing_normals(*hit, direction);
        const TraceMaterial& material = materials[hit->material];
        if (material.scattering == Scattering::Diffuse) {
            if (bounce == 0) {
                ++counters.direct;
                return;
            }
            if (!normals.front) {
                ++counters.absorbed;
                return;
            }
            deposit.stored = true;
            medium.absorb(hit->distance, power);
            deposit.flux = glm::dvec3(power) * weight;
            deposit.position = hit->position;
            deposit.normal = normals.geometric;
            const std::int64_t texel = scene_->open_texel_at(hit->surface, hit->lightmap_uv);
            const double area =
                texel >= 0 ? scene_->texel(static_cast<std::size_t>(texel)).area : 0.0;
            if (texel < 0 || !(area > 0.0)) {
                ++counters.unmapped;
                return;
            }
            deposit.texel = texel;
            deposit.value = deposit.flux / area;
            ++counters.stored;
            return;
        }
        medium.update(
            material, normals.front,
            scatter_specular(material, *hit, normals, photon_sample(halton, 4 + bounce, pair.seed),
                             origin, direction, power));
        if (!(glm::max(power.x, glm::max(power.y, power.z)) > 0.0f)) {
            ++counters.absorbed;
            return;
        }
    }
}

void CausticReference::run_pass(JobSystem& jobs) {
    if (pairs_.empty() || settings_.photons_per_pass == 0) {
        return;
    }
    const std::uint64_t per_pair = (settings_.photons_per_pass + pairs_.size() - 1) / pairs_.size();
    std::vector<Deposit> deposits;
    std::vector<CausticReferenceCounters> chunk_counters;
    for (std::size_t p = 0; p < pairs_.size(); ++p) {
        for (std::uint64_t start = 0; start < per_pair; start += kChunk) {
            const std::uint64_t count = std::min(kChunk, per_pair - start);
            deposits.assign(count, Deposit{});
            // Per-task counters, merged afterwards: sums of integers do not depend on order.
            constexpr std::size_t kGrain = 256;
            const std::size_t tasks = (count + kGrain - 1) / kGrain;
            chunk_counters.assign(tasks, CausticReferenceCounters{});
            jobs.parallel_for(0, tasks, [&](std::size_t task) {
                const std::size_t end = std::min<std::size_t>(count, (task + 1) * kGrain);
                for (std::size_t i = task * kGrain; i < end; ++i) {
                    trace(pairs_[p], per_pair_ + start + i, deposits[i], chunk_counters[task]);
                }
            });
            for (const CausticReferenceCounters& c : chunk_counters) {
                counters_.emitted += c.emitted;
                counters_.stored += c.stored;
                counters_.direct += c.direct;
                counters_.escaped += c.escaped;
                counters_.absorbed += c.absorbed;
                counters_.unmapped += c.unmapped;
                counters_.truncated += c.truncated;
            }
            // Binned in photon order: the sums are the same for any thread count.
            for (const Deposit& deposit : deposits) {
                if (deposit.stored && footprints_) {
                    footprints_->add(deposit.position, deposit.normal, deposit.flux);
                }
                if (deposit.texel >= 0) {
                    const auto t = static_cast<std::size_t>(deposit.texel);
                    sum_[t] += deposit.value;
                    sum_squares_[t] += deposit.value * deposit.value;
                }
            }
        }
    }
    per_pair_ += per_pair;
}

glm::dvec3 CausticReference::irradiance(std::size_t texel) const {
    if (per_pair_ == 0 || texel >= sum_.size()) {
        return glm::dvec3(0.0);
    }
    return sum_[texel] / static_cast<double>(per_pair_);
}

glm::dvec3 CausticReference::standard_error(std::size_t texel) const {
    if (per_pair_ == 0 || texel >= sum_.size()) {
        return glm::dvec3(0.0);
    }
    // One virtual sample = a pair chosen uniformly (probability 1 / P) and one of its photons:
    // X = P * deposit, M = P * N samples, E = sum / N, E[X^2] = P * sum_squares / N.
    const double pairs = static_cast<double>(pairs_.size());
    const double n = static_cast<double>(per_pair_);
    const glm::dvec3 mean = sum_[texel] / n;
    const glm::dvec3 second = pairs * sum_squares_[texel] / n;
    const glm::dvec3 variance = glm::max(second - mean * mean, glm::dvec3(0.0)) / (pairs * n);
    return glm::sqrt(variance);
}

std::vector<glm::dvec3> CausticReference::irradiance_all() const {
    std::vector<glm::dvec3> all(sum_.size());
    for (std::size_t t = 0; t < all.size(); ++t) {
        all[t] = irradiance(t);
    }
    return all;
}

glm::dvec3 CausticReference::stored_power() const {
    glm::dvec3 power(0.0);
    for (std::size_t t = 0; t < sum_.size(); ++t) {
        power += irradiance(t) * scene_->texel(t).area;
    }
    return power;
}

void CausticReference::set_footprints(std::vector<CausticFootprint> footprints) {
    footprints_.emplace(std::move(footprints));
}

glm::dvec3 CausticReference::footprint_irradiance(std::size_t i) const {
    if (!footprints_ || per_pair_ == 0 || i >= footprints_->size()) {
        return glm::dvec3(0.0);
    }
    return footprints_->flux(i) / (static_cast<double>(per_pair_) * footprints_->area(i));
}

glm::dvec3 CausticReference::footprint_standard_error(std::size_t i) const {
    if (!footprints_ || per_pair_ == 0 || i >= footprints_->size()) {
        return glm::dvec3(0.0);
    }
    // As standard_error, with the disc's area in place of the texel's.
    const double pairs = static_cast<double>(pairs_.size());
    const double n = static_cast<double>(per_pair_);
    const double area = footprints_->area(i);
    const glm::dvec3 mean = footprints_->flux(i) / (n * area);
    const glm::dvec3 second = pairs * footprints_->flux_squares(i) / (n * area * area);
    const glm::dvec3 variance = glm::max(second - mean * mean, glm::dvec3(0.0)) / (pairs * n);
    return glm::sqrt(variance);
}

}  // namespace luxel::lighting::reference
