#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/lighting/core/caustic_emitter.hpp"
#include "luxel/lighting/core/path_cells.hpp"
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
    /// object), where the photon is still splatted. 24 bits (kMaxCausticSurface): the other
    /// 8 of the word hold the footprint. Both share one 32-bit word the shaders split with
    /// bitfieldExtract (shaders/caustics/caustic_interface.h), surface in the low bits, as the
    /// x86-64 and AArch64 ABIs lay bitfields out (a test checks it).
    std::int32_t surface : 24 = -1;
    /// The radius of the patch the photon stands for at its hit, from its photon differential
    /// (photon_differential.hpp), encoded by encode_footprint_radius; 0: unknown.
    std::uint32_t footprint : 8 = 0;
    glm::vec3 power{0.0f};  ///< watts per channel
    /// The hit's light-map UV, two 16-bit unsigned fixed-point numbers (u in the low half, as
    /// GLSL's unpackUnorm2x16 reads them; 1/65535 of a page, under 1/30 texel on a 2048 page);
    /// 0 where `surface` is -1. It puts the photon in its light-map texel without a ray, for
    /// the caustic layer of the light maps that views other than the camera's sample
    /// (lighting/gpu CausticLightMaps). It took the slot of the incident direction, which no
    /// estimator read.
    std::uint32_t lightmap_uv_bits = 0;

    [[nodiscard]] glm::vec2 lightmap_uv() const;
};
static_assert(sizeof(CausticPhoton) == 32, "caustic photons are 32 bytes");

/// Surfaces a caustic photon can name: its 24-bit field holds -2^23 .. 2^23 - 1. A photon on
/// a surface beyond (a level of eight million light-mapped surfaces) is stored as on none.
inline constexpr std::int32_t kMaxCausticSurface = (1 << 23) - 1;

/// A footprint radius (metres) as 8 bits, logarithmically: code c >= 1 stands for
/// 0.1 mm * 2^((c - 1) / 16), 16 codes an octave (steps of 4.4%, so at most 2.2% off), up to
/// about 6 m; 0 stands for unknown (no radius, or not finite). Radii outside the range clamp
/// to its ends. The shaders decode it with the same constants (caustic_interface.h).
[[nodiscard]] std::uint32_t encode_footprint_radius(float radius);
/// The radius code `code` stands for, 0 for code 0.
[[nodiscard]] float decode_footprint_radius(std::uint32_t code);

/// A light-map UV in [0, 1]^2 as two 16-bit fixed-point numbers, and back (GLSL's
/// packUnorm2x16 layout; values outside [0, 1] are clamped, NaN reads 0).
[[nodiscard]] std::uint32_t encode_lightmap_uv(const glm::vec2& uv);
[[nodiscard]] glm::vec2 decode_lightmap_uv(std::uint32_t bits);

