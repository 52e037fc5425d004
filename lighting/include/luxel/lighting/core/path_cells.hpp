#pragma once

#include <array>
#include <cstdint>

#include <glm/glm.hpp>

#include "luxel/lighting/core/axis_box.hpp"

namespace luxel::lighting {

/// Where a set of photon paths went, coarsely (docs/METHOD.md §7.2): the cells of a 16 x 16 x 16
/// grid over a region that some path segment crossed, one bit each (512 bytes), and whether a
/// segment left the region. A caustic list keeps one, so that a moved object re-aims only the
/// lists whose photons passed where it was or where it is, not every list. The answer errs one
/// way only: meets() is true for every box a recorded segment meets (and for some it does not).
///
/// Not the PathSegmentIndex of the global photons: a caustic list's tens of thousands of paths
/// would cost 24 bytes a segment there, and a list is invalidated whole, so one bit per cell is
/// all it needs.
class PathCells {
  public:
    static constexpr int kCells = 16;

    /// No region: every segment counts as outside it, so any box with a recorded path meets.
    PathCells() = default;
    explicit PathCells(const AxisBox& region);

    /// Records the segment from `from` to `to` (a far `to` for a path that escaped: the part
    /// beyond the region only sets the outside flag). A non-finite end counts as outside.
    void add_segment(const glm::vec3& from, const glm::vec3& to);
    /// Adds another record's cells (over the same region) to this one.
    void merge(const PathCells& other);
    /// Forgets the segments, keeps the region.
    void clear();

    /// Whether some recorded segment may meet `box`: a cell of the box's holds one, or the box
    /// reaches outside the region and some segment went there. False for an empty box.
    [[nodiscard]] bool meets(const AxisBox& box) const;
    /// Whether nothing was recorded.
    [[nodiscard]] bool empty() const;
    [[nodiscard]] const AxisBox& region() const { return region_; }
    /// Whether some segment left the region.
    [[nodiscard]] bool outside() const { return outside_; }

  private:
    void mark(const glm::ivec3& cell);
    [[nodiscard]] bool marked(const glm::ivec3& cell) const;

    AxisBox region_;
    glm::vec3 cell_size_{0.0f};
    std::array<std::uint64_t, kCells * kCells * kCells / 64> bits_{};
    bool outside_ = false;
};

}  // namespace luxel::lighting
