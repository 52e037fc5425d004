#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/lighting/core/axis_box.hpp"
#include "luxel/lighting/core/photon_map.hpp"

namespace luxel::lighting {

/// One straight piece of a stored photon path: from the light to its first hop, or from one
/// hop to the next.
struct PathSegment {
    glm::vec3 from{0.0f};
    glm::vec3 to{0.0f};
};

/// Whether the closed segment meets the closed box (the slab test; a segment with a non-finite
/// end meets nothing).
[[nodiscard]] bool segment_meets_box(const PathSegment& segment, const AxisBox& box);

/// The segments of a traced group's paths: photon k's from `origins[k]` through its hops.
[[nodiscard]] std::vector<PathSegment> path_segments(const TracedGroup& traced);

/// Where the stored photon paths go (docs/METHOD.md §4.5, exact invalidation): every group's
/// path segments, binned in a hashed grid by the cells each passes through, so that when an
/// object moves the groups whose photons crossed where it was or where it is are found at once,
/// without waiting for the round-robin probes to pick one of their photons, and without
/// testing every stored path. The grid only narrows the search: a candidate group's segments
/// are then tested exactly, so groups_meeting() answers what a test of every segment would.
///
/// Cells are cubes of one size, chosen from the first group's extent (an eighth of it): coarse
/// enough that a segment across a room visits a few dozen cells, fine enough that a crate's box
/// meets a few. The grid has no bounds (cells are hashed), so geometry that moves far away
/// needs no rebuild. A segment that would visit more than kMaxCellsPerSegment cells (a
/// directional light's photons start far outside the scene) leaves its group unbinned: always
/// tested exactly.
class PathSegmentIndex {
  public:
    static constexpr std::size_t kMaxCellsPerSegment = 4096;

    /// Replaces group `group`'s segments (growing the group table as needed).
    void set_group(std::uint32_t group, std::vector<PathSegment> segments);
    /// Forgets group `group`'s segments (its light went away or was switched off).
    void clear_group(std::uint32_t group);

    /// The groups with a segment that meets `box`, ascending, without repeats.
    [[nodiscard]] std::vector<std::uint32_t> groups_meeting(const AxisBox& box) const;
    /// The groups with a segment that meets any of `boxes`, ascending, without repeats; one
    /// read of each candidate group's segments for all the boxes it may meet, cheaper than a
    /// query per box when boxes overlap (an object's old and new places). Groups g with
    /// skip[g] != 0 are neither tested nor returned (the caller knows their answer already).
    [[nodiscard]] std::vector<std::uint32_t> groups_meeting(
        std::span<const AxisBox> boxes, std::span<const std::uint8_t> skip = {}) const;

    [[nodiscard]] std::span<const PathSegment> segments(std::uint32_t group) const;
    [[nodiscard]] std::size_t group_count() const { return groups_.size(); }
    [[nodiscard]] std::size_t segment_count() const { return segment_count_; }
    /// The grid's cell edge in metres (0 until the first group with segments).
    [[nodiscard]] float cell_size() const { return cell_size_; }
    /// Bytes held (capacity): segments, each group's cells, the cells' group lists.
    [[nodiscard]] std::size_t bytes_used() const;

  private:
    struct Group {
        std::vector<PathSegment> segments;
        bool unbinned = false;
    };

    struct Candidate {
        std::uint32_t group = 0;
        std::uint32_t box = 0;
        auto operator<=>(const Candidate&) const = default;
    };
    /// The groups binned in the cells `box` covers (all of them for a box too large for the
    /// grid) and the unbinned ones, each as (group, box_index).
    void add_candidates(const AxisBox& box, std::uint32_t box_index,
                        std::vector<Candidate>& candidates) const;
    /// The cells the segment passes through, appended to `cells`; false when there would be
    /// more than kMaxCellsPerSegment.
    bool add_cells(const PathSegment& segment, std::vector<std::uint64_t>& cells) const;
    /// The cells of all the segments, sorted and unique; false (and none) when one segment
    /// would visit too many. Walked again when a group is cleared instead of kept per group:
    /// 8 bytes a cell for every group would double the index's memory for a walk that costs
    /// about what storing them did.
    bool cells_of(std::span<const PathSegment> segments, std::vector<std::uint64_t>& cells) const;

    std::vector<Group> groups_;
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cell_groups_;
    std::vector<std::uint32_t> unbinned_;  ///< sorted
    std::size_t segment_count_ = 0;
    float cell_size_ = 0.0f;
};

}  // namespace luxel::lighting