struct CausticSettings {
    /// Photons per (generator, light) pair; the paper's 10,000 for its one glass sphere and one
    /// light. A scene with G generators and L lights keeps G * L lists of this many, unless
    /// that exceeds max_photons.
    std::uint32_t photons_per_pair = 10'000;
    /// The first-generation photons all pairs may hold together (luxel; METHOD 7.6): where
    /// G * L * photons_per_pair would exceed it (10,000 lamps around one glass sphere), each
    /// pair gets a share in proportion to the power its light sends toward its generator
    /// (CausticEmitter::nominal_power), at least one photon per slice and at most
    /// photons_per_pair. About 32 MB of photons. 0: no limit.
    std::uint32_t max_photons = 1'000'000;
    /// K: a list is retraced over K frames, one slice per frame (the paper: 8).
    std::uint32_t slices = 8;
    /// A photon still bouncing between specular surfaces after this many interactions is
    /// dropped (counted as truncated): light trapped in glass by total internal reflection.
    std::uint32_t max_specular_interactions = 16;
    /// Progressive caustics (luxel; METHOD 7.6): while nothing invalidates a pair's list,
    /// further generations of photons_per_pair photons are traced, one slice a frame as the
    /// first generation is, and averaged in when complete, so a still caustic's noise falls as
    /// 1 / sqrt(photons); a change drops them and starts again from the first generation. This
    /// is how many photons the refinements of all pairs may hold together, shared in proportion
    /// to the power each light sends toward its generator (CausticEmitter::nominal_power);
    /// 0 turns refinement off.
    std::uint32_t refinement_photons = 320'000;
    /// At most this many generations per pair, the first included.
    std::uint32_t max_generations = 32;
    /// After a change to a settled list, its retraced slices stand in for the stale ones
    /// (CausticPhotonList; METHOD 7.6); false: the stale ones stay in view until retraced, as
    /// in [LC04].
    bool stand_in = true;
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
/// `differential` is the photon's at emission (CausticEmitter::differential), followed through
/// each specular interaction to give the stored photon its footprint (0, unknown, where it
/// went invalid). `incident_direction`, when given, receives a stored photon's direction of
/// travel on arrival (unit; the photon does not keep it), for tests of the specular paths'
/// geometry.
[[nodiscard]] std::optional<CausticPhoton> trace_caustic_photon(
    const RayScene& scene, std::span<const TraceMaterial> materials, const EmittedPhoton& photon,
    PhotonDifferential differential, std::uint64_t sample_index, std::uint32_t seed,
    std::uint32_t max_specular_interactions, CausticTraceCounters& counters,
    PathCells* cells = nullptr, glm::vec3* incident_direction = nullptr);

/// The caustic photons of one (generator, light) pair: photon_count photons in K slices, and
/// up to G - 1 further generations of as many (progressive caustics).
///
/// Slice k holds the photons j (0 <= j < photon_count) with j mod K = k. Photon j uses the
/// Halton point of index 1 + k * ceil(N / K) + j / K, so each slice is a contiguous run of the
/// Halton sequence and covers the whole emission cone on its own (with the plain index j, the
/// base-2 digits of j mod 8 would confine each slice to one eighth of the cone's cos theta).
/// Generation g's slice k is slice s = g K + k, and its i-th photon takes index
/// 1 + s * ceil(N / K) + i: every generation continues the same sequence.
///
/// Retracing is driven by dirty slices of the first generation: invalidate() marks all K
/// (something moved) and drops the later generations, and each frame slice_for_frame() names
/// the slice to retrace: frame mod K if dirty, else the next dirty one. While things keep
/// moving every slice is retraced exactly once per K frames. When nothing is dirty and the list
/// may hold more generations (set_generation_limit), refinement_slice() names the next slice of
/// the generation being traced; it is kept aside until its K slices are done, then every
/// stored photon's power is scaled so the G generations together carry the pair's power once.
///
/// Fresh slices stand in for stale ones after a change to a settled list (METHOD 7.6): when
/// the list was current as invalidate() hit it, once a quarter of its slices are retraced
/// (at least one) they hide the stale ones (photons of a scene that no longer exists: a moved
/// sphere's caustic where the sphere was), and the c retraced slices carry the pair's power,
/// each photon scaled by K / c, until the last one is retraced. (One slice of eight shown
/// eight times as bright was measured noisier than the stale ones beside it.) A list invalidated
/// again before it was current (an object that keeps moving) shows its stale slices beside the
/// fresh ones as before: they are a frame or a few old, and hiding them would show one slice's
/// photons K times as bright.
///
/// While such a list catches up (catching_up()), its refinement slices are shown as each is
/// traced rather than a generation at a time: the m slices shown carry the pair's power
/// together, each photon K / m of the power it was emitted with, so the error after a change
/// falls with every slice (a generation of K slices waits K frames or more at the catch-up
/// share). Every stored photon is rescaled at each such slice, which a still list, refining a
/// generation at a time, does not pay.
class CausticPhotonList {
  public:
    /// `stand_in`: CausticSettings::stand_in.
    CausticPhotonList(std::uint32_t photon_count, std::uint32_t slices, std::uint32_t seed,
                      bool stand_in = true);

    /// Replaces the emission (the light or the generator moved or changed) and marks every
    /// slice for retrace. `path_region`: the box the list records its photons' paths over
    /// (paths_meet; the scene's); empty, any change met by any path re-aims the list.
    void set_emitter(CausticEmitter emitter, const AxisBox& path_region = {});
    [[nodiscard]] const CausticEmitter& emitter() const { return emitter_; }
    /// Gives the emitter new siblings without a retrace: only for siblings whose spheres no
    /// ray of this pair crosses, old or new (CausticEmitter::may_sample), so no photon's share
    /// of the power changes.
    void set_siblings_keeping_photons(std::vector<BoundingSphere> siblings);
    /// Marks every slice of the first generation for retrace and drops the others (the
    /// receivers moved).
    void invalidate();
    /// Whether a path segment of a photon traced since the last invalidation (stored, dropped,
    /// escaped, staged or refined) may meet one of `boxes` (PathCells: never false when one
    /// does): where geometry changed, the list must be retraced; elsewhere its photons hold.
    [[nodiscard]] bool paths_meet(std::span<const AxisBox> boxes) const;
    [[nodiscard]] const PathCells& path_cells() const { return path_cells_; }

