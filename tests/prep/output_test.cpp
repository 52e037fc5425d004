// The prepared scene: one primitive per surface, per-node mesh copies, pass-through of
// specular primitives, the same triangles as the input, output identical for any thread count,
// and a round trip through the file and the runtime.

#include <memory>

#include <gtest/gtest.h>

#include "luxel/ecs/registry.hpp"
#include "luxel/lighting/components.hpp"
#include "luxel/scene/gltf.hpp"
#include "luxel/world/scene_instance.hpp"
#include "mesh_builders.hpp"
#include "prep_test_support.hpp"
#include "temp_dir.hpp"
#include "validator.hpp"

namespace {

using namespace luxel;

scene::Material glass() {
    scene::Material material;
    material.name = "glass";
    material.metallic = 0.0f;
    material.roughness = 0.0f;
    material.transmission = 1.0f;
    return material;
}

/// Two nodes instancing one box mesh, a glass sphere, and a mesh with a diffuse and a glass
/// primitive.
scene::Scene mixed_scene() {
    scene::Scene s = luxel::testing::single_mesh_scene(levels::make_box(glm::vec3(0.6f)), "box");
    s.materials.push_back(glass());
    scene::Node second = s.nodes[0];
    second.name = "box copy";
    second.translation = {2.0f, 0.0f, 0.0f};
    s.nodes.push_back(second);
    s.roots.push_back(1);

    scene::Primitive sphere = levels::make_sphere(0.3f, 24, 12);
    sphere.material = 1;
    luxel::testing::add_mesh_node(s, "glass sphere", std::move(sphere), {0.0f, 1.0f, 0.0f});

    scene::Primitive panel = levels::make_quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 2, 2);
    panel.material = 0;
    scene::Primitive lens = levels::make_quad({0, 0, 0.5f}, {1, 0, 0}, {0, 1, 0}, 1, 1);
    lens.material = 1;
    s.meshes.push_back({"panel and lens", {lens, panel}});
    scene::Node panel_node;
    panel_node.name = "panel";
    panel_node.mesh = 2;
    panel_node.translation = {-2.0f, 0.0f, 0.0f};
    panel_node.flags.raw["lightmap"] = "stale";
    s.nodes.push_back(panel_node);
    s.roots.push_back(3);
    return s;
}

TEST(Output, EveryLightMappedNodeGetsItsOwnMeshWithOnePrimitivePerSurface) {
    const scene::Scene input = mixed_scene();
    prep::PrepOptions options;
    options.crease_degrees = 60.0;
    const auto result = luxel::testing::run_prep(input, options);
    const scene::Scene& out = result.scene;
    ASSERT_EQ(out.nodes.size(), 4u);
    // The two boxes no longer share a mesh; the first keeps the original index.
    EXPECT_EQ(out.nodes[0].mesh, 0);
    EXPECT_NE(out.nodes[1].mesh, out.nodes[0].mesh);
    ASSERT_EQ(out.meshes.size(), 4u);
    std::vector<int> ids;
    for (const int n : {0, 1}) {
        const auto layout =
            scene::read_lightmap_layout(out.nodes[static_cast<std::size_t>(n)].flags.raw);
        ASSERT_TRUE(layout.has_value());
        ASSERT_EQ(layout->surfaces.size(), 6u);
        const scene::Mesh& mesh =
            out.meshes[static_cast<std::size_t>(out.nodes[static_cast<std::size_t>(n)].mesh)];
        ASSERT_EQ(mesh.primitives.size(), 6u);
        for (std::size_t s = 0; s < 6; ++s) {
            EXPECT_EQ(layout->surfaces[s].primitive, static_cast<int>(s));
            EXPECT_EQ(mesh.primitives[s].triangle_count(), 2u);
            EXPECT_EQ(mesh.primitives[s].texcoords1.size(), mesh.primitives[s].positions.size());
            EXPECT_NEAR(layout->surfaces[s].area, 0.36, 1e-6);
            ids.push_back(layout->surfaces[s].id);
        }
    }
    std::sort(ids.begin(), ids.end());
    EXPECT_TRUE(std::adjacent_find(ids.begin(), ids.end()) == ids.end()) << "ids must be unique";

    // Glass gets no light map and keeps its mesh.
    EXPECT_FALSE(out.nodes[2].flags.raw.contains("lightmap"));
    EXPECT_EQ(out.nodes[2].mesh, 1);
    EXPECT_TRUE(out.meshes[1].primitives[0].texcoords1.empty());
    EXPECT_EQ(out.meshes[1].primitives[0].indices, input.meshes[1].primitives[0].indices);

    // A mixed mesh: its surfaces first, then the glass primitive unchanged; the stale layout
    // was replaced.
    const auto layout = scene::read_lightmap_layout(out.nodes[3].flags.raw);
    ASSERT_TRUE(layout.has_value());
    ASSERT_EQ(layout->surfaces.size(), 1u);
    const scene::Mesh& mixed = out.meshes[static_cast<std::size_t>(out.nodes[3].mesh)];
    ASSERT_EQ(mixed.primitives.size(), 2u);
    EXPECT_EQ(mixed.primitives[0].material, 0);
    EXPECT_EQ(mixed.primitives[1].material, 1);
    EXPECT_TRUE(mixed.primitives[1].texcoords1.empty());
    EXPECT_EQ(mixed.primitives[0].triangle_count(), 8u);
}

