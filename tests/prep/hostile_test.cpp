// Hostile input for luxel-prep: non-manifold edges and vertices, degenerate and zero-area
// faces, missing normals, isolated vertices, a million triangles, an empty scene. Each ends in
// a repaired, valid output or a clear error, never a crash.

#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "luxel/runtime/clock.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/scene/gltf.hpp"
#include "mesh_builders.hpp"
#include "prep_test_support.hpp"

namespace {

using namespace luxel;

/// Saves and reloads the prepared scene (the writer and loader validate everything) and checks
/// its pages.
void expect_valid_output(const prep::PrepResult& result, int padding = 1) {
    const auto bytes = scene::save_gltf_to_memory(result.scene, scene::GltfContainer::Binary);
    const scene::Scene reloaded = scene::load_gltf_from_memory(bytes, "prepared");
    const luxel::testing::PageCheck check =
        luxel::testing::check_light_map_pages(reloaded, padding);
    EXPECT_TRUE(check.failures.empty()) << check.failures.front();
}

std::size_t output_triangles(const prep::PrepResult& result) {
    std::size_t n = 0;
    for (const auto& mesh : result.scene.meshes) {
        for (const auto& p : mesh.primitives) {
            n += p.triangle_count();
        }
    }
    return n;
}

TEST(Hostile, NonManifoldEdgesAndVerticesAreSplitOff) {
    scene::Primitive p;
    // A fin: three triangles on the edge (0,1); a fourth with the edge's winding reversed twice
    // over; and two fans meeting only at vertex 5 (a bow tie).
    p.positions = {{0, 0, 0}, {1, 0, 0}, {0.5f, 1, 0}, {0.5f, -1, 0}, {0.5f, 0, 1},
                   {3, 0, 0}, {4, 1, 0}, {4, -1, 0},   {2, 1, 0},     {2, -1, 0}};
    p.indices = {0, 1, 2, 1, 0, 3, 0, 1, 4,  // three faces on edge 0-1, one of them wound
                                             // the same way as the first
                 5, 6, 7, 5, 8, 9};          // the bow tie
    const auto result = luxel::testing::run_prep(luxel::testing::single_mesh_scene(p));
    EXPECT_GT(result.report.repairs.non_manifold_faces, 0u);
    EXPECT_FALSE(result.report.warnings.empty());
    EXPECT_EQ(output_triangles(result), 5u);
    expect_valid_output(result);
}

TEST(Hostile, DegenerateAndZeroAreaFacesAreDropped) {
    scene::Primitive p = levels::make_quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 2, 2);
    const auto base = static_cast<std::uint32_t>(p.positions.size());
    // Collinear corners, two corners on one spot, and a needle a picometre wide.
    p.positions.insert(p.positions.end(), {{0, 0, 1},
                                           {1, 0, 1},
                                           {2, 0, 1},
                                           {5, 5, 5},
                                           {5, 5, 5},
                                           {0, 2, 0},
                                           {1e-12f, 3, 0},
                                           {0, 4, 0}});
    p.normals.resize(p.positions.size(), glm::vec3(0, 0, 1));
    p.texcoords0.resize(p.positions.size(), glm::vec2(0.0f));
    p.indices.insert(p.indices.end(), {base, base + 1, base + 2, base + 3, base + 4, 0, base + 5,
                                       base + 6, base + 7, 0, 0, 1});
    const auto result = luxel::testing::run_prep(luxel::testing::single_mesh_scene(p));
    EXPECT_EQ(result.report.repairs.degenerate_faces, 4u);
    EXPECT_EQ(output_triangles(result), 8u);
    expect_valid_output(result);
}

TEST(Hostile, MissingNormalsAreComputedPerSurface) {
    scene::Primitive box = levels::make_box(glm::vec3(1.0f));
    box.normals.clear();
    scene::Scene s = luxel::testing::single_mesh_scene(box);
    s.nodes[0].scale = {2.0f, 1.0f, 1.0f};  // normals come back in the node's own space
    s.nodes[0].rotation = glm::angleAxis(0.5f, glm::vec3(0, 1, 0));
    const auto result = luxel::testing::run_prep(s);
    EXPECT_EQ(result.report.repairs.faces_without_normals, 12u);
    for (const auto& p : result.scene.meshes[0].primitives) {
        ASSERT_EQ(p.normals.size(), p.positions.size());
        for (std::size_t t = 0; t < p.indices.size(); t += 3) {
            const glm::vec3 a = p.positions[p.indices[t]];
            const glm::vec3 face = glm::normalize(
                glm::cross(p.positions[p.indices[t + 1]] - a, p.positions[p.indices[t + 2]] - a));
            for (std::size_t k = 0; k < 3; ++k) {
                const glm::vec3 n = p.normals[p.indices[t + k]];
                EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
                // Each cube face is its own surface: flat, sharp-edged normals.
                EXPECT_GT(glm::dot(n, face), 0.999f);
            }
        }
    }
    expect_valid_output(result);
}

