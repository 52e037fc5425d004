#include "luxel/lighting/reference/reference_integrator.hpp"

#include <algorithm>
#include <cmath>

#include "luxel/lighting/core/gather.hpp"

namespace luxel::lighting::reference {
namespace {

glm::dvec3 sample_standard_error(const glm::dvec3& sum, const glm::dvec3& sum_squares,
                                 std::uint64_t count) {
    if (count < 2) {
        return glm::dvec3(0.0);
    }
    const double n = static_cast<double>(count);
    const glm::dvec3 mean = sum / n;
    // Unbiased sample variance, then the variance of the mean.
    const glm::dvec3 variance =
        glm::max(sum_squares / n - mean * mean, glm::dvec3(0.0)) * (n / (n - 1.0));
    return glm::sqrt(variance / n);
}

}  // namespace

ReferenceIntegrator::ReferenceIntegrator(const ReferenceScene& scene, ReferenceSettings settings)
    : scene_(&scene),
      settings_(settings),
      caustics_(scene, settings.caustics),
      indirect_(scene, settings.indirect_photons),
      moments_(scene.texel_count() * kComponentCount) {
    if (settings_.indirect == IndirectMethod::Photons) {
        settings_.paths.indirect = false;
    }
}

std::uint64_t ReferenceIntegrator::bytes_per_texel() {
    // One node of the scene's std::unordered_map<int64_t, uint32_t> page lookup as malloc
    // rounds it (next pointer, key, value: 24 bytes to 32) and its bucket pointer.
    constexpr std::uint64_t kLookupEntry = 32 + sizeof(void*);
    // ReferenceScene::from_world reads each surface's texels from GatherTexels.
    constexpr std::uint64_t kScene = sizeof(ReferenceTexel) + sizeof(GatherTexel) + kLookupEntry;
    // CausticReference and IndirectPhotons: a sum and a sum of squares each.
    constexpr std::uint64_t kPhotons = 2 * 2 * sizeof(glm::dvec3);
    // A pass's copy of the caustic field, and the irradiance (or areas) the output reads.
    constexpr std::uint64_t kTemporaries = 2 * sizeof(glm::dvec3);
    return kScene + kComponentCount * sizeof(Moments) + kPhotons + kTemporaries;
}

void ReferenceIntegrator::run_pass(JobSystem& jobs) {
    caustics_.run_pass(jobs);
    if (settings_.indirect == IndirectMethod::Photons) {
        indirect_.run_pass(jobs);
    }
    const std::vector<glm::dvec3> caustic_field = caustics_.irradiance_all();
    const PathEstimator estimator(*scene_, settings_.paths, caustic_field);
    const std::size_t texels = scene_->texel_count();
    const std::uint32_t per_pass = settings_.samples_per_pass;
    const std::uint64_t first_sample = samples_;
    // Counters per grain of texels, merged in order afterwards.
    constexpr std::size_t kGrain = 16;
    std::vector<PathCounters> counters((texels + kGrain - 1) / kGrain);
    jobs.parallel_for(0, counters.size(), [&](std::size_t task) {
        const std::size_t end = std::min(texels, (task + 1) * kGrain);
        for (std::size_t t = task * kGrain; t < end; ++t) {
            const ReferenceTexel& texel = scene_->texel(t);
            for (std::uint32_t s = 0; s < per_pass; ++s) {
                SampleStream random(settings_.seed, t, first_sample + s);
                const Components sample = estimator.irradiance(texel, random, counters[task]);
                for (std::size_t c = 0; c < kComponentCount; ++c) {
                    Moments& m = moments_[t * kComponentCount + c];
                    m.sum += sample.value[c];
                    m.sum_squares += sample.value[c] * sample.value[c];
                }
            }
        }
    });
    for (const PathCounters& c : counters) {
        counters_.rays += c.rays;
        counters_.truncated += c.truncated;
        counters_.non_finite += c.non_finite;
    }
    samples_ += per_pass;
    ++passes_;
}

void ReferenceIntegrator::set_pass_size(std::uint32_t samples_per_pass,
                                        std::uint64_t caustic_photons_per_pass) {
    settings_.samples_per_pass = samples_per_pass;
    settings_.caustics.photons_per_pass = caustic_photons_per_pass;
    caustics_.set_photons_per_pass(caustic_photons_per_pass);
}

void ReferenceIntegrator::set_indirect_photons_per_pass(std::uint64_t photons) {
    settings_.indirect_photons.photons_per_pass = photons;
    indirect_.set_photons_per_pass(photons);
}

glm::dvec3 ReferenceIntegrator::irradiance(Component component, std::size_t texel) const {
    if (texel >= scene_->texel_count()) {
        return glm::dvec3(0.0);
    }
    glm::dvec3 mean = samples_ > 0 ? moments(component, texel).sum / static_cast<double>(samples_)
                                   : glm::dvec3(0.0);
    if (component == Component::Caustic) {
        mean += caustics_.irradiance(texel);
    }
    if (component == Component::Indirect && settings_.indirect == IndirectMethod::Photons) {
        mean += indirect_.irradiance(texel);
    }
    return mean;
}

glm::dvec3 ReferenceIntegrator::total(std::size_t texel) const {
    return irradiance(Component::Direct, texel) + irradiance(Component::Indirect, texel) +
           irradiance(Component::Caustic, texel);
}

glm::dvec3 ReferenceIntegrator::standard_error(Component component, std::size_t texel) const {
    if (texel >= scene_->texel_count()) {
        return glm::dvec3(0.0);
    }
    const Moments& m = moments(component, texel);
    glm::dvec3 error = sample_standard_error(m.sum, m.sum_squares, samples_);
    if (component == Component::Caustic) {
        const glm::dvec3 photons = caustics_.standard_error(texel);
        error = glm::sqrt(error * error + photons * photons);
    }
    if (component == Component::Indirect && settings_.indirect == IndirectMethod::Photons) {
        const glm::dvec3 photons = indirect_.standard_error(texel);
        error = glm::sqrt(error * error + photons * photons);
    }
    return error;
}

glm::dvec3 ReferenceIntegrator::total_standard_error(std::size_t texel) const {
    glm::dvec3 variance(0.0);
    for (std::size_t c = 0; c < kComponentCount; ++c) {
        const glm::dvec3 e = standard_error(static_cast<Component>(c), texel);
        variance += e * e;
    }
    return glm::sqrt(variance);
}

std::vector<glm::dvec3> ReferenceIntegrator::irradiance(Component component) const {
    std::vector<glm::dvec3> all(scene_->texel_count());
    for (std::size_t t = 0; t < all.size(); ++t) {
        all[t] = irradiance(component, t);
    }
    return all;
}

double ReferenceIntegrator::relative_standard_error(Component component) const {
    double error = 0.0;
    double signal = 0.0;
    for (std::size_t t = 0; t < scene_->texel_count(); ++t) {
        const double area = scene_->texel(t).area;
        const glm::dvec3 se = standard_error(component, t);
        const glm::dvec3 mean = irradiance(component, t);
        error += area * glm::dot(se, se);
        signal += area * glm::dot(mean, mean);
    }
    return signal > 0.0 ? std::sqrt(error / signal) : 0.0;
}

}  // namespace luxel::lighting::reference
