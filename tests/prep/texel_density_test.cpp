// Texel sizes that fit each object (tools/prep texel_density.hpp, issue 22): a prop's width
// keeps its texels, a slab's thickness does not count, an author's texel_scale in the node's
// extras, and a level-wide texel budget.

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "luxel/prep/texel_density.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/scene/lightmap_layout.hpp"
#include "mesh_builders.hpp"
#include "prep_test_support.hpp"

namespace {

using namespace luxel;

prep::NodeExtent extent(glm::dvec3 size, double scale = 1.0) {
    prep::NodeExtent e;
    e.size = size;
    // A box's area: what the budget counts.
    e.area = 2.0 * (size.x * size.y + size.y * size.z + size.z * size.x);
    e.texel_scale = scale;
    return e;
}

TEST(TexelDensity, APropsWidthKeepsItsTexelsAndASlabsThicknessDoesNotCount) {
    prep::PrepOptions options;  // 5 cm texels, 4 across
    const std::vector<prep::NodeExtent> nodes = {
        extent({0.04, 0.40, 0.04}),   // a lamp stem: 4 cm wide -> 1 cm texels
        extent({1.20, 0.02, 0.80}),   // a table top 2 cm thick: 80 cm wide, keeps 5 cm
        extent({4.00, 2.60, 3.00}),   // a room
        extent({0.002, 0.002, 1.0}),  // a 2 mm wire: at most eight times finer
    };
    const std::vector<double> sizes = prep::node_texel_sizes(nodes, options);
    ASSERT_EQ(sizes.size(), nodes.size());
    EXPECT_DOUBLE_EQ(sizes[0], 0.01);
    EXPECT_DOUBLE_EQ(sizes[1], 0.05);
    EXPECT_DOUBLE_EQ(sizes[2], 0.05);
    EXPECT_DOUBLE_EQ(sizes[3], 0.05 / 8.0);

    options.min_texels_across = 0;  // off: one size for all
    for (const double size : prep::node_texel_sizes(nodes, options)) {
        EXPECT_DOUBLE_EQ(size, 0.05);
    }
}

TEST(TexelDensity, TheAuthorsScaleAndTheBudget) {
    prep::PrepOptions options;
    options.min_texels_across = 0;
    const std::vector<prep::NodeExtent> nodes = {extent({2, 2, 2}, 2.0), extent({2, 2, 2}, 0.5)};
    std::vector<double> sizes = prep::node_texel_sizes(nodes, options);
    EXPECT_DOUBLE_EQ(sizes[0], 0.1);
    EXPECT_DOUBLE_EQ(sizes[1], 0.025);

    // 24 m^2 at 0.1 m and at 0.025 m: 2,400 + 38,400 texels; a budget of half of that makes
    // both sqrt(2) coarser, keeping their ratio.
    const double texels = 24.0 / (0.1 * 0.1) + 24.0 / (0.025 * 0.025);
    options.texel_budget = static_cast<std::uint64_t>(texels / 2.0);
    sizes = prep::node_texel_sizes(nodes, options);
    // (the budget is a whole number of texels: within 1e-4)
    EXPECT_NEAR(sizes[0], 0.1 * std::sqrt(2.0), 1e-4 * sizes[0]);
    EXPECT_NEAR(sizes[1], 0.025 * std::sqrt(2.0), 1e-4 * sizes[1]);
    EXPECT_NEAR(24.0 / (sizes[0] * sizes[0]) + 24.0 / (sizes[1] * sizes[1]),
                static_cast<double>(options.texel_budget), 1.0);
    // A budget the level is within changes nothing.
    options.texel_budget = static_cast<std::uint64_t>(texels * 2.0);
    EXPECT_DOUBLE_EQ(prep::node_texel_sizes(nodes, options)[0], 0.1);
}

TEST(TexelDensity, ATexelScaleOutOfRangeNamesTheNode) {
    scene::Node node;
    EXPECT_DOUBLE_EQ(prep::texel_scale_of(node, "node 3 'Lamp'"), 1.0);
    node.flags.raw["texel_scale"] = 0.25;
    EXPECT_DOUBLE_EQ(prep::texel_scale_of(node, "node 3 'Lamp'"), 0.25);
    for (const nlohmann::json& bad : {nlohmann::json(0.0), nlohmann::json(-1.0),
                                      nlohmann::json(100.0), nlohmann::json("fine")}) {
        node.flags.raw["texel_scale"] = bad;
        try {
            (void)prep::texel_scale_of(node, "node 3 'Lamp'");
            ADD_FAILURE() << "accepted " << bad.dump();
        } catch (const Error& e) {
            const std::string message = e.what();
            EXPECT_NE(message.find("node 3 'Lamp'"), std::string::npos) << message;
            EXPECT_NE(message.find("texel_scale"), std::string::npos) << message;
        }
    }
}

TEST(TexelDensity, EachNodesLayoutRecordsItsOwnSizeAndTheScaleSurvives) {
    // A 1 m box at texel_scale 2 and a 6 cm post beside it, 4 texels across by default.
    scene::Scene level =
        luxel::testing::single_mesh_scene(levels::make_box(glm::vec3(1.0f)), "box");
    level.nodes[0].flags.raw["texel_scale"] = 2.0;
    scene::Primitive post = levels::make_box(glm::vec3(0.06f, 1.0f, 0.06f));
    post.material = 0;
    luxel::testing::add_mesh_node(level, "post", std::move(post), {2.0f, 0.0f, 0.0f});

    const prep::PrepResult result = luxel::testing::run_prep(level, prep::PrepOptions{}, 2);
    const auto box = scene::read_lightmap_layout(result.scene.nodes[0].flags.raw);
    const auto stem = scene::read_lightmap_layout(result.scene.nodes[1].flags.raw);
    ASSERT_TRUE(box && stem);
    EXPECT_FLOAT_EQ(box->texel_size, 0.1f);
    EXPECT_FLOAT_EQ(stem->texel_size, 0.015f);
    EXPECT_DOUBLE_EQ(result.scene.nodes[0].flags.raw.at("texel_scale").get<double>(), 2.0);
    // The box's 6 m^2 at 10 cm: 600 texels, within the chart rounding.
    std::int64_t box_texels = 0;
    for (const scene::LightmapSurface& surface : box->surfaces) {
        box_texels += surface.texels;
    }
    EXPECT_GE(box_texels, 600);
    EXPECT_LE(box_texels, 900);
    ASSERT_EQ(result.report.nodes.size(), 2u);
    EXPECT_NEAR(result.report.nodes[1].texel_size, 0.015, 1e-8);  // a float box's width / 4
}

}  // namespace
