#include "luxel/lighting/core/path_segment_index.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "grid_walk.hpp"

namespace luxel::lighting {

namespace {

/// Cell coordinates are kept within +-2^20 so three fit one 64-bit key; a segment reaching
/// beyond leaves its group unbinned.
constexpr std::int64_t kCoordLimit = (std::int64_t{1} << 20) - 1;
constexpr std::uint64_t kCoordMask = (std::uint64_t{1} << 21) - 1;
/// Cells visited by a query box's expansion beyond which scanning every group is cheaper.
constexpr std::int64_t kMaxQueryCells = std::int64_t{1} << 16;
/// A query box grows by this fraction of a cell before it picks cells, so that a segment
/// grazing a cell's corner (where the traversal's rounding may have stepped into the
/// neighbouring cell instead) is still a candidate; the exact test then decides.
constexpr double kQueryMargin = 1e-3;

std::uint64_t cell_key(std::int64_t x, std::int64_t y, std::int64_t z) {
    const auto pack = [](std::int64_t v) {
        return static_cast<std::uint64_t>(v + kCoordLimit + 1) & kCoordMask;
    };
    return pack(x) | (pack(y) << 21) | (pack(z) << 42);
}

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

bool segment_meets_box(const PathSegment& segment, const AxisBox& box) {
    // Most segments a query tests pass nowhere near the box, which their own bounds tell with
    // six comparisons and no division (exact: a segment lies within its bounds). Branch-free,
    // since a branch per axis mispredicts on segments rejected at random.
    const glm::vec3 low = glm::min(segment.from, segment.to);
    const glm::vec3 high = glm::max(segment.from, segment.to);
    if (static_cast<int>(high.x < box.min.x) | static_cast<int>(high.y < box.min.y) |
        static_cast<int>(high.z < box.min.z) | static_cast<int>(low.x > box.max.x) |
        static_cast<int>(low.y > box.max.y) | static_cast<int>(low.z > box.max.z)) {
        return false;
    }
    if (box.empty() || !finite(segment.from) || !finite(segment.to)) {
        return false;
    }
    // Slab test in double over the parameter t in [0, 1] of from + t (to - from).
    double enter = 0.0;
    double leave = 1.0;
    for (int axis = 0; axis < 3; ++axis) {
        const double from = segment.from[axis];
        const double delta = static_cast<double>(segment.to[axis]) - from;
        const double lo = box.min[axis];
        const double hi = box.max[axis];
        if (delta == 0.0) {
            if (from < lo || from > hi) {
                return false;
            }
            continue;
        }
        double t0 = (lo - from) / delta;
        double t1 = (hi - from) / delta;
        if (t0 > t1) {
            std::swap(t0, t1);
        }
        enter = std::max(enter, t0);
        leave = std::min(leave, t1);
        if (enter > leave) {
            return false;
        }
    }
    return true;
}

std::vector<PathSegment> path_segments(const TracedGroup& traced) {
    std::vector<PathSegment> segments;
    segments.reserve(traced.hops.size());
    for (std::size_t k = 0; k + 1 < traced.starts.size(); ++k) {
        const std::uint32_t first = traced.starts[k];
        const std::uint32_t end = std::min<std::uint32_t>(
            traced.starts[k + 1], static_cast<std::uint32_t>(traced.hops.size()));
        if (first >= end) {
            continue;
        }
        if (k < traced.origins.size()) {
            segments.push_back({traced.origins[k], traced.hops[first].position});
        }
        for (std::uint32_t h = first + 1; h < end; ++h) {
            segments.push_back({traced.hops[h - 1].position, traced.hops[h].position});
        }
    }
    return segments;
}

bool PathSegmentIndex::add_cells(const PathSegment& segment,
                                 std::vector<std::uint64_t>& cells) const {
    if (!finite(segment.from) || !finite(segment.to)) {
        return true;  // meets nothing: no cells
    }
    const double scale = 1.0 / static_cast<double>(cell_size_);
    const glm::dvec3 a = glm::dvec3(segment.from) * scale;
    const glm::dvec3 b = glm::dvec3(segment.to) * scale;
    const auto limit = static_cast<double>(kCoordLimit - 1);
    for (int axis = 0; axis < 3; ++axis) {
        if (std::abs(a[axis]) > limit || std::abs(b[axis]) > limit) {
            return false;
        }
    }
    return walk_grid(
        a, b, static_cast<std::int64_t>(kMaxCellsPerSegment),
        [&](const glm::i64vec3& cell) { cells.push_back(cell_key(cell.x, cell.y, cell.z)); });
}

bool PathSegmentIndex::cells_of(std::span<const PathSegment> segments,
                                std::vector<std::uint64_t>& cells) const {
    for (const PathSegment& s : segments) {
        if (!add_cells(s, cells)) {
            cells.clear();
            return false;
        }
    }
    std::sort(cells.begin(), cells.end());
    cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
    return true;
}

void PathSegmentIndex::set_group(std::uint32_t group, std::vector<PathSegment> segments) {
    clear_group(group);
    if (segments.empty()) {
        return;
    }
    if (!(cell_size_ > 0.0f)) {
        AxisBox extent;
        for (const PathSegment& s : segments) {
            if (finite(s.from) && finite(s.to)) {
                extent.add(s.from);
                extent.add(s.to);
            }
        }
        const glm::vec3 size = extent.empty() ? glm::vec3(0.0f) : extent.max - extent.min;
        const float largest = std::max(size.x, std::max(size.y, size.z));
        // An eighth of the paths' extent; a metre when the extent says nothing (one point).
        cell_size_ = std::isfinite(largest) && largest > 1e-6f ? largest / 8.0f : 1.0f;
    }
    Group& entry = groups_[group];
    std::vector<std::uint64_t> cells;
    entry.unbinned = !cells_of(segments, cells);
    if (entry.unbinned) {
        unbinned_.insert(std::upper_bound(unbinned_.begin(), unbinned_.end(), group), group);
    } else {
        for (const std::uint64_t cell : cells) {
            cell_groups_[cell].push_back(group);
        }
    }
    segment_count_ += segments.size();
    entry.segments = std::move(segments);
}

void PathSegmentIndex::clear_group(std::uint32_t group) {
    if (group >= groups_.size()) {
        groups_.resize(static_cast<std::size_t>(group) + 1);
        return;
    }
    Group& entry = groups_[group];
    std::vector<std::uint64_t> cells;
    if (!entry.unbinned) {
        cells_of(entry.segments, cells);
    }
    for (const std::uint64_t cell : cells) {
        const auto found = cell_groups_.find(cell);
        if (found == cell_groups_.end()) {
            continue;
        }
        std::erase(found->second, group);
        if (found->second.empty()) {
            cell_groups_.erase(found);
        }
    }
    if (entry.unbinned) {
        std::erase(unbinned_, group);
    }
    segment_count_ -= entry.segments.size();
    entry = Group{};
}

std::vector<std::uint32_t> PathSegmentIndex::groups_meeting(const AxisBox& box) const {
    return groups_meeting(std::span<const AxisBox>(&box, 1));
}

void PathSegmentIndex::add_candidates(const AxisBox& box, std::uint32_t box_index,
                                      std::vector<Candidate>& candidates) const {
    const double scale = 1.0 / static_cast<double>(cell_size_);
    const glm::dvec3 lo = glm::dvec3(box.min) * scale - kQueryMargin;
    const glm::dvec3 hi = glm::dvec3(box.max) * scale + kQueryMargin;
    const auto bound = static_cast<double>(kCoordLimit);
    double cells = 1.0;
    bool scan_all = false;
    for (int axis = 0; axis < 3; ++axis) {
        scan_all = scan_all || std::abs(lo[axis]) > bound || std::abs(hi[axis]) > bound;
        cells *= std::floor(hi[axis]) - std::floor(lo[axis]) + 1.0;
    }
    scan_all = scan_all || cells > static_cast<double>(kMaxQueryCells);
    if (scan_all) {
        // A box as large as the scene meets most groups anyway: test them all.
        for (std::uint32_t g = 0; g < groups_.size(); ++g) {
            candidates.push_back({g, box_index});
        }
        return;
    }
    const glm::i64vec3 first(static_cast<std::int64_t>(std::floor(lo.x)),
                             static_cast<std::int64_t>(std::floor(lo.y)),
                             static_cast<std::int64_t>(std::floor(lo.z)));
    const glm::i64vec3 end(static_cast<std::int64_t>(std::floor(hi.x)),
                           static_cast<std::int64_t>(std::floor(hi.y)),
                           static_cast<std::int64_t>(std::floor(hi.z)));
    for (std::int64_t z = first.z; z <= end.z; ++z) {
        for (std::int64_t y = first.y; y <= end.y; ++y) {
            for (std::int64_t x = first.x; x <= end.x; ++x) {
                const auto cell = cell_groups_.find(cell_key(x, y, z));
                if (cell != cell_groups_.end()) {
                    for (const std::uint32_t g : cell->second) {
                        candidates.push_back({g, box_index});
                    }
                }
            }
        }
    }
    for (const std::uint32_t g : unbinned_) {
        candidates.push_back({g, box_index});
    }
}

std::vector<std::uint32_t> PathSegmentIndex::groups_meeting(
    std::span<const AxisBox> boxes, std::span<const std::uint8_t> skip) const {
    std::vector<std::uint32_t> found;
    if (segment_count_ == 0) {
        return found;
    }
    std::vector<Candidate> candidates;
    for (std::size_t b = 0; b < boxes.size(); ++b) {
        const AxisBox& box = boxes[b];
        if (!box.empty() && finite(box.min) && finite(box.max)) {
            add_candidates(box, static_cast<std::uint32_t>(b), candidates);
        }
    }
    std::erase_if(candidates,
                  [&](const Candidate& c) { return c.group < skip.size() && skip[c.group] != 0; });
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    // Each candidate group's segments are read once for every box it may meet: the two boxes
    // of a moved object (where it was, where it is) mostly overlap, and reading the segments
    // is what a query costs.
    std::vector<const AxisBox*> its_boxes;
    for (std::size_t run = 0; run < candidates.size();) {
        const std::uint32_t g = candidates[run].group;
        its_boxes.clear();
        std::size_t next = run;
        for (; next < candidates.size() && candidates[next].group == g; ++next) {
            its_boxes.push_back(&boxes[candidates[next].box]);
        }
        run = next;
        const bool meets = std::any_of(
            groups_[g].segments.begin(), groups_[g].segments.end(), [&](const PathSegment& s) {
                return std::any_of(its_boxes.begin(), its_boxes.end(),
                                   [&](const AxisBox* box) { return segment_meets_box(s, *box); });
            });
        if (meets) {
            found.push_back(g);
        }
    }
    return found;
}

std::span<const PathSegment> PathSegmentIndex::segments(std::uint32_t group) const {
    if (group >= groups_.size()) {
        return {};
    }
    return groups_[group].segments;
}

std::size_t PathSegmentIndex::bytes_used() const {
    std::size_t bytes =
        groups_.capacity() * sizeof(Group) + unbinned_.capacity() * sizeof(std::uint32_t);
    for (const Group& group : groups_) {
        bytes += group.segments.capacity() * sizeof(PathSegment);
    }
    // The hash map: a node per cell (key, vector, next pointer) and a bucket pointer each.
    bytes += cell_groups_.bucket_count() * sizeof(void*);
    for (const auto& [cell, groups] : cell_groups_) {
        bytes += sizeof(cell) + sizeof(groups) + sizeof(void*) +
                 groups.capacity() * sizeof(std::uint32_t);
    }
    return bytes;
}

}  // namespace luxel::lighting