    [[nodiscard]] bool needs_retrace() const { return dirty_count_ > 0; }
    [[nodiscard]] bool slice_dirty(std::uint32_t slice) const { return dirty_.at(slice) != 0; }
    /// The slice to retrace in `frame`, or nullopt when the list is current.
    [[nodiscard]] std::optional<std::uint32_t> slice_for_frame(std::uint64_t frame) const;

    /// How many generations the list may hold, the first included (at least 1); fewer than
    /// it holds keeps those and traces no more.
    void set_generation_limit(std::uint32_t generations);
    [[nodiscard]] std::uint32_t generation_limit() const { return generation_limit_; }
    /// Complete generations stored (1 until the first refinement completes).
    [[nodiscard]] std::uint32_t generations() const { return generations_; }
    /// The next slice of the generation being refined (an index from slice_count() on), or
    /// nullopt while the list needs a retrace or holds its limit.
    [[nodiscard]] std::optional<std::uint32_t> refinement_slice() const;

    /// Whether trace_part has work: a slice in progress, a dirty slice or a refinement slice.
    [[nodiscard]] bool has_work() const {
        return tracing_ || needs_retrace() || refinement_slice().has_value();
    }
    /// The photons trace_part still has to trace before the list is current and at its
    /// generation limit, at most one slice's worth (an estimate for the scheduler).
    [[nodiscard]] std::uint32_t part_photons_left() const;
    /// While catching_up(): about how many photons the list still has to trace to be caught
    /// up (its dirty slices, and its refinement slices until it holds the generations it held
    /// before the change); 0 otherwise. An estimate for the scheduler, which may then give a
    /// catching-up caustic several slices in a frame where its share has room.
    [[nodiscard]] std::uint64_t catch_up_photons_left() const;
    /// Traces up to `max_photons` photons of one slice in parallel: the slice in progress, else
    /// the next dirty slice, else the next refinement slice. The slice's photons are staged
    /// until all are traced, then replace it (or complete the generation being refined), so a
    /// reader never sees half a slice; invalidate() discards a staged part. This is how the
    /// lighting system spends a frame's caustic share in units that fit it.
    CausticTraceCounters trace_part(const RayScene& scene, std::span<const TraceMaterial> materials,
                                    std::uint32_t max_photons,
                                    std::uint32_t max_specular_interactions, JobSystem& jobs);
    /// Slices trace_part completed, first-generation and refinement ones.
    [[nodiscard]] std::uint64_t parts_completed() const { return parts_completed_; }

    /// Retraces one slice in parallel and replaces its photons.
    CausticTraceCounters retrace_slice(const RayScene& scene,
                                       std::span<const TraceMaterial> materials,
                                       std::uint32_t slice, std::uint32_t max_specular_interactions,
                                       JobSystem& jobs);

    /// One slice of several lists, for retracing them together: a dirty slice, or a
    /// refinement slice.
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
    /// K, the slices of one generation.
    [[nodiscard]] std::uint32_t slices_per_generation() const { return slices_per_generation_; }
    /// The slices stored: K per complete generation.
    [[nodiscard]] std::uint32_t slice_count() const {
        return static_cast<std::uint32_t>(slices_.size());
    }
    /// Photons of slice s (any generation): ceil((N - k) / K) of them, k = s mod K.
    [[nodiscard]] std::uint32_t slice_size(std::uint32_t slice) const;
    /// The Halton index of photon j of the first generation (see the class comment).
    [[nodiscard]] std::uint64_t sample_index(std::uint32_t photon) const;
    /// The Halton index of the i-th photon of slice s (any generation).
    [[nodiscard]] std::uint64_t slice_sample_index(std::uint32_t slice, std::uint32_t i) const;
    [[nodiscard]] std::uint32_t seed() const { return seed_; }

