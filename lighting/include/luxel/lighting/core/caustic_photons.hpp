#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/lighting/core/caustic_emitter.hpp"
#include "luxel/lighting/core/photon_tracer.hpp"
#include "luxel/lighting/core/ray_scene.hpp"
#include "luxel/runtime/jobs.hpp"

/// Caustic photons (docs/METHOD.md §7.1-7.2): per (generator, light) pair, QMC
/// photons emitted toward the generator, followed through specular reflection and refraction,
/// and stored at their first diffuse hit when at least one specular interaction came before it
/// (L S+ D paths). Photons whose first hit is diffuse are dropped: that light is the global
/// photons' job. The list is kept in K slices retraced one per frame while anything moves.
namespace luxel::lighting {

/// One caustic photon at its first diffuse hit: 32 bytes, position and power first so that
/// the splat pass can read them as they are.
struct CausticPhoton {
    glm::vec3 position{0.0f};
    /// The light-mapped surface hit; -1 on a diffuse object without a light map (a moving
    /// object), where the photon is still splatted.
    std::int32_t surface = -1;
    glm::vec3 power{0.0f};  ///< watts per channel
    /// The photon's travel direction on arrival (pointing into the surface), octahedral-encoded
    /// in two 16-bit fixed-point numbers (error below 1e-4 rad).
    std::uint32_t direction_bits = 0;

    [[nodiscard]] glm::vec3 incident_direction() const;
};
static_assert(sizeof(CausticPhoton) == 32, "caustic photons are 32 bytes");

/// Octahedral encoding of a unit vector into 32 bits, and back (the result is unit length).
[[nodiscard]] std::uint32_t encode_direction(const glm::vec3& unit);
[[nodiscard]] glm::vec3 decode_direction(std::uint32_t bits);

struct CausticSettings {
    /// Photons per (generator, light) pair; the paper's 10,000 for its one glass sphere and one
    /// light. A scene with G generators and L lights keeps G * L lists of this many.
    std::uint32_t photons_per_pair = 10'000;
    /// K: a list is retraced over K frames, one slice per frame (the paper: 8).
    std::uint32_t slices = 8;
    /// A photon still bouncing between specular surfaces after this many interactions is
    /// dropped (counted as truncated): light trapped in glass by total internal reflection.
    std::uint32_t max_specular_interactions = 16;
};

/// Counters of caustic tracing.
struct CausticTraceCounters {
    std::uint64_t photons = 0;         ///< photon samples processed
    std::uint64_t traced = 0;          ///< of those, emitted with power (and shot)
    std::uint64_t segments = 0;        ///< rays shot
    std::uint64_t stored = 0;          ///< reached a diffuse surface after >= 1 specular hit
    std::uint64_t direct_diffuse = 0;  ///< first hit diffuse: dropped
    std::uint64_t escaped = 0;         ///< left the scene
    std::uint64_t absorbed = 0;        ///< diffuse back face, or no power left
    std::uint64_t truncated = 0;       ///< more specular interactions than the limit

    CausticTraceCounters& operator+=(const CausticTraceCounters& other);
};

/// Traces one caustic photon. Specular interactions as the global tracer: mirrors reflect with
/// Schlick's conductor Fresnel of their tint; dielectrics choose reflection with probability
/// F (unpolarised Fresnel, from sample dimensions 4 on, `seed` rotated) and refraction
/// otherwise, with total internal reflection where Snell has no solution. Power is never split:
/// one photon, at most one stored hit. No Beer absorption: no luxel material has an absorption
/// coefficient (TraceMaterial's tint scales a refracted photon once, at the interface).
[[nodiscard]] std::optional<CausticPhoton> trace_caustic_photon(
    const RayScene& scene, std::span<const TraceMaterial> materials, const EmittedPhoton& photon,
    std::uint64_t sample_index, std::uint32_t seed, std::uint32_t max_specular_interactions,
    CausticTraceCounters& counters);

/// The caustic photons of one (generator, light) pair: photon_count photons in K slices.
///
/// Slice k holds the photons j (0 <= j < photon_count) with j mod K = k. Photon j uses the
/// Halton point of index 1 + k * ceil(N / K) + j / K, so each slice is a contiguous run of the
/// Halton sequence and covers the whole emission cone on its own (with the plain index j, the
/// base-2 digits of j mod 8 would confine each slice to one eighth of the cone's cos theta).
///
/// Retracing is driven by dirty slices: invalidate() marks all K (something moved), and each
/// frame slice_for_frame() names the slice to retrace: frame mod K if dirty, else the next dirty
/// one. While things keep moving every slice is retraced exactly once per K frames; when
/// nothing moves nothing is traced.
class CausticPhotonList {
  public:
    CausticPhotonList(std::uint32_t photon_count, std::uint32_t slices, std::uint32_t seed);