TEST(Hostile, IsolatedVerticesAreLeftOut) {
    scene::Primitive p = levels::make_quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 1, 1);
    p.positions.push_back({9, 9, 9});
    p.normals.push_back({0, 0, 1});
    p.texcoords0.push_back({0, 0});
    const auto result = luxel::testing::run_prep(luxel::testing::single_mesh_scene(p));
    EXPECT_EQ(result.report.repairs.isolated_vertices, 1u);
    EXPECT_EQ(result.scene.meshes[0].primitives[0].positions.size(), 4u);
    expect_valid_output(result);
}

TEST(Hostile, EmptySceneAndSceneWithoutLightMappedMeshes) {
    const auto empty = luxel::testing::run_prep(scene::Scene{});
    EXPECT_EQ(empty.report.surfaces, 0u);
    EXPECT_EQ(empty.report.pages, 0);
    EXPECT_FALSE(empty.report.warnings.empty());
    EXPECT_TRUE(empty.scene.nodes.empty());

    scene::Scene mirror =
        luxel::testing::single_mesh_scene(levels::make_quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}));
    mirror.materials[0].metallic = 1.0f;
    mirror.materials[0].roughness = 0.0f;
    const auto result = luxel::testing::run_prep(mirror);
    EXPECT_EQ(result.report.surfaces, 0u);
    EXPECT_FALSE(result.scene.nodes[0].flags.raw.contains("lightmap"));
    (void)scene::save_gltf_to_memory(result.scene, scene::GltfContainer::Binary);
}

TEST(Hostile, AMillionTrianglesFinishInSeconds) {
    // 708 x 707 cells of rolling hills: 1,001,112 triangles over 20 x 20 m.
    const float frequency = 2.0f * glm::pi<float>() / 3.0f;
    const scene::Primitive hills = levels::make_height_field(
        -10.0f, 10.0f, -10.0f, 10.0f, 0.0f, 708, 707,
        [=](float x, float z) { return 0.2f * std::sin(frequency * x) * std::cos(frequency * z); },
        [=](float x, float z) {
            return glm::vec2(0.2f * frequency * std::cos(frequency * x) * std::cos(frequency * z),
                             -0.2f * frequency * std::sin(frequency * x) * std::sin(frequency * z));
        });
    ASSERT_GE(hills.triangle_count(), 1'000'000u);
    prep::PrepOptions options;
    options.texel_size = 0.1;
    Stopwatch stopwatch;
    const auto result = luxel::testing::run_prep(luxel::testing::single_mesh_scene(hills), options);
    EXPECT_EQ(result.report.triangles, hills.triangle_count());
    EXPECT_GE(result.report.efficiency, 0.7);
    EXPECT_LE(result.report.stretch_max, 1.5);
    std::cout << "1,001,112 triangles prepared in " << stopwatch.elapsed_ms() << " ms:";
    for (const auto& [stage, ms] : result.report.stage_ms) {
        std::cout << " " << stage << " " << ms << " ms";
    }
    std::cout << "\n";
}

TEST(Hostile, ThousandsOfTinyObjectsPackQuickly) {
    // 2,000 separate 10 cm cubes in one mesh: 12,000 surfaces of 2 x 2 texels each.
    scene::Primitive cubes;
    for (int i = 0; i < 2000; ++i) {
        scene::Primitive cube = levels::make_box(glm::vec3(0.1f));
        for (auto& p : cube.positions) {
            p += glm::vec3(static_cast<float>(i % 100) * 0.2f, 0.0f,
                           static_cast<float>(i / 100) * 0.2f);
        }
        levels::append(cubes, cube);
    }
    Stopwatch stopwatch;
    const auto result = luxel::testing::run_prep(luxel::testing::single_mesh_scene(cubes));
    EXPECT_EQ(result.report.surfaces, 12000u);
    expect_valid_output(result);
    // Two by two texels with a texel of padding all round: a quarter of the page is covered.
    EXPECT_NEAR(result.report.efficiency, 0.25, 0.01);
    EXPECT_EQ(result.report.pages, 1);
    std::cout << "12,000 surfaces prepared in " << stopwatch.elapsed_ms() << " ms:";
    for (const auto& [stage, ms] : result.report.stage_ms) {
        std::cout << " " << stage << " " << ms << " ms";
    }
    std::cout << "\n";
}