    /// The stored photons of one slice, in photon order, with their share of the pair's power
    /// over the generations stored.
    /// Empty while a fresh slice stands in for it (the class comment).
    [[nodiscard]] std::span<const CausticPhoton> slice(std::uint32_t k) const {
        if (k < hidden_.size() && hidden_[k] != 0) {
            return {};
        }
        return standing_in_ && k < stand_ins_.size() ? stand_ins_[k] : slices_.at(k);
    }
    /// Whether retraced slices stand in for stale ones now (the class comment).
    [[nodiscard]] bool standing_in() const { return standing_in_; }
    /// Whether the list is catching up after a change to it while it was settled: it was
    /// current when invalidated and has stale slices left (standing in, or about to), or has
    /// not yet refined back to the generations it held then (within its limit).
    [[nodiscard]] bool catching_up() const;
    /// How many times slice k has been written (retraced, or rescaled as a generation was
    /// averaged in): a renderer re-uploads the slices whose count changed, and tests check the
    /// schedule with it.
    [[nodiscard]] std::uint64_t slice_retraces(std::uint32_t k) const {
        return slice_retraces_.at(k);
    }
    /// Photons slice() shows, over all slices.
    [[nodiscard]] std::size_t stored_count() const;
    /// Sum of the power of the photons slice() shows, per channel.
    [[nodiscard]] glm::dvec3 stored_power() const;
    /// Bytes held: photon capacity (the generation being refined included) plus the per-slice
    /// bookkeeping.
    [[nodiscard]] std::size_t bytes_used() const;

  private:
    void store_slice(std::uint32_t slice, std::span<const std::optional<CausticPhoton>> traced);
    /// Stores a complete slice's photons: replaces a first-generation slice, or adds a slice to
    /// the generation being refined.
    void commit_slice(std::uint32_t slice, std::vector<CausticPhoton> photons);
    /// Emits and traces the i-th photon of slice s.
    [[nodiscard]] std::optional<CausticPhoton> trace_photon(
        const RayScene& scene, std::span<const TraceMaterial> materials, std::uint32_t slice,
        std::uint32_t i, std::uint32_t max_specular_interactions, CausticTraceCounters& counters,
        PathCells* cells) const;
    /// Averages the refined generation in: every stored photon's power times G / (G + 1), the
    /// new ones' times 1 / (G + 1), appended as slices G K .. G K + K - 1.
    void complete_generation();
    /// A catching-up list's refinement slice, shown at once (the class comment): the m slices
    /// shown before it keep m / (m + 1) of their power, its photons get K / (m + 1) of theirs.
    void append_refined_slice(std::uint32_t slice, std::vector<CausticPhoton> photons);
    /// After a first-generation slice was committed: while a list that was current when it was
    /// invalidated still has stale slices, hides them and scales the retraced ones to carry the
    /// pair's power; once none is stale, back to scale 1 (the class comment).
    void update_stand_in();
    /// Ends a stand-in: the hidden slices shown again, the stored photons as traced.
    void end_stand_in();

    CausticEmitter emitter_;
    PathCells path_cells_;  ///< where the photons traced since the last invalidation went
    std::uint32_t photon_count_;
    std::uint32_t seed_;
    std::uint32_t slices_per_generation_;  ///< K
    std::uint32_t slice_stride_;           ///< ceil(N / K): Halton indices per slice
    std::vector<std::vector<CausticPhoton>> slices_;
    std::vector<std::uint8_t> dirty_;  ///< one per slice of the first generation
    /// Stand-ins: per first-generation slice, whether it is hidden (stale), and the fresh
    /// slices' photons with their power times K / c, which slice() shows while standing in.
    /// Scaled copies, not the stored photons scaled in place, so that the stored ones stay
    /// exactly as traced (a retrace of an unchanged scene reproduces them bit for bit).
    std::vector<std::uint8_t> hidden_;
    std::vector<std::vector<CausticPhoton>> stand_ins_;
    bool standing_in_ = false;
    /// The list was current when the last invalidate() hit it: its fresh slices may stand in.
    bool stand_in_allowed_ = false;
    /// The generations it held then (0: it was not current); catching_up() until it is back.
    std::uint32_t catch_up_generations_ = 0;
    std::vector<std::uint64_t> slice_retraces_;
    std::uint32_t dirty_count_ = 0;
    bool stand_in_enabled_ = true;  ///< CausticSettings::stand_in
    std::uint32_t generations_ = 1;
    std::uint32_t generation_limit_ = 1;
    /// The generation being refined: its K slices as they are traced, with the power each
    /// photon was emitted with (the pair's power over N).
    std::vector<std::vector<CausticPhoton>> refined_;
    std::vector<std::uint8_t> refined_done_;
    std::uint32_t refined_count_ = 0;
    /// trace_part's slice in progress: its index, the photons traced so far and the next one.
    bool tracing_ = false;
    std::uint32_t tracing_slice_ = 0;
    std::uint32_t tracing_next_ = 0;
    std::vector<CausticPhoton> staged_;
    std::uint64_t part_cursor_ = 0;  ///< first-generation slices trace_part completed
    std::uint64_t parts_completed_ = 0;
};

}  // namespace luxel::lighting
