// PathCells: where a caustic list's photon paths went, coarsely. Checked against the exact
// segment-box test of the global photons' index: a box a segment meets must always be met.

#include <array>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "luxel/lighting/core/path_cells.hpp"
#include "luxel/lighting/core/path_segment_index.hpp"

namespace {

using namespace luxel::lighting;

AxisBox box(const glm::vec3& lo, const glm::vec3& hi) {
    const std::array<glm::vec3, 2> corners{lo, hi};
    return box_around(corners);
}

const AxisBox kRoom = box({-4.0f, 0.0f, -4.0f}, {4.0f, 4.0f, 4.0f});  // cells of 0.5 x 0.25 x 0.5

TEST(PathCells, ASegmentMeetsTheBoxesAlongItAndNotThoseBesideIt) {
    PathCells cells(kRoom);
    EXPECT_TRUE(cells.empty());
    cells.add_segment({-3.0f, 1.0f, 0.2f}, {3.0f, 3.0f, 0.2f});
    EXPECT_FALSE(cells.empty());
    EXPECT_FALSE(cells.outside());
    EXPECT_TRUE(cells.meets(box({-0.1f, 1.9f, 0.1f}, {0.1f, 2.1f, 0.3f})));  // its middle
    EXPECT_TRUE(cells.meets(box({2.9f, 2.9f, 0.1f}, {3.1f, 3.1f, 0.3f})));   // its end
    EXPECT_FALSE(cells.meets(box({-0.2f, 0.1f, 0.1f}, {0.2f, 0.6f, 0.3f})))
        << "a crate on the floor under the path";
    EXPECT_FALSE(cells.meets(box({-1.0f, 1.0f, 2.0f}, {1.0f, 3.0f, 3.0f}))) << "beside it in z";
    EXPECT_FALSE(cells.meets(AxisBox{})) << "an empty box meets nothing";
    // A box wholly outside the region: no path went outside, so nothing there was crossed.
    EXPECT_FALSE(cells.meets(box({10.0f, 1.0f, 0.0f}, {11.0f, 2.0f, 1.0f})));
}

TEST(PathCells, AnEscapedPathMeetsEveryBoxThatLeavesTheRegion) {
    PathCells cells(kRoom);
    cells.add_segment({0.0f, 1.0f, 0.0f}, glm::vec3(0.0f, 1.0f, 0.0f) + 1e6f * glm::vec3(0, 0, 1));
    EXPECT_TRUE(cells.outside());
    EXPECT_TRUE(cells.meets(box({-0.1f, 0.9f, 3.0f}, {0.1f, 1.1f, 3.5f})));
    EXPECT_TRUE(cells.meets(box({10.0f, 1.0f, 0.0f}, {11.0f, 2.0f, 1.0f})))
        << "somewhere outside: the path may have gone there";
    EXPECT_FALSE(cells.meets(box({-3.0f, 3.0f, -3.0f}, {-2.0f, 3.5f, -2.0f})));
    // A beam that starts outside (a directional light's) is clipped to the region.
    PathCells beam(kRoom);
    beam.add_segment({1.0f, 100.0f, 1.0f}, {1.0f, 0.0f, 1.0f});
    EXPECT_TRUE(beam.outside());
    EXPECT_TRUE(beam.meets(box({0.9f, 3.8f, 0.9f}, {1.1f, 3.9f, 1.1f})));
    EXPECT_FALSE(beam.meets(box({-1.1f, 1.0f, -1.1f}, {-0.9f, 2.0f, -0.9f})));
}

TEST(PathCells, ClearMergeAndNoRegion) {
    PathCells a(kRoom);
    PathCells b(kRoom);
    a.add_segment({-3.0f, 1.0f, -3.0f}, {-3.0f, 1.0f, 3.0f});
    b.add_segment({3.0f, 1.0f, -3.0f}, {3.0f, 1.0f, 3.0f});
    const AxisBox near_b = box({2.9f, 0.9f, -0.1f}, {3.1f, 1.1f, 0.1f});
    EXPECT_FALSE(a.meets(near_b));
    a.merge(b);
    EXPECT_TRUE(a.meets(near_b));
    a.clear();
    EXPECT_TRUE(a.empty());
    EXPECT_FALSE(a.meets(near_b));
    EXPECT_EQ(a.region().min, kRoom.min) << "clear keeps the region";

    // Without a region every recorded path is "outside": any box meets, as before path cells.
    PathCells none;
    EXPECT_FALSE(none.meets(near_b));
    none.add_segment({0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f});
    EXPECT_TRUE(none.meets(box({50.0f, 50.0f, 50.0f}, {51.0f, 51.0f, 51.0f})));
    // Non-finite ends count as outside, they do not poison the cells.
    PathCells hostile(kRoom);
    hostile.add_segment({0.0f, 1.0f, 0.0f}, {std::numeric_limits<float>::quiet_NaN(), 1.0f, 0.0f});
    EXPECT_TRUE(hostile.outside());
    EXPECT_FALSE(hostile.meets(box({-1.0f, 0.5f, -1.0f}, {1.0f, 1.5f, 1.0f})));
}

TEST(PathCells, NeverMissesABoxASegmentMeets) {
    // Random segments (some leaving the room, some on cell boundaries) against random boxes:
    // wherever the exact slab test says a segment meets a box, the cells must say so too; and
    // the cells must not be so coarse that they meet nearly everything.
    std::mt19937 random(7);
    std::uniform_real_distribution<float> coordinate(-5.0f, 5.0f);
    std::uniform_real_distribution<float> size(0.05f, 1.0f);
    std::uniform_int_distribution<int> grid(-8, 8);
    std::uniform_real_distribution<float> inside(-4.0f, 3.0f);
    int met = 0;
    int false_alarms = 0;
    int quiet = 0;
    for (int trial = 0; trial < 400; ++trial) {
        PathCells cells(kRoom);
        std::vector<PathSegment> segments;
        for (int s = 0; s < 3; ++s) {
            PathSegment segment{
                {coordinate(random), coordinate(random) * 0.5f + 2.0f, coordinate(random)},
                {coordinate(random), coordinate(random) * 0.5f + 2.0f, coordinate(random)}};
            if (s == 2) {
                // On cell boundaries: x and z at multiples of 0.5 m, y of 0.25 m.
                segment.from = {0.5f * grid(random), 0.25f * (grid(random) + 8),
                                0.5f * grid(random)};
                segment.to = {segment.from.x, 0.25f * (grid(random) + 8), 0.5f * grid(random)};
            }
            cells.add_segment(segment.from, segment.to);
            segments.push_back(segment);
        }
        for (int q = 0; q < 20; ++q) {
            // Inside the room: a box reaching outside meets any path that escaped.
            const glm::vec3 lo(inside(random), 0.375f * (inside(random) + 4.0f), inside(random));
            const AxisBox query = box(lo, lo + glm::vec3(size(random), size(random), size(random)));
            bool exact = false;
            for (const PathSegment& segment : segments) {
                exact = exact || segment_meets_box(segment, query);
            }
            const bool coarse = cells.meets(query);
            if (exact) {
                ++met;
                EXPECT_TRUE(coarse) << "trial " << trial << ", query " << q;
            } else if (coarse) {
                ++false_alarms;
            } else {
                ++quiet;
            }
        }
    }
    EXPECT_GT(met, 100);
    EXPECT_GT(quiet, false_alarms) << "the cells still tell most boxes a path misses apart";
}

}  // namespace
