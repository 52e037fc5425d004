// Exact invalidation's index of stored path segments (docs/METHOD.md §4.5): whatever the grid
// does, groups_meeting() must answer exactly what testing every stored segment answers, for
// random paths and boxes, segments along cell faces and through cell corners, far-reaching
// segments (unbinned), degenerate and non-finite ones, and after groups are replaced and
// cleared.

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "luxel/lighting/core/path_segment_index.hpp"

namespace {

using namespace luxel::lighting;

AxisBox box_of(const glm::vec3& lo, const glm::vec3& hi) {
    AxisBox box;
    box.add(lo);
    box.add(hi);
    return box;
}

/// Every group with a segment meeting the box, by testing every segment.
std::vector<std::uint32_t> brute_force(const std::vector<std::vector<PathSegment>>& groups,
                                       const AxisBox& box) {
    std::vector<std::uint32_t> found;
    for (std::uint32_t g = 0; g < groups.size(); ++g) {
        if (std::any_of(groups[g].begin(), groups[g].end(),
                        [&](const PathSegment& s) { return segment_meets_box(s, box); })) {
            found.push_back(g);
        }
    }
    return found;
}

TEST(SegmentMeetsBox, TheSlabTestOnEdgeCases) {
    const AxisBox unit = box_of(glm::vec3(0.0f), glm::vec3(1.0f));
    EXPECT_TRUE(
        segment_meets_box({glm::vec3(-1.0f, 0.5f, 0.5f), glm::vec3(2.0f, 0.5f, 0.5f)}, unit));
    EXPECT_FALSE(
        segment_meets_box({glm::vec3(-1.0f, 1.5f, 0.5f), glm::vec3(2.0f, 1.5f, 0.5f)}, unit));
    // Ends short of the box, inside it, touching its face, along its edge.
    EXPECT_FALSE(
        segment_meets_box({glm::vec3(-2.0f, 0.5f, 0.5f), glm::vec3(-0.1f, 0.5f, 0.5f)}, unit));
    EXPECT_TRUE(segment_meets_box({glm::vec3(0.2f), glm::vec3(0.3f)}, unit));
    EXPECT_TRUE(
        segment_meets_box({glm::vec3(-1.0f, 0.5f, 0.5f), glm::vec3(0.0f, 0.5f, 0.5f)}, unit));
    EXPECT_TRUE(
        segment_meets_box({glm::vec3(-1.0f, 1.0f, 1.0f), glm::vec3(2.0f, 1.0f, 1.0f)}, unit));
    // A diagonal that passes beside the box's corner.
    EXPECT_FALSE(
        segment_meets_box({glm::vec3(1.2f, 2.0f, 0.5f), glm::vec3(2.0f, 1.2f, 0.5f)}, unit));
    // A point, and a segment with a non-finite end, and an empty box.
    EXPECT_TRUE(segment_meets_box({glm::vec3(0.5f), glm::vec3(0.5f)}, unit));
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_FALSE(segment_meets_box({glm::vec3(0.5f), glm::vec3(nan, 0.5f, 0.5f)}, unit));
    EXPECT_FALSE(segment_meets_box({glm::vec3(0.5f), glm::vec3(0.6f)}, AxisBox{}));
}

TEST(PathSegmentIndex, FindsExactlyTheGroupsABruteForceTestFinds) {
    std::mt19937 rng(1234);
    std::uniform_real_distribution<float> room(-2.0f, 2.0f);
    std::uniform_real_distribution<float> size(0.01f, 1.2f);
    std::uniform_int_distribution<int> hops(1, 6);
    constexpr std::uint32_t kGroups = 60;
    std::vector<std::vector<PathSegment>> groups(kGroups);
    PathSegmentIndex index;
    const auto fill = [&](std::uint32_t g) {
        std::vector<PathSegment> segments;
        for (int photon = 0; photon < 8; ++photon) {
            glm::vec3 at(room(rng), room(rng), room(rng));
            for (int h = hops(rng); h > 0; --h) {
                const glm::vec3 next(room(rng), room(rng), room(rng));
                segments.push_back({at, next});
                at = next;
            }
        }
        // Hard cases in some groups: axis-aligned segments on the cell grid's faces (the
        // first group's extent sets the cells; these lie on round coordinates), a point, a
        // non-finite segment, and one reaching ten kilometres away (unbinned).
        if (g % 7 == 0) {
            segments.push_back({glm::vec3(0.0f, 0.0f, -2.0f), glm::vec3(0.0f, 0.0f, 2.0f)});
            segments.push_back({glm::vec3(-1.0f, 1.0f, 0.5f), glm::vec3(1.0f, -1.0f, 0.5f)});
        }
        if (g % 11 == 3) {
            segments.push_back({glm::vec3(0.25f), glm::vec3(0.25f)});
            segments.push_back(
                {glm::vec3(0.0f), glm::vec3(std::numeric_limits<float>::infinity(), 0.0f, 0.0f)});
        }
        if (g % 13 == 5) {
            segments.push_back({glm::vec3(-10000.0f, 0.3f, 0.2f), glm::vec3(1.5f, 0.3f, 0.2f)});
        }
        groups[g] = segments;
        index.set_group(g, std::move(segments));
    };
    for (std::uint32_t g = 0; g < kGroups; ++g) {
        fill(g);
    }
    ASSERT_GT(index.cell_size(), 0.0f);

    const auto check = [&](const char* when) {
        int meeting = 0;
        for (int q = 0; q < 400; ++q) {
            const glm::vec3 lo(room(rng), room(rng), room(rng));
            const AxisBox box = box_of(lo, lo + glm::vec3(size(rng), size(rng), size(rng)));
            const std::vector<std::uint32_t> expected = brute_force(groups, box);
            EXPECT_EQ(index.groups_meeting(box), expected) << when << ", query " << q;
            meeting += expected.empty() ? 0 : 1;
        }
        // Boxes on the grid's own corners and faces, and a box far larger than the room.
        for (const float c : {0.0f, 0.5f, 1.0f, -1.0f}) {
            const AxisBox box = box_of(glm::vec3(c), glm::vec3(c + 0.001f));
            EXPECT_EQ(index.groups_meeting(box), brute_force(groups, box)) << when;
        }
        const AxisBox huge = box_of(glm::vec3(-1e5f), glm::vec3(1e5f));
        EXPECT_EQ(index.groups_meeting(huge), brute_force(groups, huge)) << when;
        // Several boxes at once (a moved object's old and new places, overlapping, and one
        // elsewhere, and an empty one): the union of what each box alone finds.
        for (int q = 0; q < 100; ++q) {
            const glm::vec3 lo(room(rng), room(rng), room(rng));
            const glm::vec3 extent(size(rng), size(rng), size(rng));
            const glm::vec3 elsewhere(room(rng), room(rng), room(rng));
            const std::vector<AxisBox> boxes{
                box_of(lo, lo + extent), box_of(lo + 0.1f * extent, lo + 1.1f * extent),
                box_of(elsewhere, elsewhere + extent), AxisBox{}};
            std::vector<std::uint32_t> expected;
            for (const AxisBox& box : boxes) {
                const std::vector<std::uint32_t> one = brute_force(groups, box);
                expected.insert(expected.end(), one.begin(), one.end());
            }
            std::sort(expected.begin(), expected.end());
            expected.erase(std::unique(expected.begin(), expected.end()), expected.end());
            EXPECT_EQ(index.groups_meeting(boxes), expected) << when << ", boxes " << q;
        }
        // The check compared something: most random boxes meet some group, not all meet all.
        EXPECT_GT(meeting, 100) << when;
    };
    check("after filling");

    // Replace some groups' paths and clear others: nothing stale may remain.
    for (std::uint32_t g = 0; g < kGroups; g += 3) {
        fill(g);
    }
    for (std::uint32_t g = 1; g < kGroups; g += 5) {
        groups[g].clear();
        index.clear_group(g);
    }
    check("after replacing and clearing");
    std::size_t segments = 0;
    for (const auto& g : groups) {
        segments += g.size();
    }
    EXPECT_EQ(index.segment_count(), segments);
    EXPECT_GT(index.bytes_used(), segments * sizeof(PathSegment));
}

TEST(PathSegmentIndex, PathSegmentsRunFromTheLightThroughEveryHop) {
    TracedGroup traced;
    traced.hops = {{glm::vec3(1.0f, 0.0f, 0.0f)},
                   {glm::vec3(1.0f, 1.0f, 0.0f)},
                   {glm::vec3(0.0f, 0.0f, 2.0f)}};
    traced.starts = {0, 2, 2, 3};  // photon 1 hit nothing
    traced.origins = {glm::vec3(0.0f), glm::vec3(5.0f), glm::vec3(0.0f, 0.0f, 1.0f)};
    const std::vector<PathSegment> segments = path_segments(traced);
    ASSERT_EQ(segments.size(), 3u);
    EXPECT_EQ(segments[0].from, glm::vec3(0.0f));
    EXPECT_EQ(segments[0].to, glm::vec3(1.0f, 0.0f, 0.0f));
    EXPECT_EQ(segments[1].from, glm::vec3(1.0f, 0.0f, 0.0f));
    EXPECT_EQ(segments[1].to, glm::vec3(1.0f, 1.0f, 0.0f));
    EXPECT_EQ(segments[2].from, glm::vec3(0.0f, 0.0f, 1.0f));
    EXPECT_EQ(segments[2].to, glm::vec3(0.0f, 0.0f, 2.0f));
}

}  // namespace
