#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/lighting/reference/reference_scene.hpp"
#include "luxel/lighting/reference/sample_stream.hpp"
#include "luxel/runtime/jobs.hpp"

/// A dense photon estimate of the indirect component (docs/METHOD.md §10.1), the reference's
/// answer to scenes where a light sits close to a surface. Path tracing from a texel finds such
/// a hot spot only through the rare cosine samples that land in it, each with a huge weight
/// (Cornell: a point light 10 cm under the ceiling, 318 W/m^2; relative standard error 0.64 at
/// 32 spp). NEE or a direct-map lookup at the first bounce cannot help: for a point light the
/// direct irradiance at the hit is already deterministic, the variance is in where the hit lands.
/// Photons from the lights reach the hot spot in proportion to its power instead, so each
/// texel's error depends only on how many photons it receives.
namespace luxel::lighting::reference {

struct IndirectPhotonSettings {
    /// Photons per pass over all lights (chosen in proportion to their flux).
    std::uint64_t photons_per_pass = 1'000'000;
    /// Scattering events (diffuse and specular) one photon may have; Russian roulette ends
    /// paths long before (see PathSettings::max_vertices).
    std::uint32_t max_vertices = 10'000;
    std::uint32_t seed = 1;
};

struct IndirectPhotonCounters {
    std::uint64_t emitted = 0;
    std::uint64_t deposits = 0;   ///< photon arrivals binned into a texel
    std::uint64_t escaped = 0;    ///< left the scene
    std::uint64_t absorbed = 0;   ///< Russian roulette, a diffuse back face, or no power left
    std::uint64_t unmapped = 0;   ///< arrivals on a surface without a light map
    std::uint64_t truncated = 0;  ///< more than max_vertices interactions
};

/// Photons from every light (point and spot: from the position; directional: a disc over the
/// scene; area: a point by area, a cosine direction), followed through diffuse reflections
/// (Russian roulette with survival max(albedo), as PathEstimator) and specular interactions
/// (scatter_specular). Every arrival on the front of a light-mapped diffuse surface after at
/// least one diffuse reflection is binned into the texel holding the hit's light-map UV,
/// divided by the texel's world area: each texel's mean indirect irradiance over its area (a
/// texel-sized box filter), including delta-light caustics reflected onward.
///
/// Unbiased for that box-filtered irradiance. The real-time IIM samples the texel centre; the
/// difference is the texel discretisation (docs/RESULTS.md measures it). Photons are
/// pseudo-random (SampleStream keyed by photon index), so the per-photon sums of squares give
/// an honest standard error; a photon's arrivals in one texel are summed before squaring.
/// Deterministic for a seed whatever the thread count (arrivals are binned in photon order).
class IndirectPhotons {
  public:
    IndirectPhotons(const ReferenceScene& scene, IndirectPhotonSettings settings);

    void run_pass(JobSystem& jobs);
    void set_photons_per_pass(std::uint64_t photons) { settings_.photons_per_pass = photons; }

    /// Photons emitted so far (all lights).
    [[nodiscard]] std::uint64_t photons() const { return photons_; }
    [[nodiscard]] const IndirectPhotonCounters& counters() const { return counters_; }
    /// Mean indirect irradiance of a texel, W/m^2 per channel (zero before the first pass).
    [[nodiscard]] glm::dvec3 irradiance(std::size_t texel) const;
    [[nodiscard]] glm::dvec3 standard_error(std::size_t texel) const;

  private:
    struct Emitter {
        std::size_t light = 0;
        double probability = 0.0;  ///< of choosing this light for a photon
        double cumulative = 0.0;   ///< upper end of its slot in [0, 1)
        glm::dvec3 flux{0.0};      ///< W per channel (spot: before the falloff)
        /// A sky or sun with portals: their photons, as the real-time engine emits them (each
        /// looked back from before it is traced).
        std::shared_ptr<const PhotonEmitter> through_portals;
    };
    struct Deposit {
        std::uint32_t texel = 0;
        glm::dvec3 value{0.0};  ///< one photon's arrivals in the texel, W/m^2 (as the only photon)
    };
    /// Where one photon of `emitter` starts, along which direction, carrying what (W, divided
    /// by the emitter's probability), from `random`; false when it carries nothing.
    [[nodiscard]] bool start(const Emitter& emitter, SampleStream& random, glm::vec3& origin,
                             glm::vec3& direction, glm::dvec3& power) const;
    /// Traces photon `index`, appending its per-texel sums to `out`.
    void trace(std::uint64_t index, std::vector<Deposit>& out,
               IndirectPhotonCounters& counters) const;

    const ReferenceScene* scene_;
    IndirectPhotonSettings settings_;
    std::vector<Emitter> emitters_;
    std::uint64_t photons_ = 0;
    std::vector<glm::dvec3> sum_;
    std::vector<glm::dvec3> sum_squares_;
    IndirectPhotonCounters counters_;
};

}  // namespace luxel::lighting::reference
