#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/lighting/reference/caustic_reference.hpp"
#include "luxel/lighting/reference/indirect_photons.hpp"
#include "luxel/lighting/reference/path_estimator.hpp"
#include "luxel/lighting/reference/reference_scene.hpp"
#include "luxel/runtime/jobs.hpp"

/// The reference light maps (docs/METHOD.md §10.1): per-texel irradiance of every light-mapped
/// surface, split into direct, indirect and caustic, with its own standard error.
namespace luxel::lighting::reference {

/// How the indirect component is estimated. Paths: from each texel, NEE at every diffuse
/// vertex (slow where a light sits close to a surface: its hot spot is found only by rare
/// samples). Photons: IndirectPhotons, a texel-binned photon estimate (each texel's mean over
/// its area), whose error does not depend on where the light is.
enum class IndirectMethod : std::uint8_t { Paths, Photons };

struct ReferenceSettings {
    /// Path samples per texel and pass (each: NEE at the texel plus one path).
    std::uint32_t samples_per_pass = 16;
    CausticReferenceSettings caustics;
    PathSettings paths;
    IndirectMethod indirect = IndirectMethod::Paths;
    /// Photons: the photons per pass (paths.indirect is turned off).
    IndirectPhotonSettings indirect_photons;
    std::uint32_t seed = 1;  ///< the path samples' seed (caustics.seed is the photons')
};

/// Progressive: each run_pass() first bins a pass of caustic photons (CausticReference), then
/// takes samples_per_pass path samples at every texel (PathEstimator) in parallel. Per texel
/// and component it keeps the sum and the sum of squares of the samples, so the mean and its
/// standard error are known after any pass. Deterministic for (seed, caustics.seed): each
/// texel's samples come from its own SampleStream, and photons are binned in order.
///
/// The caustic component is the photon estimate (point, spot, directional lights) plus the
/// path-traced caustics of area lights. The indirect component's paths read the caustic
/// estimate of the pass at diffuse vertices (light from a caustic reflected onward); its
/// standard error does not include that estimate's noise.
class ReferenceIntegrator {
  public:
    ReferenceIntegrator(const ReferenceScene& scene, ReferenceSettings settings);
    /// Bytes the reference keeps per light-map texel, at its peak: the scene's texel and its
    /// lookup entry, this integrator's moments, the caustic and indirect photon sums, and the
    /// per-texel arrays a pass and the output make. Times ReferenceScene::count_texels(), what
    /// a tool checks against its limit before it builds the scene.
    [[nodiscard]] static std::uint64_t bytes_per_texel();

    void run_pass(JobSystem& jobs);
    /// Changes the size of the passes to come (a tool spreading a total over passes); 0
    /// samples runs only the caustic photons.
    void set_pass_size(std::uint32_t samples_per_pass, std::uint64_t caustic_photons_per_pass);
    /// IndirectMethod::Photons: the indirect photons of the passes to come.
    void set_indirect_photons_per_pass(std::uint64_t photons);

    [[nodiscard]] std::uint32_t passes() const { return passes_; }
    /// Path samples per texel so far.
    [[nodiscard]] std::uint64_t samples() const { return samples_; }
    [[nodiscard]] const ReferenceScene& scene() const { return *scene_; }
    [[nodiscard]] const CausticReference& caustics() const { return caustics_; }
    /// CausticReference::set_footprints: the caustic photons also at pixel resolution.
    void set_caustic_footprints(std::vector<CausticFootprint> footprints) {
        caustics_.set_footprints(std::move(footprints));
    }
    [[nodiscard]] const IndirectPhotons& indirect_photons() const { return indirect_; }
    [[nodiscard]] const ReferenceSettings& settings() const { return settings_; }
    [[nodiscard]] const PathCounters& path_counters() const { return counters_; }

    /// Mean irradiance of a component at a texel (global index), W/m^2 per channel.
    [[nodiscard]] glm::dvec3 irradiance(Component component, std::size_t texel) const;
    /// The sum of the three components.
    [[nodiscard]] glm::dvec3 total(std::size_t texel) const;
    /// Standard error of irradiance(component, texel).
    [[nodiscard]] glm::dvec3 standard_error(Component component, std::size_t texel) const;
    /// Standard error of total(texel) (the components' errors added in quadrature: their
    /// samples are drawn independently per component only approximately, see the class note).
    [[nodiscard]] glm::dvec3 total_standard_error(std::size_t texel) const;
    /// irradiance() of every texel in global order.
    [[nodiscard]] std::vector<glm::dvec3> irradiance(Component component) const;
    /// The reference's own expected relRMSE for a component: sqrt(sum_t A_t se_t^2 /
    /// sum_t A_t E_t^2) over texels and channels, the same weighting as docs/METHOD.md §10.2's
    /// error, so a reference is converged enough to judge an error e when this is below e / 10.
    /// 0 when the component is zero everywhere.
    [[nodiscard]] double relative_standard_error(Component component) const;

  private:
    struct Moments {
        glm::dvec3 sum{0.0};
        glm::dvec3 sum_squares{0.0};
    };
    [[nodiscard]] const Moments& moments(Component component, std::size_t texel) const {
        return moments_[texel * kComponentCount + static_cast<std::size_t>(component)];
    }

    const ReferenceScene* scene_;
    ReferenceSettings settings_;
    CausticReference caustics_;
    IndirectPhotons indirect_;
    std::vector<Moments> moments_;  ///< texel-major, kComponentCount per texel
    std::uint32_t passes_ = 0;
    std::uint64_t samples_ = 0;
    PathCounters counters_;
};

}  // namespace luxel::lighting::reference
