// Surfaces (docs/METHOD.md §3.1): faces of one material joined across edges flatter than the
// crease angle, split further by the texel budget.

#include <cmath>
#include <iostream>
#include <numeric>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "luxel/prep/surfaces.hpp"
#include "mesh_builders.hpp"
#include "prep_test_support.hpp"

namespace {

using namespace luxel;

prep::NodeGeometry geometry_of(const scene::Primitive& primitive) {
    const scene::Scene s = luxel::testing::single_mesh_scene(primitive);
    return prep::build_geometry(s.meshes[0], s.materials, glm::dmat4(1.0), false);
}

/// The Cornell box's bumpy floor (tools/levels): bumps 1.5 cm high, 40 cm apart.
scene::Primitive bumpy_floor(int cells) {
    constexpr float amplitude = 0.015f;
    const float frequency = 2.0f * glm::pi<float>() / 0.4f;
    return levels::make_height_field(
        -1.0f, 1.0f, -1.0f, 1.0f, 0.0f, cells, cells,
        [=](float x, float z) {
            return amplitude * std::sin(frequency * x) * std::sin(frequency * z);
        },
        [=](float x, float z) {
            return glm::vec2(
                amplitude * frequency * std::cos(frequency * x) * std::sin(frequency * z),
                amplitude * frequency * std::sin(frequency * x) * std::cos(frequency * z));
        });
}

/// The definition of crease surfaces, checked edge by edge: faces joined by a connected edge
/// share a surface, and every surface is held together by connected edges alone.
void expect_components_of_connected_edges(const prep::NodeGeometry& geometry,
                                          const std::vector<prep::CreaseSurface>& surfaces,
                                          double crease_degrees) {
    std::vector<int> surface_of(geometry.faces.size(), -1);
    for (std::size_t s = 0; s < surfaces.size(); ++s) {
        for (const int f : surfaces[s].faces) {
            ASSERT_EQ(surface_of[static_cast<std::size_t>(f)], -1) << "face in two surfaces";
            surface_of[static_cast<std::size_t>(f)] = static_cast<int>(s);
        }
    }
    const double cos_crease = std::cos(glm::radians(crease_degrees));
    auto connected = [&](int a, int b) {
        const prep::Face& fa = geometry.faces[static_cast<std::size_t>(a)];
        const prep::Face& fb = geometry.faces[static_cast<std::size_t>(b)];
        return fa.material == fb.material && glm::dot(fa.normal, fb.normal) > cos_crease;
    };
    for (std::size_t f = 0; f < geometry.faces.size(); ++f) {
        ASSERT_GE(surface_of[f], 0) << "face " << f << " in no surface";
        for (const int n : geometry.faces[f].neighbours) {
            if (n >= 0 && connected(static_cast<int>(f), n)) {
                EXPECT_EQ(surface_of[f], surface_of[static_cast<std::size_t>(n)]);
            }
        }
    }
    for (const auto& surface : surfaces) {
        // Walk connected edges from the first face; the walk must reach the whole surface.
        std::vector<bool> seen(geometry.faces.size(), false);
        std::vector<int> stack{surface.faces.front()};
        seen[static_cast<std::size_t>(surface.faces.front())] = true;
        std::size_t reached = 0;
        while (!stack.empty()) {
            const int f = stack.back();
            stack.pop_back();
            ++reached;
            for (const int n : geometry.faces[static_cast<std::size_t>(f)].neighbours) {
                if (n >= 0 && !seen[static_cast<std::size_t>(n)] && connected(f, n)) {
                    seen[static_cast<std::size_t>(n)] = true;
                    stack.push_back(n);
                }
            }
        }
        EXPECT_EQ(reached, surface.faces.size());
    }
}

TEST(Surfaces, CubeIsSixSurfacesAtSixtyDegrees) {
    const auto geometry = geometry_of(levels::make_box(glm::vec3(1.0f)));
    const auto surfaces = prep::find_crease_surfaces(geometry, 60.0);
    ASSERT_EQ(surfaces.size(), 6u);
    for (const auto& surface : surfaces) {
        EXPECT_EQ(surface.faces.size(), 2u);
        EXPECT_NEAR(surface.area, 1.0, 1e-6);
    }
    // Through the whole tool: six surfaces, one primitive each.
    const auto result = luxel::testing::run_prep(
        luxel::testing::single_mesh_scene(levels::make_box(glm::vec3(1.0f))), [] {
            prep::PrepOptions o;
            o.crease_degrees = 60.0;
            return o;
        }());
    EXPECT_EQ(result.report.surfaces, 6u);
    EXPECT_EQ(result.scene.meshes[0].primitives.size(), 6u);
}

TEST(Surfaces, UvSphereIsOneSurfaceAtSixtyDegrees) {
    const scene::Primitive sphere = levels::make_sphere(0.5f, 32, 16);
    const auto geometry = geometry_of(sphere);
    // The seam duplicates vertices for TEXCOORD_0; welding closes it.
    EXPECT_EQ(geometry.mesh.n_vertices(), 32u * 15u + 2u);
    const auto surfaces = prep::find_crease_surfaces(geometry, 60.0);
    ASSERT_EQ(surfaces.size(), 1u);
    EXPECT_NEAR(surfaces[0].area, 4.0 * glm::pi<double>() * 0.25, 0.05);
    // At 5 cm texels the sphere is about 1260 texels: within a budget of 4096 it stays one
    // surface, made of several charts.
    prep::PrepOptions options;
    options.crease_degrees = 60.0;
    options.texel_size = 0.05;
    options.surface_texel_budget = 4096.0;
    const auto result =
        luxel::testing::run_prep(luxel::testing::single_mesh_scene(sphere), options);
    EXPECT_EQ(result.report.surfaces, 1u);
    EXPECT_GT(result.report.charts, 1u) << "a closed sphere cannot be one flat chart";
}

TEST(Surfaces, CornellBumpyFloorStaysOneSurfaceAtTenDegrees) {
    // The bumps' steepest slope is atan(0.015 * 2 pi / 0.4) = 13.2 degrees, but the crease
    // rule compares neighbouring faces, and their normals turn by about amplitude * frequency^2
    // per metre (3.7 rad/m): over the 62-cell floor's 3.2 cm cells that is 7 degrees, 9.4 with
    // the triangulation's diagonals (less on the finer floors). So at 10 degrees the floor is
    // one surface; below its steepest neighbour angle it falls apart.
    const auto geometry = geometry_of(bumpy_floor(62));
    const double steepest = prep::max_connected_dihedral_degrees(geometry);
    std::cout << "62 cells: neighbouring faces differ by up to " << steepest << " degrees\n";
    EXPECT_GT(steepest, 5.0);
    EXPECT_LT(steepest, 10.0);
    const auto at_10 = prep::find_crease_surfaces(geometry, 10.0);
    EXPECT_EQ(at_10.size(), 1u);
    EXPECT_EQ(prep::find_crease_surfaces(geometry, 20.0).size(), 1u);
    const auto at_half = prep::find_crease_surfaces(geometry, 0.5 * steepest);
    EXPECT_GT(at_half.size(), 1u);
    expect_components_of_connected_edges(geometry, at_half, 0.5 * steepest);
}

TEST(Surfaces, CoarseBumpyFloorSplitsAtTenButNotAtTwentyDegrees) {
    // The same bumps on 32 cells of 6.25 cm: neighbours differ by up to 17 degrees.
    const auto geometry = geometry_of(bumpy_floor(32));
    const double steepest = prep::max_connected_dihedral_degrees(geometry);
    std::cout << "32 cells: neighbouring faces differ by up to " << steepest << " degrees\n";
    ASSERT_GT(steepest, 10.0);
    ASSERT_LT(steepest, 20.0);
    const auto at_10 = prep::find_crease_surfaces(geometry, 10.0);
    EXPECT_GT(at_10.size(), 1u);
    expect_components_of_connected_edges(geometry, at_10, 10.0);
    EXPECT_EQ(prep::find_crease_surfaces(geometry, 20.0).size(), 1u);
}

TEST(Surfaces, MaterialsSeparateCoplanarFaces) {
    // One flat quad grid whose two halves have different materials: two surfaces at any angle.
    scene::Primitive left = levels::make_quad({0, 0, 0}, {1, 0, 0}, {0, 0, -1}, 4, 4);
    scene::Primitive right = levels::make_quad({1, 0, 0}, {1, 0, 0}, {0, 0, -1}, 4, 4);
    scene::Scene s = luxel::testing::single_mesh_scene(left);
    s.materials.push_back(luxel::testing::diffuse_material("other"));
    right.material = 1;
    s.meshes[0].primitives.push_back(right);
    const auto geometry = prep::build_geometry(s.meshes[0], s.materials, glm::dmat4(1.0), false);
    EXPECT_EQ(prep::find_crease_surfaces(geometry, 180.0).size(), 2u);
    // Without the second material they weld into one surface across the shared edge.
    s.meshes[0].primitives[1].material = 0;
    const auto welded = prep::build_geometry(s.meshes[0], s.materials, glm::dmat4(1.0), false);
    EXPECT_EQ(prep::find_crease_surfaces(welded, 1.0).size(), 1u);
}

TEST(Surfaces, TexelBudgetSplitsLargeSurfacesIntoConnectedPieces) {
    // A 4 x 4 m floor at 5 cm texels is 6400 texels: with a budget of 1024 it needs at least
    // seven surfaces, each within the budget.
    const scene::Scene floor = luxel::testing::single_mesh_scene(
        levels::make_quad({-2, 0, 2}, {4, 0, 0}, {0, 0, -4}, 16, 16));
    prep::PrepOptions options;
    options.surface_texel_budget = 1024.0;
    const auto result = luxel::testing::run_prep(floor, options);
    EXPECT_GE(result.report.surfaces, 7u);
    EXPECT_EQ(result.report.crease_surfaces, 1u);
    double total = 0.0;
    for (const auto& surface : result.nodes.at(0).surfaces) {
        EXPECT_LE(surface.area / (0.05 * 0.05), 1024.0 + 1e-6);
        total += surface.area;
    }
    EXPECT_NEAR(total, 16.0, 1e-6);
}

}  // namespace
