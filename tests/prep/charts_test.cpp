// Charts: planar projection where it is faithful, conformal maps where they do better, cuts
// where neither passes; bounds: no flipped or overlapping triangles, area stretch within 1.5.

#include <cmath>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "luxel/scene/gltf.hpp"
#include "mesh_builders.hpp"
#include "prep_test_support.hpp"

namespace {

using namespace luxel;

void expect_pages_sound(const prep::PrepResult& result, int padding = 1) {
    const luxel::testing::PageCheck check =
        luxel::testing::check_light_map_pages(result.scene, padding);
    EXPECT_TRUE(check.failures.empty()) << check.failures.front();
    EXPECT_EQ(check.texels, result.report.texels);
    EXPECT_EQ(check.surfaces, result.report.surfaces);
    EXPECT_EQ(check.charts, result.report.charts);
}

void expect_stretch_within_bounds(const prep::PrepResult& result, double bound = 1.5) {
    EXPECT_LE(result.report.stretch_max, bound);
    EXPECT_GE(result.report.stretch_min, 1.0 / bound);
    for (const auto& node : result.nodes) {
        for (const auto& chart : node.charts) {
            EXPECT_LE(chart.stretch_max, bound);
            EXPECT_GE(chart.stretch_min, 1.0 / bound);
        }
    }
}

TEST(Charts, FlatWallIsOnePlanarChartAtTheTexelSize) {
    // 2 m x 1 m at 5 cm: 40 x 20 texels, exact.
    const auto result = luxel::testing::run_prep(luxel::testing::single_mesh_scene(
        levels::make_quad({0, 0, 0}, {2, 0, 0}, {0, 1, 0}, 8, 4)));
    ASSERT_EQ(result.nodes.size(), 1u);
    ASSERT_EQ(result.nodes[0].charts.size(), 1u);
    const prep::Chart& chart = result.nodes[0].charts[0];
    EXPECT_EQ(chart.method, prep::ChartMethod::Planar);
    EXPECT_EQ(chart.width, 40);
    EXPECT_EQ(chart.height, 20);
    EXPECT_NEAR(chart.stretch_min, 1.0, 1e-3);
    EXPECT_NEAR(chart.stretch_max, 1.0, 1e-3);
    EXPECT_EQ(result.report.texels, 800);
    expect_pages_sound(result);
}

TEST(Charts, CoarseQuadOverTheBudgetStaysOneChart) {
    // A 4 x 4 m floor as modelling tools write it, one quad of two triangles: 6400 texels,
    // over the surface budget (1024), but cutting it gives two triangles, each in a rectangle
    // as large as the whole floor's (issue 22: Blender rooms packed at 43%).
    const auto coarse = luxel::testing::run_prep(luxel::testing::single_mesh_scene(
        levels::make_quad({0, 0, 0}, {4, 0, 0}, {0, 4, 0}, 1, 1)));
    EXPECT_EQ(coarse.report.charts, 1u);
    EXPECT_EQ(coarse.report.texels, 6400);
    EXPECT_GE(coarse.report.efficiency, 0.9);
    expect_pages_sound(coarse);
    // The same floor finely meshed is still cut to the budget: its halves are rectangles.
    const auto fine = luxel::testing::run_prep(luxel::testing::single_mesh_scene(
        levels::make_quad({0, 0, 0}, {4, 0, 0}, {0, 4, 0}, 16, 16)));
    EXPECT_GE(fine.report.surfaces, 7u);
    EXPECT_GE(fine.report.efficiency, 0.8);
    expect_pages_sound(fine);
}

TEST(Charts, OpenCylinderUnrollsConformally) {
    // The brass ring's shape: a tube cannot be one flat chart, but its pieces are developable,
    // so conformal maps flatten them with (almost) no stretch at all.
    const auto result = luxel::testing::run_prep(
        luxel::testing::single_mesh_scene(levels::make_open_cylinder(0.5f, 0.3f, 96)));
    EXPECT_EQ(result.report.crease_surfaces, 1u);
    EXPECT_GE(result.report.conformal_charts, 1u);
    EXPECT_LE(result.report.charts, 4u);
    EXPECT_LT(result.report.stretch_max / result.report.stretch_min, 1.1);
    expect_stretch_within_bounds(result);
    expect_pages_sound(result);
}

TEST(Charts, SphereChartsStayWithinTheStretchBound) {
    prep::PrepOptions options;
    options.texel_size = 0.02;
    const auto result = luxel::testing::run_prep(
        luxel::testing::single_mesh_scene(levels::make_sphere(0.5f, 48, 24)), options);
    EXPECT_GT(result.report.charts, 1u);
    EXPECT_LE(result.report.charts, 12u) << "cube-map-like pieces, not splinters";
    expect_stretch_within_bounds(result);
    expect_pages_sound(result);
}

TEST(Charts, SteepHillsAreCutUntilEveryPieceIsWithinBounds) {
    // Bumps 20 cm high, 50 cm apart: slopes up to 68 degrees, far from flat.
    const float frequency = 2.0f * glm::pi<float>() / 0.5f;
    const auto hills = levels::make_height_field(
        -1.0f, 1.0f, -1.0f, 1.0f, 0.0f, 48, 48,
        [=](float x, float z) { return 0.2f * std::sin(frequency * x) * std::sin(frequency * z); },
        [=](float x, float z) {
            return glm::vec2(0.2f * frequency * std::cos(frequency * x) * std::sin(frequency * z),
                             0.2f * frequency * std::sin(frequency * x) * std::cos(frequency * z));
        });
    prep::PrepOptions options;
    options.crease_degrees = 90.0;
    const auto result = luxel::testing::run_prep(luxel::testing::single_mesh_scene(hills), options);
    EXPECT_EQ(result.report.crease_surfaces, 1u);
    expect_stretch_within_bounds(result);
    expect_pages_sound(result);
}

TEST(Charts, SpiralRampIsCutWhereItsProjectionWouldOverlap) {
    // Two turns of a gently rising helicoid: every normal is within 10 degrees of up, so a
    // planar projection keeps the stretch, but the turns would land on top of each other.
    scene::Primitive ramp;
    constexpr int kAround = 96;
    constexpr int kAcross = 4;
    for (int i = 0; i <= kAround; ++i) {
        const float angle = 4.0f * glm::pi<float>() * static_cast<float>(i) / kAround;
        for (int j = 0; j <= kAcross; ++j) {
            const float radius = 1.0f + static_cast<float>(j) / kAcross;
            ramp.positions.emplace_back(radius * std::cos(angle), 0.25f * angle / glm::pi<float>(),
                                        -radius * std::sin(angle));
        }
    }
    for (int i = 0; i < kAround; ++i) {
        for (int j = 0; j < kAcross; ++j) {
            const auto a = static_cast<std::uint32_t>(i * (kAcross + 1) + j);
            const auto b = a + 1;
            const auto c = a + kAcross + 1;
            const auto d = c + 1;
            ramp.indices.insert(ramp.indices.end(), {a, c, b, b, c, d});
        }
    }
    const auto result = luxel::testing::run_prep(luxel::testing::single_mesh_scene(ramp));
    EXPECT_EQ(result.report.crease_surfaces, 1u);
    EXPECT_GT(result.report.charts, 1u);
    expect_stretch_within_bounds(result);
    expect_pages_sound(result);
}

TEST(Charts, ChartsWiderThanAPageAreCut) {
    // A corridor wall 20 m long: 400 texels, on pages of 128.
    prep::PrepOptions options;
    options.page_size = 128;
    options.surface_texel_budget = 1e9;
    const auto result =
        luxel::testing::run_prep(luxel::testing::single_mesh_scene(
                                     levels::make_quad({0, 0, 0}, {20, 0, 0}, {0, 1, 0}, 80, 4)),
                                 options);
    EXPECT_GE(result.report.charts, 4u);
    for (const auto& chart : result.nodes.at(0).charts) {
        EXPECT_LE(chart.width + 2, 128);
        EXPECT_LE(chart.height + 2, 128);
    }
    EXPECT_EQ(result.page_size, 128);
    expect_pages_sound(result);
}

TEST(Charts, SurfacesSplitWhereASmallPageCannotHoldThem) {
    // 40-texel pages: the Cornell walls' 40 x 40 texels are cut to fit, and surfaces of
    // several charts that would not fit one page together become several surfaces.
    prep::PrepOptions options;
    options.page_size = 40;
    const auto result =
        luxel::testing::run_prep(scene::load_gltf(luxel::testing::level_file("cornell")), options);
    EXPECT_EQ(result.page_size, 40);
    EXPECT_GT(result.page_count, 1);
    expect_pages_sound(result);
}

TEST(Charts, PaddingIsHonouredAtLargerWidths) {
    prep::PrepOptions options;
    options.padding = 3;
    const auto result = luxel::testing::run_prep(
        luxel::testing::single_mesh_scene(levels::make_box(glm::vec3(1.0f, 0.5f, 0.3f))), options);
    EXPECT_EQ(result.report.surfaces, 6u);
    expect_pages_sound(result, 3);
}

}  // namespace
