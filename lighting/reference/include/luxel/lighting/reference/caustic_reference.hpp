#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/lighting/reference/caustic_disc_emitter.hpp"
#include "luxel/lighting/reference/caustic_footprints.hpp"
#include "luxel/lighting/reference/reference_scene.hpp"
#include "luxel/runtime/jobs.hpp"

/// The dense photon estimate of caustics from point, spot and directional lights (docs/METHOD.md
/// §10.1): paths from a surface cannot reach a delta light through glass or a mirror, so the
/// reference shoots photons from the lights instead and bins them at texel resolution.
namespace luxel::lighting::reference {

struct CausticReferenceSettings {
    /// Photons per pass over all (delta light, specular object) pairs, split evenly between
    /// them. Tests use 1e6 in all; a reference worth judging a method by wants 1e8 or more
    /// (docs/METHOD.md §10.1), run over as many passes as it takes.
    std::uint64_t photons_per_pass = 1'000'000;
    /// A photon still bouncing between specular surfaces after this many interactions is
    /// dropped (counted as truncated).
    std::uint32_t max_specular = 64;
    std::uint32_t seed = 1;
};

struct CausticReferenceCounters {
    std::uint64_t emitted = 0;    ///< photon samples, all pairs
    std::uint64_t stored = 0;     ///< binned into a texel
    std::uint64_t direct = 0;     ///< first hit diffuse: not a caustic, not stored
    std::uint64_t escaped = 0;    ///< left the scene
    std::uint64_t absorbed = 0;   ///< diffuse back face, or no power left
    std::uint64_t unmapped = 0;   ///< a caustic on a surface without a light map
    std::uint64_t truncated = 0;  ///< more than max_specular interactions
};

/// Photons from each delta light toward every specular object's bounding sphere (the
/// reference's own CausticDiscEmitter, not the real-time CausticEmitter: through the disc
/// facing the light, or a beam over it), followed through mirrors and dielectrics with
/// scatter_specular, and binned at
/// their first diffuse hit after at least one specular one into the texel holding the hit's
/// light-map UV, divided by the texel's world area. The result is each texel's mean caustic
/// irradiance over its area (a box filter the size of a texel).
///
/// Where the cones toward two spheres overlap, a photon direction is counted by every pair
/// whose cone holds it; each photon is weighted by 1 / (how many of its light's spheres its
/// first ray crosses), which keeps the sum unbiased. Photon samples are the Halton points of
/// photon_sample (dimensions 0-3 for emission, 4 on for Fresnel choices), continuing from
/// pass to pass, so the estimate is deterministic for a seed and independent of threads.
class CausticReference {
  public:
    CausticReference(const ReferenceScene& scene, CausticReferenceSettings settings);

    /// Emits, traces and bins one pass of photons (parallel tracing, binning in photon order).
    void run_pass(JobSystem& jobs);
    /// The size of the passes to come.
    void set_photons_per_pass(std::uint64_t photons) { settings_.photons_per_pass = photons; }

    /// (light, sphere) pairs that can carry power; no pair: no caustic from delta lights.
    [[nodiscard]] std::size_t pair_count() const { return pairs_.size(); }
    /// Photons emitted per pair so far.
    [[nodiscard]] std::uint64_t photons_per_pair() const { return per_pair_; }
    [[nodiscard]] const CausticReferenceCounters& counters() const { return counters_; }

    /// Mean caustic irradiance of a texel (W/m^2 per channel), zero before the first pass.
    [[nodiscard]] glm::dvec3 irradiance(std::size_t texel) const;
    /// Standard error of irradiance(texel), treating the photons as independent samples of a
    /// light-and-pair choice: an upper bound for the stratified, quasi-random photons used.
    [[nodiscard]] glm::dvec3 standard_error(std::size_t texel) const;
    /// irradiance() of every texel, in global texel order.
    [[nodiscard]] std::vector<glm::dvec3> irradiance_all() const;
    /// Total power binned so far, W per channel (the sum over texels of E * area).
    [[nodiscard]] glm::dvec3 stored_power() const;

    /// Also collects every caustic photon into the footprints that hold it (pixel resolution:
    /// CausticFootprints), from the next pass on; call before the first pass, or the passes
    /// before it are missing from them. Photons on surfaces without a light map count there too.
    void set_footprints(std::vector<CausticFootprint> footprints);
    [[nodiscard]] std::size_t footprint_count() const {
        return footprints_ ? footprints_->size() : 0;
    }
    /// Mean caustic irradiance over footprint i (W/m^2 per channel), and its standard error
    /// (as standard_error's); zero before the first pass.
    [[nodiscard]] glm::dvec3 footprint_irradiance(std::size_t i) const;
    [[nodiscard]] glm::dvec3 footprint_standard_error(std::size_t i) const;

  private:
    struct Pair {
        std::uint32_t light = 0;
        std::uint32_t sphere = 0;
        std::uint32_t seed = 0;
        CausticDiscEmitter emitter;
    };
    struct Deposit {
        bool stored = false;  ///< a caustic photon at its first diffuse hit
        std::int64_t texel = -1;
        glm::dvec3 value{0.0};  ///< photon power (as the only photon) / texel area
        glm::dvec3 flux{0.0};   ///< photon power (as the only photon)
        glm::vec3 position{0.0f};
        glm::vec3 normal{0.0f};  ///< the surface's, facing the photon
    };
    /// Traces one photon of `pair`; fills `deposit` when it makes a caustic.
    void trace(const Pair& pair, std::uint64_t index, Deposit& deposit,
               CausticReferenceCounters& counters) const;

    const ReferenceScene* scene_;
    CausticReferenceSettings settings_;
    std::vector<Pair> pairs_;
    std::uint64_t per_pair_ = 0;
    std::vector<glm::dvec3> sum_;          ///< per texel: sum of deposits
    std::vector<glm::dvec3> sum_squares_;  ///< per texel: sum of squared deposits
    std::optional<CausticFootprints> footprints_;
    CausticReferenceCounters counters_;
};

}  // namespace luxel::lighting::reference
