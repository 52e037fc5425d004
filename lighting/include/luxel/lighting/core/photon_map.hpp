#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/lighting/core/compensated_sum.hpp"
#include "luxel/lighting/core/ray_scene.hpp"

/// Where photon hits live (docs/METHOD.md §4.3-4.4): per surface, in contiguous arrays, each hit
/// knowing which path hop put it there so that invalidating a path removes its hits in O(1) each.
namespace luxel::lighting {

/// One photon hit on a light-mapped surface: 32 bytes.
struct StoredHit {
    glm::vec3 position{0.0f};
    glm::vec3 power{0.0f};    ///< watts per channel carried by the photon when it arrived
    std::uint32_t group = 0;  ///< the group whose path made this hit (bits 0-23), bounce (24-31)
    std::uint32_t hop = 0;    ///< index of that hop in the group's hop array

    [[nodiscard]] std::uint32_t group_index() const { return group & 0x00FFFFFFu; }
    /// Diffuse bounces before this hit (0: direct from the light), saturating at 255.
    [[nodiscard]] std::uint32_t bounces() const { return group >> 24; }
};

/// A hop of a traced photon path, as the tracer reports it.
struct TracedHop {
    glm::vec3 position{0.0f};
    glm::vec3 power{0.0f};
    std::int32_t surface = -1;  ///< -1: not light-mapped, nothing stored
    ObjectId object = kNoObject;
    std::uint32_t bounces = 0;
};

/// The photons of one group as traced: hops of photon k are hops[starts[k] .. starts[k + 1]).
struct TracedGroup {
    std::vector<TracedHop> hops;
    std::vector<std::uint32_t> starts;  ///< photon_count + 1 entries
    /// Where each photon left its light (photon_count entries; empty: not known), the first
    /// point of its path for the PathSegmentIndex.
    std::vector<glm::vec3> origins;
};

/// What a surface holds and how much has changed on it.
struct SurfacePhotons {
    std::vector<StoredHit> hits;
    CompensatedSum stored_energy;  ///< sum over hits of (r + g + b) power
    /// The energy of every hit ever stored on or removed from the surface, and the same for
    /// hits with at least one bounce (the indirect part). Never reset: delta_f and delta_i are
    /// these counts minus a reader's position in them (SurfaceDeltas).
    CompensatedSum changed_full;
    CompensatedSum changed_indirect;
};

/// Comparison tolerance for probe paths, in metres.
struct DivergenceTolerance {
    float distance = 1e-3f;
};

class PhotonMap {
  public:
    /// Surfaces are numbered 0 .. surface_count - 1; groups 0 .. group_count - 1.
    PhotonMap(std::size_t surface_count, std::size_t group_count);

    /// Adds empty surfaces or groups at the end; returns the first new index.
    std::uint32_t add_surfaces(std::size_t count);
    std::uint32_t add_groups(std::size_t count);

    /// Replaces every stored path of `group` with `traced` (removing the old hits first).
    void replace_group(std::uint32_t group, const TracedGroup& traced);
    /// Removes every hit of `group` (its light went away or was disabled).
    void clear_group(std::uint32_t group);

    /// Whether photon `photon` of `group`, traced anew as `hops`, differs from its stored path:
    /// a different number of hops, a different surface or object at some hop, or a stored hop
    /// that moved by more than the tolerance. Hops that were not stored (surface -1) compare by
    /// object only.
    [[nodiscard]] bool diverges(std::uint32_t group, std::uint32_t photon,
                                std::span<const TracedHop> hops,
                                const DivergenceTolerance& tolerance) const;

    [[nodiscard]] const SurfacePhotons& surface(std::uint32_t surface) const {
        return surfaces_[surface];
    }
    [[nodiscard]] std::size_t surface_count() const { return surfaces_.size(); }
    [[nodiscard]] std::size_t group_count() const { return groups_.size(); }

    [[nodiscard]] std::size_t stored_hit_count() const { return stored_hits_; }
    /// Hops kept for path comparison (stored or not).
    [[nodiscard]] std::size_t hop_count() const;
    /// Bytes held for stored hits and path bookkeeping (capacity, not just size).
    [[nodiscard]] std::size_t bytes_used() const;

    /// Recomputes a surface's stored energy from its hits (the check that the running sums do
    /// not drift).
    [[nodiscard]] double recount_energy(std::uint32_t surface) const;

  private:
    /// A hop's place: the surface and slot of its stored hit, or (-1, object) when not stored.
    struct HopRecord {
        std::int32_t surface = -1;
        std::uint32_t slot_or_object = 0;
    };
    struct GroupPaths {
        std::vector<HopRecord> hops;
        std::vector<std::uint32_t> starts;
    };

    void remove_hit(std::uint32_t surface, std::uint32_t slot);

    std::vector<SurfacePhotons> surfaces_;
    std::vector<GroupPaths> groups_;
    std::size_t stored_hits_ = 0;
};

}  // namespace luxel::lighting
