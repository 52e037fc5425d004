#include "luxel/lighting/reference/indirect_photons.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/constants.hpp>

#include "luxel/lighting/core/photon_tracer.hpp"
#include "luxel/lighting/reference/sample_stream.hpp"

namespace luxel::lighting::reference {
namespace {

constexpr double kPi = glm::pi<double>();
/// Photons traced in parallel before their arrivals are binned in order: bounds the deposit
/// buffers at a few megabytes whatever the pass size.
constexpr std::uint64_t kChunk = 1u << 16;
constexpr std::size_t kGrain = 512;

double channel_sum(const glm::dvec3& v) {
    return v.x + v.y + v.z;
}

/// A direction at angle acos(cos_theta) from `axis`, azimuth 2 pi u.
glm::vec3 around(const glm::vec3& axis, double cos_theta, double u) {
    glm::vec3 tangent;
    glm::vec3 bitangent;
    orthonormal_basis(axis, tangent, bitangent);
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    const double phi = 2.0 * kPi * u;
    return glm::normalize(glm::vec3(glm::dvec3(tangent) * (sin_theta * std::cos(phi)) +
                                    glm::dvec3(bitangent) * (sin_theta * std::sin(phi)) +
                                    glm::dvec3(axis) * cos_theta));
}

}  // namespace

IndirectPhotons::IndirectPhotons(const ReferenceScene& scene, IndirectPhotonSettings settings)
    : scene_(&scene),
      settings_(settings),
      sum_(scene.texel_count(), glm::dvec3(0.0)),
      sum_squares_(scene.texel_count(), glm::dvec3(0.0)) {
    const auto lights = scene.lights();
    double total = 0.0;
    for (std::size_t l = 0; l < lights.size(); ++l) {
        const LightSource& source = lights[l].source;
        glm::dvec3 flux(0.0);
        switch (source.kind) {
            case LightKind::Point:
            case LightKind::Spot:
                flux = glm::dvec3(source.power);
                break;
            case LightKind::Directional: {
                const double r = scene.bounds().radius;
                flux = glm::dvec3(source.power) * (kPi * r * r);
                break;
            }
            case LightKind::Area:
                flux = glm::dvec3(source.power) * (kPi * lights[l].triangles.area());
                break;
            case LightKind::Sky: {
                const double r = scene.bounds().radius;
                flux = source.sky != nullptr
                           ? source.sky->integral() *
                                 (kPi * r * r * static_cast<double>(source.sky_scale))
                           : glm::dvec3(0.0);
                break;
            }
        }
        std::shared_ptr<const PhotonEmitter> through_portals;
        if ((source.kind == LightKind::Sky || source.kind == LightKind::Directional) &&
            !source.portals.empty()) {
            through_portals = std::make_shared<const PhotonEmitter>(source, scene.bounds());
            flux = glm::dvec3(through_portals->total_power());
        }
        if (channel_sum(flux) > 0.0 && std::isfinite(channel_sum(flux))) {
            emitters_.push_back({l, channel_sum(flux), 0.0, flux, std::move(through_portals)});
            total += channel_sum(flux);
        }
    }
    double cumulative = 0.0;
    for (Emitter& e : emitters_) {
        e.probability /= total;
        cumulative += e.probability;
        e.cumulative = cumulative;
    }
    if (!emitters_.empty()) {
        emitters_.back().cumulative = 1.0;
    }
}

bool IndirectPhotons::start(const Emitter& emitter, SampleStream& random, glm::vec3& origin,
                            glm::vec3& direction, glm::dvec3& power) const {
    const ReferenceLight& light = scene_->lights()[emitter.light];
    const LightSource& source = light.source;
    power = emitter.flux / emitter.probability;
    const glm::dvec2 d = random.next2();
    if (emitter.through_portals != nullptr) {
        // One photon of the real-time engine's own portal sampling (photon count 1: its power
        // is the flux estimate), kept only where the sky or sun is open behind it.
        const EmittedPhoton photon = emitter.through_portals->emit(d, random.next2(), 1);
        if (!(channel_sum(glm::dvec3(photon.power)) > 0.0) ||
            scene_->rays().occluded(photon.origin, -photon.direction,
                                    std::numeric_limits<float>::infinity())) {
            return false;
        }
        power = glm::dvec3(photon.power) / emitter.probability;
        origin = photon.origin;
        direction = photon.direction;
        return true;
    }
    switch (source.kind) {
        case LightKind::Point:
            origin = source.position;
            direction = around({0.0f, 0.0f, 1.0f}, 1.0 - 2.0 * d.x, d.y);
            break;
        case LightKind::Spot: {
            // Uniform over the outer cone; the falloff scales the photon (the flux above is
            // the power into the whole cone before the falloff, as the reference's intensity).
            const double cos_outer =
                std::cos(std::clamp(static_cast<double>(source.outer_cone), 1e-6, kPi));
            const double cos_theta = 1.0 - d.x * (1.0 - cos_outer);
            origin = source.position;
            direction = around(glm::normalize(source.direction), cos_theta, d.y);
            power *= spot_falloff(source, cos_theta);
            break;
        }
        case LightKind::Directional: {
            direction = glm::normalize(source.direction);
            origin = scene_disc_origin(scene_->bounds(), direction, d);
            break;
        }
        case LightKind::Area: {
            const TriangleSampler::Sample sample = light.triangles.sample(random.next2());
            if (glm::dot(sample.normal, sample.normal) <= 0.0f || !(sample.density > 0.0)) {
                return false;
            }
            // pi L / density is this point's estimate of the light's flux (the light's mean
            // radiance x pi x area when its radiance is uniform).
            power = glm::dvec3(area_radiance(source, sample.triangle, sample.piece)) *
                    (kPi / (sample.density * emitter.probability));
            direction = cosine_direction(sample.normal, d);
            origin = offset_ray_origin(sample.point, sample.normal);
            break;
        }
        case LightKind::Sky: {
            // A direction by the sky's own distribution, then a point on the scene disc
            // facing it: L pi R^2 / pdf is this photon's estimate of the sky's flux.
            const SkyRadiance::Sample from = source.sky->sample(d);
            if (!(from.pdf > 0.0)) {
                return false;
            }
            const BoundingSphere bounds = scene_->bounds();
            direction = -from.direction;
            origin = scene_disc_origin(bounds, direction, random.next2());
            const double disc =
                kPi * static_cast<double>(bounds.radius) * static_cast<double>(bounds.radius);
            power = glm::dvec3(from.radiance) * (static_cast<double>(source.sky_scale) * disc /
                                                 (from.pdf * emitter.probability));
            break;
        }
    }
    return true;
}

void IndirectPhotons::trace(std::uint64_t index, std::vector<Deposit>& out,
                            IndirectPhotonCounters& counters) const {
    ++counters.emitted;
    SampleStream random(settings_.seed, index, 0x1d1ec7);
    const double pick = random.next();
    const Emitter& emitter = *std::find_if(emitters_.begin(), emitters_.end() - 1,
                                           [&](const Emitter& e) { return pick < e.cumulative; });
    glm::vec3 origin(0.0f);
    glm::vec3 direction(0.0f, -1.0f, 0.0f);
    glm::dvec3 power(0.0);
    if (!start(emitter, random, origin, direction, power)) {
        ++counters.absorbed;
        return;
    }
    const std::size_t first = out.size();
    const RayScene& rays = scene_->rays();
    const auto materials = scene_->materials();
    bool diffuse_seen = false;
    ClosedMedium medium;
    for (std::uint32_t vertex = 0;; ++vertex) {
        if (vertex >= settings_.max_vertices) {
            ++counters.truncated;
            break;
        }
        if (!(glm::max(power.x, glm::max(power.y, power.z)) > 0.0)) {
            ++counters.absorbed;
            break;
        }
        const auto hit = rays.intersect(origin, direction);
        if (!hit) {
            ++counters.escaped;
            break;
        }
        const FacingNormals normals = facing_normals(*hit, direction);
        const TraceMaterial& material = materials[hit->material];
        if (material.scattering != Scattering::Diffuse) {
            glm::vec3 p(power);
            medium.update(
                material, normals.front,
                scatter_specular(material, *hit, normals, random.next(), origin, direction, p));
            power = glm::dvec3(p);
            continue;
        }
        if (!normals.front) {
            ++counters.absorbed;  // one-sided, as PathEstimator: the back absorbs
            break;
        }
        {
            glm::vec3 p(power);
            medium.absorb(hit->distance, p);
            power = glm::dvec3(p);
        }
        if (diffuse_seen) {
            const std::int64_t t = scene_->open_texel_at(hit->surface, hit->lightmap_uv);
            const double area = t >= 0 ? scene_->texel(static_cast<std::size_t>(t)).area : 0.0;
            if (t >= 0 && area > 0.0) {
                const auto texel = static_cast<std::uint32_t>(t);
                // A photon's arrivals in one texel are one sample: summed, not squared apart.
                auto same =
                    std::find_if(out.begin() + static_cast<std::ptrdiff_t>(first), out.end(),
                                 [&](const Deposit& x) { return x.texel == texel; });
                if (same == out.end()) {
                    out.push_back({texel, power / area});
                } else {
                    same->value += power / area;
                }
                ++counters.deposits;
            } else {
                ++counters.unmapped;
            }
        }
        diffuse_seen = true;
        const glm::dvec3 albedo(material.albedo);
        const double survival = std::min(glm::max(albedo.x, glm::max(albedo.y, albedo.z)), 1.0);
        if (!(survival > 0.0) || random.next() >= survival) {
            ++counters.absorbed;
            break;
        }
        power *= albedo / survival;
        const glm::vec3& n = normals.geometric;
        direction = cosine_direction(n, random.next2());
        origin = offset_ray_origin(hit->position, n);
    }
}

void IndirectPhotons::run_pass(JobSystem& jobs) {
    if (emitters_.empty() || settings_.photons_per_pass == 0) {
        photons_ += settings_.photons_per_pass;
        return;
    }
    std::vector<std::vector<Deposit>> deposits;
    std::vector<IndirectPhotonCounters> counters;
    const std::uint64_t total = settings_.photons_per_pass;
    for (std::uint64_t start = 0; start < total; start += kChunk) {
        const std::uint64_t count = std::min(kChunk, total - start);
        const std::size_t tasks = (count + kGrain - 1) / kGrain;
        deposits.assign(tasks, {});
        counters.assign(tasks, IndirectPhotonCounters{});
        jobs.parallel_for(0, tasks, [&](std::size_t task) {
            const std::uint64_t end = std::min<std::uint64_t>(count, (task + 1) * kGrain);
            for (std::uint64_t i = task * kGrain; i < end; ++i) {
                trace(photons_ + start + i, deposits[task], counters[task]);
            }
        });
        // Binned in task order (photon order): the sums do not depend on the thread count.
        for (std::size_t task = 0; task < tasks; ++task) {
            for (const Deposit& deposit : deposits[task]) {
                sum_[deposit.texel] += deposit.value;
                sum_squares_[deposit.texel] += deposit.value * deposit.value;
            }
            const IndirectPhotonCounters& c = counters[task];
            counters_.emitted += c.emitted;
            counters_.deposits += c.deposits;
            counters_.escaped += c.escaped;
            counters_.absorbed += c.absorbed;
            counters_.unmapped += c.unmapped;
            counters_.truncated += c.truncated;
        }
    }
    photons_ += total;
}

glm::dvec3 IndirectPhotons::irradiance(std::size_t texel) const {
    if (photons_ == 0 || texel >= sum_.size()) {
        return glm::dvec3(0.0);
    }
    return sum_[texel] / static_cast<double>(photons_);
}

glm::dvec3 IndirectPhotons::standard_error(std::size_t texel) const {
    if (photons_ < 2 || texel >= sum_.size()) {
        return glm::dvec3(0.0);
    }
    // Every photon is one sample (zero for the texels it misses).
    const double n = static_cast<double>(photons_);
    const glm::dvec3 mean = sum_[texel] / n;
    const glm::dvec3 variance =
        glm::max(sum_squares_[texel] / n - mean * mean, glm::dvec3(0.0)) * (n / (n - 1.0));
    return glm::sqrt(variance / n);
}

}  // namespace luxel::lighting::reference
