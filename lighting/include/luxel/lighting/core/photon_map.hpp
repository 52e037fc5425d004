#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/lighting/core/compensated_sum.hpp"
#include "luxel/lighting/core/ray_scene.hpp"

/// Where photon hits live (docs/METHOD.md §4.3-4.4): per surface, in contiguous arrays, each hit
/// knowing its group; each group knows the surfaces its hits lie on and a fingerprint of every
/// photon's path, which is all that retracing and path comparison need.
namespace luxel::lighting {

/// One stored photon hit as a reader sees it (PhotonMap::hit).
struct StoredHit {
    glm::vec3 position{0.0f};
    glm::vec3 power{0.0f};    ///< watts per channel carried by the photon when it arrived
    std::uint32_t group = 0;  ///< the group whose path made this hit
    /// Diffuse bounces before this hit (0: direct from the light), saturating at 255.
    std::uint32_t bounces = 0;
};

/// A stored hit's power: three IEEE half floats relative to its group's power scale (the
/// largest channel of any hop the group stored), which holds each channel to 2^-11 of its own
/// value down to 6e-5 of the group's brightest photon.
using HalfPower = std::array<std::uint16_t, 3>;

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

/// What a surface holds and how much has changed on it. The hits are three parallel arrays,
/// 22 bytes a hit: retracing a group finds its hits by reading the owners alone (4 bytes a hit).
struct SurfacePhotons {
    std::vector<glm::vec3> positions;
    std::vector<HalfPower> powers;
    std::vector<std::uint32_t> owners;  ///< group (bits 0-23) and bounces (24-31, saturating)
    CompensatedSum stored_energy;       ///< sum over hits of (r + g + b) power
    /// The energy of every hit ever stored on or removed from the surface, and the same for
    /// hits with at least one bounce (the indirect part). Never reset: delta_f and delta_i are
    /// these counts minus a reader's position in them (SurfaceDeltas).
    CompensatedSum changed_full;
    CompensatedSum changed_indirect;

    [[nodiscard]] std::size_t hit_count() const { return owners.size(); }
};

/// Comparison tolerance for probe paths, in metres: a stored hop that moved farther always
/// makes its path diverge (see PhotonMap::diverges for what a smaller move does).
struct DivergenceTolerance {
    float distance = 1e-3f;
};

class PhotonMap {
  public:
    /// Surfaces are numbered 0 .. surface_count - 1; groups 0 .. group_count - 1.
    PhotonMap(std::size_t surface_count, std::size_t group_count,
              DivergenceTolerance tolerance = {});

    /// Adds empty surfaces or groups at the end; returns the first new index.
    std::uint32_t add_surfaces(std::size_t count);
    std::uint32_t add_groups(std::size_t count);

    /// Replaces every stored path of `group` with `traced` (removing the old hits first).
    void replace_group(std::uint32_t group, const TracedGroup& traced);
    /// The same for several distinct groups at once (`traced[i]` replaces `groups[i]`, stored in
    /// that order): the old hits go in one pass over the surfaces they lie on.
    void replace_groups(std::span<const std::uint32_t> groups, std::span<const TracedGroup> traced);
    /// Removes every hit of `group` (its light went away or was disabled).
    void clear_group(std::uint32_t group);
    void clear_groups(std::span<const std::uint32_t> groups);

    /// Whether photon `photon` of `group`, traced anew as `hops`, differs from its stored path,
    /// by the paths' fingerprints: the number of hops, each hop's surface (or, where nothing was
    /// stored, its object) and each stored hop's position on a grid of cells tolerance / sqrt(3)
    /// wide. A stored hop that moved by more than the tolerance always diverges; one that moved
    /// less diverges only when it crossed a cell's face (a needless retrace, not a missed one).
    /// Two different paths share a fingerprint with probability 2^-32, and the next probe of
    /// the group, M frames on, tries another photon.
    [[nodiscard]] bool diverges(std::uint32_t group, std::uint32_t photon,
                                std::span<const TracedHop> hops) const;

    [[nodiscard]] const SurfacePhotons& surface(std::uint32_t surface) const {
        return surfaces_[surface];
    }
    [[nodiscard]] std::size_t surface_count() const { return surfaces_.size(); }
    [[nodiscard]] std::size_t group_count() const { return groups_.size(); }

    /// Hit `index` (< hit_count()) of `surface`, its power in watts.
    [[nodiscard]] StoredHit hit(std::uint32_t surface, std::size_t index) const;

    [[nodiscard]] std::size_t stored_hit_count() const { return stored_hits_; }
    /// Photons whose paths are kept for comparison.
    [[nodiscard]] std::size_t path_count() const;
    /// Bytes held for stored hits and path bookkeeping (capacity, not just size).
    [[nodiscard]] std::size_t bytes_used() const;

    /// Recomputes a surface's stored energy from its hits (the check that the running sums do
    /// not drift).
    [[nodiscard]] double recount_energy(std::uint32_t surface) const;

  private:
    struct GroupPaths {
        std::vector<std::uint32_t> fingerprints;  ///< one per photon
        std::vector<std::uint32_t> surfaces;      ///< where its hits lie, each once
        float power_scale = 0.0f;                 ///< what a half-float power of 1 means
    };

    [[nodiscard]] std::uint32_t fingerprint(std::span<const TracedHop> hops) const;
    [[nodiscard]] glm::vec3 power(std::uint32_t owner, const HalfPower& power) const;
    void store_group(std::uint32_t group, const TracedGroup& traced);

    std::vector<SurfacePhotons> surfaces_;
    std::vector<GroupPaths> groups_;
    std::size_t stored_hits_ = 0;
    double inverse_cell_ = 0.0;  ///< 1 / the fingerprints' grid spacing, per metre
    /// Scratch of clear_groups: 1 for a group being cleared, 1 for a surface to compact.
    std::vector<std::uint8_t> clearing_;
    std::vector<std::uint8_t> touched_;
};

}  // namespace luxel::lighting
