#pragma once

#include <cstdint>
#include <vector>

#include "luxel/lighting/core/light_source.hpp"
#include "luxel/lighting/core/path_segment_index.hpp"
#include "luxel/lighting/core/photon_map.hpp"
#include "luxel/lighting/core/photon_tracer.hpp"
#include "luxel/runtime/jobs.hpp"

/// The paper's selective photon emission (docs/METHOD.md §4): a light's photons are split into G
/// groups of M photons with similar initial directions. Each frame one probe photon per group is
/// retraced; a group whose probe path diverges from the stored one is retraced whole.
namespace luxel::lighting {

/// Splits the Halton indices 1 .. groups * per_group into `groups` sets of exactly `per_group`
/// indices whose 2D points (bases 2, 3) are compact: a recursive split at the median of the
/// wider coordinate, sized in proportion to the groups on each side. Each set is sorted. The
/// same arguments always give the same sets.
[[nodiscard]] std::vector<std::vector<std::uint64_t>> partition_into_groups(
    std::uint32_t groups, std::uint32_t per_group);

struct SelectiveSettings {
    std::uint32_t groups = 77;      ///< G (the paper's configuration)
    std::uint32_t per_group = 40;   ///< M
    DivergenceTolerance tolerance;  ///< the PhotonMap's, given when it is made
    TraceLimits limits;
    /// When an object moves, appears or goes away, the groups whose stored paths cross where it
    /// was or where it is are retraced first, in the frame of the change (PathSegmentIndex);
    /// the round-robin probes stay for what the index cannot see (a photon that left the scene
    /// through where an object now stands, tolerance drift). Off: the paper's probes alone.
    bool exact_invalidation = true;
};

/// Counters of one call.
struct EmissionStats {
    std::uint32_t probes = 0;
    std::uint32_t diverged = 0;
    std::uint32_t groups_retraced = 0;
    TraceCounters trace;
};

/// One light's groups. Its groups occupy [first_group, first_group + groups) of a PhotonMap.
class LightPhotons {
  public:
    LightPhotons(PhotonEmitter emitter, std::uint32_t first_group, std::uint32_t seed,
                 const SelectiveSettings& settings);

    [[nodiscard]] std::uint32_t first_group() const { return first_group_; }
    [[nodiscard]] std::uint32_t group_count() const {
        return static_cast<std::uint32_t>(indices_.size());
    }
    [[nodiscard]] std::uint32_t photons_per_group() const { return per_group_; }
    [[nodiscard]] const PhotonEmitter& emitter() const { return emitter_; }
    /// Replaces the light (it moved or changed): every group must be retraced.
    void set_emitter(PhotonEmitter emitter);

    /// Traces photon `photon` of group `group` (local index) into `hops`; returns where it left
    /// the light.
    glm::vec3 trace(const RayScene& scene, std::span<const TraceMaterial> materials,
                    std::uint32_t group, std::uint32_t photon, std::vector<TracedHop>& hops,
                    TraceCounters& counters) const;
    /// Traces a whole group.
    [[nodiscard]] TracedGroup trace_group(const RayScene& scene,
                                          std::span<const TraceMaterial> materials,
                                          std::uint32_t group, TraceCounters& counters) const;

  private:
    PhotonEmitter emitter_;
    std::uint32_t first_group_;
    std::uint32_t seed_;
    std::uint32_t per_group_;
    TraceLimits limits_;
    std::vector<std::vector<std::uint64_t>> indices_;
};

/// Runs the probes of `frame` for the given lights against `map`: photon (frame mod M) of every
/// group is retraced in parallel and compared; the global indices of the groups whose probe
/// diverged are appended to `invalid_groups` in ascending order. Nothing in `map` changes.
EmissionStats run_probes(const RayScene& scene, std::span<const TraceMaterial> materials,
                         std::span<const LightPhotons* const> lights, const PhotonMap& map,
                         std::uint64_t frame, JobSystem& jobs,
                         std::vector<std::uint32_t>& invalid_groups);

/// Retraces the given groups (global indices) in parallel and stores them in `map` in group
/// order, so the result is the same for any thread count.
EmissionStats retrace_groups(const RayScene& scene, std::span<const TraceMaterial> materials,
                             std::span<const LightPhotons* const> lights, PhotonMap& map,
                             std::span<const std::uint32_t> groups, JobSystem& jobs,
                             PathSegmentIndex* index = nullptr);

}  // namespace luxel::lighting