TEST(Hostile, ImpossibleRequestsAreClearErrors) {
    const scene::Scene wall = luxel::testing::single_mesh_scene(
        levels::make_quad({0, 0, 0}, {100, 0, 0}, {0, 100, 0}, 1, 1));
    auto expect_error = [&](const prep::PrepOptions& options, const std::string& mention) {
        try {
            (void)luxel::testing::run_prep(wall, options);
            ADD_FAILURE() << "no error; expected one naming " << mention;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(mention), std::string::npos) << e.what();
        }
    };
    prep::PrepOptions huge_triangle;  // two triangles 100 m across on 64-texel pages
    huge_triangle.page_size = 64;
    expect_error(huge_triangle, "--texel-size");
    prep::PrepOptions tiny_texels;  // 10^10 texels
    tiny_texels.texel_size = 0.001;
    expect_error(tiny_texels, "--texel-size");
    prep::PrepOptions bad;
    bad.texel_size = -1.0;
    expect_error(bad, "--texel-size");
    bad = {};
    bad.crease_degrees = 200.0;
    expect_error(bad, "--crease-deg");
    bad = {};
    bad.padding = -1;
    expect_error(bad, "--padding");
    bad = {};
    bad.page_size = 2;
    expect_error(bad, "--page-size");
}

/// What prepare() threw, or "" when it succeeded.
std::string prep_error(const scene::Scene& input, const prep::PrepOptions& options) {
    try {
        (void)luxel::testing::run_prep(input, options);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

/// `pieces` separate triangles 1 m apart along x: each is a surface of its own.
scene::Primitive separate_triangles(int pieces) {
    scene::Primitive p;
    for (int i = 0; i < pieces; ++i) {
        const auto x = static_cast<float>(2 * i);
        const auto base = static_cast<std::uint32_t>(p.positions.size());
        p.positions.insert(p.positions.end(), {{x, 0, 0}, {x + 1, 0, 0}, {x, 1, 0}});
        p.indices.insert(p.indices.end(), {base, base + 1, base + 2});
    }
    return p;
}

// luxel-prep copies every node's mesh: a few thousand nodes sharing one large mesh are
// counted, node by node, against prep-triangles before the first copy is made.
TEST(Hostile, TrianglesCopiedPerNodeAreCheckedBeforeCopying) {
    scene::Scene input = luxel::testing::single_mesh_scene(separate_triangles(10));
    for (int i = 1; i < 3; ++i) {  // three nodes draw the mesh: 30 triangles to copy
        scene::Node& node = input.nodes.emplace_back(input.nodes.front());
        node.name = "copy " + std::to_string(i);
        node.translation.z = static_cast<float>(i);
        input.roots.push_back(static_cast<int>(input.nodes.size()) - 1);
    }
    prep::PrepOptions options;
    options.max_triangles = 29;
    const std::string error = prep_error(input, options);
    EXPECT_NE(error.find("prep-triangles"), std::string::npos) << error;
    EXPECT_NE(error.find("30 triangles"), std::string::npos) << error;
    options.max_triangles = 30;
    EXPECT_EQ(prep_error(input, options), "");
}

// Every surface is a primitive of four or more accessors; a file with more than the loaders'
// `elements` limit would be refused by every tool, so luxel-prep refuses to write it.
TEST(Hostile, SurfacesBeyondTheAccessorLimitAreRefused) {
    const scene::Scene input = luxel::testing::single_mesh_scene(separate_triangles(10));
    prep::PrepOptions options;
    options.max_accessors = 10 * prep::kAccessorsPerSurface - 1;
    const std::string error = prep_error(input, options);
    EXPECT_NE(error.find("elements"), std::string::npos) << error;
    EXPECT_NE(error.find("10 light-mapped surfaces"), std::string::npos) << error;
    options.max_accessors = 10 * prep::kAccessorsPerSurface;
    EXPECT_EQ(prep_error(input, options), "");
}

// The loaders count light-map texels over whole pages: charts within the limit can need pages
// beyond it once packed, and luxel-prep must not write such a level.
TEST(Hostile, PagesBeyondTheTexelLimitAreRefused) {
    // A 0.5 m square at 0.05 m texels: 10 x 10 texels, 12 x 12 padded, on a 64^2 page.
    const scene::Scene input = luxel::testing::single_mesh_scene(
        levels::make_quad({0, 0, 0}, {0.5f, 0, 0}, {0, 0.5f, 0}, 1, 1));
    prep::PrepOptions options;
    options.page_size = 64;
    options.max_total_texels = 64 * 64 - 1;
    const std::string error = prep_error(input, options);
    EXPECT_NE(error.find("pages (1 of 64^2)"), std::string::npos) << error;
    EXPECT_NE(error.find("lightmap-texels"), std::string::npos) << error;
    options.max_total_texels = 64 * 64;
    EXPECT_EQ(prep_error(input, options), "");
}

}  // namespace