    /// Replaces the emission (the light or the generator moved or changed) and marks every
    /// slice for retrace.
    void set_emitter(CausticEmitter emitter);
    [[nodiscard]] const CausticEmitter& emitter() const { return emitter_; }
    /// Marks every slice for retrace (the receivers moved).
    void invalidate();

    [[nodiscard]] bool needs_retrace() const { return dirty_count_ > 0; }
    [[nodiscard]] bool slice_dirty(std::uint32_t slice) const { return dirty_.at(slice) != 0; }
    /// The slice to retrace in `frame`, or nullopt when the list is current.
    [[nodiscard]] std::optional<std::uint32_t> slice_for_frame(std::uint64_t frame) const;

    /// Retraces one slice in parallel and replaces its photons.
    CausticTraceCounters retrace_slice(const RayScene& scene,
                                       std::span<const TraceMaterial> materials,
                                       std::uint32_t slice, std::uint32_t max_specular_interactions,
                                       JobSystem& jobs);

    /// One slice of several lists, for retracing them together.
    struct SliceWork {
        CausticPhotonList* list = nullptr;
        std::uint32_t slice = 0;
    };
    /// Retraces every given slice in one parallel pass and replaces their photons. The
    /// photons are traced into per-photon slots in fixed chunks and compacted in photon order,
    /// so the result does not depend on the thread count.
    static CausticTraceCounters retrace(const RayScene& scene,
                                        std::span<const TraceMaterial> materials,
                                        std::span<const SliceWork> work,
                                        std::uint32_t max_specular_interactions, JobSystem& jobs);

    [[nodiscard]] std::uint32_t photon_count() const { return photon_count_; }
    [[nodiscard]] std::uint32_t slice_count() const {
        return static_cast<std::uint32_t>(slices_.size());
    }
    /// Photons of slice k: ceil((N - k) / K) of them.
    [[nodiscard]] std::uint32_t slice_size(std::uint32_t slice) const;
    /// The Halton index of photon j (see the class comment).
    [[nodiscard]] std::uint64_t sample_index(std::uint32_t photon) const;
    [[nodiscard]] std::uint32_t seed() const { return seed_; }

    /// The stored photons of one slice, in photon order.
    [[nodiscard]] std::span<const CausticPhoton> slice(std::uint32_t k) const {
        return slices_.at(k);
    }
    /// How many times slice k has been retraced: a renderer re-uploads the slices whose count
    /// changed, and tests check the schedule with it.
    [[nodiscard]] std::uint64_t slice_retraces(std::uint32_t k) const {
        return slice_retraces_.at(k);
    }
    [[nodiscard]] std::size_t stored_count() const;
    /// Sum of the stored photons' power per channel.
    [[nodiscard]] glm::dvec3 stored_power() const;
    /// Bytes held: photon capacity plus the per-slice bookkeeping.
    [[nodiscard]] std::size_t bytes_used() const;

  private:
    void store_slice(std::uint32_t slice, std::span<const std::optional<CausticPhoton>> traced);

    CausticEmitter emitter_;
    std::uint32_t photon_count_;
    std::uint32_t seed_;
    std::uint32_t slice_stride_;  ///< ceil(N / K): Halton indices per slice
    std::vector<std::vector<CausticPhoton>> slices_;
    std::vector<std::uint8_t> dirty_;
    std::vector<std::uint64_t> slice_retraces_;
    std::uint32_t dirty_count_ = 0;
};

}  // namespace luxel::lighting