TEST(Output, KeepsEveryTriangleAndVertexAttribute) {
    const scene::Scene input = luxel::testing::single_mesh_scene(levels::make_sphere(0.5f, 32, 16));
    const auto result = luxel::testing::run_prep(input);
    const scene::Primitive& source = input.meshes[0].primitives[0];
    std::size_t triangles = 0;
    for (const auto& p : result.scene.meshes[0].primitives) {
        triangles += p.triangle_count();
        ASSERT_EQ(p.normals.size(), p.positions.size());
        ASSERT_EQ(p.texcoords0.size(), p.positions.size());
        for (std::size_t v = 0; v < p.positions.size(); ++v) {
            // Every output vertex is a copy of a source vertex, attributes and all.
            bool found = false;
            for (std::size_t s = 0; s < source.positions.size() && !found; ++s) {
                found = source.positions[s] == p.positions[v] &&
                        source.normals[s] == p.normals[v] &&
                        source.texcoords0[s] == p.texcoords0[v];
            }
            EXPECT_TRUE(found) << "vertex " << v;
        }
    }
    EXPECT_EQ(triangles, source.triangle_count());
}

TEST(Output, IsTheSameForAnyThreadCount) {
    for (const auto& input :
         {mixed_scene(), scene::load_gltf(luxel::testing::level_file("cornell")),
          scene::load_gltf(luxel::testing::level_file("furnace"))}) {
        const auto one = luxel::testing::run_prep(input, {}, 1);
        const auto two = luxel::testing::run_prep(input, {}, 2);
        const auto four = luxel::testing::run_prep(input, {}, 4);
        const auto bytes = scene::save_gltf_to_memory(one.scene, scene::GltfContainer::Binary);
        EXPECT_TRUE(bytes == scene::save_gltf_to_memory(two.scene, scene::GltfContainer::Binary));
        EXPECT_TRUE(bytes == scene::save_gltf_to_memory(four.scene, scene::GltfContainer::Binary));
    }
}

TEST(Output, RoundTripsThroughTheFileAndTheRuntime) {
    luxel::testing::TempDir dir("luxel-prep");
    const auto result = luxel::testing::run_prep(mixed_scene());
    const auto file = dir / "mixed.glb";
    scene::save_gltf(result.scene, file);
    const auto validation = luxel::testing::run_gltf_validator({file});
    EXPECT_EQ(validation.exit_code, 0) << validation.output;

    const auto loaded = std::make_shared<scene::Scene>(scene::load_gltf(file));
    ecs::Registry registry;
    const auto instance = world::instantiate(registry, loaded);
    for (const prep::PreparedNode& node : result.nodes) {
        const ecs::Entity entity = instance.nodes.at(static_cast<std::size_t>(node.node));
        ASSERT_TRUE(registry.has<lighting::LightmappedSurface>(entity));
        const auto& layout = registry.get<lighting::LightmappedSurface>(entity).layout;
        ASSERT_EQ(layout.surfaces.size(), node.surfaces.size());
        for (std::size_t s = 0; s < node.surfaces.size(); ++s) {
            EXPECT_EQ(layout.surfaces[s].rect, node.surfaces[s].rect);
            EXPECT_DOUBLE_EQ(layout.surfaces[s].area, node.surfaces[s].area);
            EXPECT_EQ(layout.surfaces[s].texels, node.surfaces[s].texels);
        }
    }
    EXPECT_FALSE(registry.has<lighting::LightmappedSurface>(instance.nodes[2]));
    const luxel::testing::PageCheck check = luxel::testing::check_light_map_pages(*loaded, 1);
    EXPECT_TRUE(check.failures.empty()) << check.failures.front();
}

}  // namespace
