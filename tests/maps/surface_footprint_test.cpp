// SurfaceFootprint's border distances: the linear distance transform against a brute-force
// search on small charts of random triangles, and a page-sized chart a search per texel could
// not finish.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <set>
#include <utility>

#include <gtest/gtest.h>

#include "luxel/lighting/core/surface_footprint.hpp"
#include "luxel/lighting/core/surface_texels.hpp"
#include "luxel/scene/texel_coverage.hpp"

namespace {

using namespace luxel;

/// Triangles with the given light-map corners (TEXCOORD_1, page units), standing in a plane.
scene::Primitive chart(const std::vector<glm::vec2>& uvs) {
    scene::Primitive primitive;
    for (std::size_t i = 0; i < uvs.size(); ++i) {
        primitive.positions.emplace_back(uvs[i].x, 0.0f, uvs[i].y);
        primitive.normals.emplace_back(0.0f, 1.0f, 0.0f);
        primitive.texcoords1.push_back(uvs[i]);
        primitive.indices.push_back(static_cast<std::uint32_t>(i));
    }
    return primitive;
}

/// The definition, searched over every cell: the distance from `point` to the nearest closed
/// unit square that no triangle's texel coverage touches. The footprint's grid is the chart's
/// bounding box, clipped to the page, with a cell of margin, and everything past it counts as
/// empty: covered cells are collected over the page and its margin, and the search runs a few
/// cells past that.
double brute_force_distance(const scene::Primitive& primitive, int page_size,
                            const glm::dvec2& point) {
    std::set<std::pair<int, int>> covered;
    for (std::size_t t = 0; t + 2 < primitive.indices.size(); t += 3) {
        const auto corner = [&](std::size_t k) {
            return glm::dvec2(primitive.texcoords1[primitive.indices[t + k]]) *
                   static_cast<double>(page_size);
        };
        scene::for_each_covered_texel(corner(0), corner(1), corner(2),
                                      {-1, -1, page_size + 1, page_size + 1},
                                      [&](int x, int y) { covered.emplace(x, y); });
    }
    double nearest = std::numeric_limits<double>::max();
    for (int y = -3; y < page_size + 3; ++y) {
        for (int x = -3; x < page_size + 3; ++x) {
            if (covered.count({x, y}) != 0) {
                continue;
            }
            const double dx = std::max({x - point.x, 0.0, point.x - (x + 1)});
            const double dy = std::max({y - point.y, 0.0, point.y - (y + 1)});
            nearest = std::min(nearest, std::sqrt(dx * dx + dy * dy));
        }
    }
    return nearest;
}

TEST(SurfaceFootprint, BorderDistancesMatchABruteForceSearch) {
    constexpr int kPage = 24;
    std::mt19937 random(7);
    std::uniform_real_distribution<float> inside(0.1f, 0.9f);
    // Every third chart runs off the page, where the grid stops and counts as empty.
    std::uniform_real_distribution<float> across(-0.3f, 1.3f);
    std::size_t centres = 0;
    std::size_t others = 0;
    for (int trial = 0; trial < 40; ++trial) {
        // 1 to 6 random triangles: overlapping, thin, disjoint, with holes between them.
        std::vector<glm::vec2> uvs;
        const int triangles = 1 + trial % 6;
        for (int k = 0; k < 3 * triangles; ++k) {
            auto& coordinate = trial % 3 == 2 ? across : inside;
            uvs.emplace_back(coordinate(random), coordinate(random));
        }
        const scene::Primitive primitive = chart(uvs);
        const lighting::SurfaceTexels texels = lighting::rasterize_surface(primitive, 0, kPage);
        const lighting::SurfaceFootprint footprint(primitive, texels);
        for (std::size_t i = 0; i < texels.texels.size(); ++i) {
            const glm::dvec2 point(texels.texels[i].page_point);
            const bool centre = point - glm::floor(point) == glm::dvec2(0.5);
            (centre ? centres : others) += 1;
            const auto expected = static_cast<float>(brute_force_distance(primitive, kPage, point));
            // Centres and border points alike: the same number as the search.
            ASSERT_EQ(footprint.border_distance(i), expected)
                << "trial " << trial << " texel " << i << " at " << point.x << ", " << point.y;
        }
    }
    // Both kinds of point were met (interior texels' centres, border texels' surface points).
    EXPECT_GT(centres, 1000u);
    EXPECT_GT(others, 100u);
}

TEST(SurfaceFootprint, APageSizedChartTakesLinearTime) {
    // One quad over a whole 1024^2 page: a million texels, most hundreds of texels from the
    // border. A ring search per texel visits the square of that distance (about 1e11 cells in
    // all); the transform visits each cell a few times.
    constexpr int kPage = 1024;
    const scene::Primitive primitive = chart({{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}});
    const lighting::SurfaceTexels texels = lighting::rasterize_surface(primitive, 0, kPage);
    ASSERT_EQ(texels.texels.size(), static_cast<std::size_t>(kPage) * kPage);
    const lighting::SurfaceFootprint footprint(primitive, texels);
    std::size_t wrong = 0;
    for (std::size_t i = 0; i < texels.texels.size(); ++i) {
        const lighting::SurfaceTexel& texel = texels.texels[i];
        // Every cell of the page is covered; the first empty ones are just off it.
        const int steps = std::min({texel.x, texel.y, kPage - 1 - texel.x, kPage - 1 - texel.y});
        wrong += footprint.border_distance(i) != static_cast<float>(steps) + 0.5f ? 1 : 0;
    }
    EXPECT_EQ(wrong, 0u);
    const std::size_t middle = (kPage / 2) * kPage + kPage / 2;
    EXPECT_EQ(footprint.border_distance(middle), 511.5f);
    EXPECT_DOUBLE_EQ(footprint.fraction(middle, 500.0), 1.0);
    EXPECT_LT(footprint.fraction(0, 10.0), 0.5);  // a corner
}

}  // namespace
