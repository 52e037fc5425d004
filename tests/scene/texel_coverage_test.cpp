// The light-map rasterizer luxel-prep and the lighting system share: conservative coverage, and
// a window that bounds the work whatever the UVs (a hostile file's TEXCOORD_1 may span
// thousands of pages).

#include <set>
#include <utility>

#include <gtest/gtest.h>

#include "luxel/scene/texel_coverage.hpp"

namespace {

using luxel::scene::for_each_covered_texel;

std::set<std::pair<int, int>> covered(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c,
                                      const luxel::scene::TexelWindow& window) {
    std::set<std::pair<int, int>> texels;
    for_each_covered_texel(a, b, c, window, [&](int x, int y) {
        EXPECT_TRUE(texels.emplace(x, y).second) << "visited twice: " << x << "," << y;
    });
    return texels;
}

TEST(TexelCoverage, ConservativeCoverageOfATriangle) {
    // The diagonal from (2, 0) to (0, 2) touches texel (1, 1) at a corner only.
    const auto texels = covered({0, 0}, {2, 0}, {0, 2}, {0, 0, 8, 8});
    EXPECT_EQ(texels, (std::set<std::pair<int, int>>{{0, 0}, {1, 0}, {0, 1}}));
    // Either winding.
    EXPECT_EQ(covered({0, 0}, {0, 2}, {2, 0}, {0, 0, 8, 8}), texels);
    // Zero area covers nothing.
    EXPECT_TRUE(covered({0, 0}, {1, 1}, {2, 2}, {0, 0, 8, 8}).empty());
}

TEST(TexelCoverage, TheWindowBoundsTheWork) {
    // A triangle spanning far more than a page (and than an int) visits only the window.
    const auto texels = covered({-1e30, -1e30}, {1e30, -1e30}, {0.0, 1e30}, {0, 0, 4, 4});
    EXPECT_EQ(texels.size(), 16u);
    // A window that holds only part of a triangle clips it.
    const auto part = covered({0, 0}, {4, 0}, {0, 4}, {2, 0, 4, 4});
    for (const auto& [x, y] : part) {
        EXPECT_GE(x, 2);
    }
    EXPECT_EQ(part, (std::set<std::pair<int, int>>{{2, 0}, {3, 0}, {2, 1}}));
    // A window with negative corners (luxel-prep counts spills beyond its mask).
    EXPECT_EQ(covered({-2, 0}, {0, 0}, {-2, 2}, {-4, -4, 4, 4}).size(), 3u);
    // Nothing inside the window: nothing visited.
    EXPECT_TRUE(covered({10, 10}, {12, 10}, {10, 12}, {0, 0, 4, 4}).empty());
}

}  // namespace
