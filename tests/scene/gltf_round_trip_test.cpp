// Load -> save -> load keeps everything luxel reads from glTF, in all three containers, and
// every file the writer produces passes the Khronos glTF validator.

#include <fstream>
#include <iterator>

#include <gtest/gtest.h>

#include "luxel/runtime/error.hpp"
#include "luxel/scene/gltf.hpp"
#include "scene_compare.hpp"
#include "temp_dir.hpp"
#include "test_scenes.hpp"
#include "validator.hpp"

namespace {

using luxel::scene::Scene;
using luxel::testing::TempDir;

std::vector<std::uint8_t> read_bytes(const std::filesystem::path& file) {
    std::ifstream stream(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()};
}

/// Saves, loads, saves the loaded scene and loads again: both loads must equal the original.
void expect_round_trip(const Scene& original, const std::filesystem::path& file,
                       const luxel::scene::SaveOptions& options = {}) {
    luxel::scene::save_gltf(original, file, options);
    const Scene first = luxel::scene::load_gltf(file);
    EXPECT_TRUE(first.report.warnings.empty())
        << (first.report.warnings.empty() ? "" : first.report.warnings.front());
    EXPECT_EQ(first.report.degenerate_triangles_dropped, 0u);
    EXPECT_EQ(first.report.primitives_skipped, 0u);
    luxel::testing::expect_same_scene(original, first);

    const std::filesystem::path again = file.parent_path() / ("again-" + file.filename().string());
    luxel::scene::save_gltf(first, again, options);
    luxel::testing::expect_same_scene(original, luxel::scene::load_gltf(again));
}

TEST(GltfRoundTrip, BinaryKeepsEverything) {
    TempDir dir;
    expect_round_trip(luxel::testing::box_room(), dir / "room.glb");
}

TEST(GltfRoundTrip, TextWithBinFileKeepsEverything) {
    TempDir dir;
    expect_round_trip(luxel::testing::box_room(), dir / "room.gltf");
    EXPECT_TRUE(std::filesystem::exists(dir / "room.bin"));
}

TEST(GltfRoundTrip, TextWithEmbeddedBufferKeepsEverything) {
    TempDir dir;
    expect_round_trip(luxel::testing::box_room(), dir / "room.gltf", {.embed_buffers = true});
    EXPECT_FALSE(std::filesystem::exists(dir / "room.bin"));
}

TEST(GltfRoundTrip, FileNamesNeedingUriEscapes) {
    TempDir dir;
    expect_round_trip(luxel::testing::box_room(), dir / "my room #1.gltf");
    EXPECT_TRUE(std::filesystem::exists(dir / "my room #1.bin"));
}

TEST(GltfRoundTrip, DefaultsAndThirtyTwoBitIndices) {
    TempDir dir;
    expect_round_trip(luxel::testing::single_triangle(), dir / "triangle.glb");
    const Scene big = luxel::testing::grid(260);  // 261^2 vertices: 32-bit indices
    ASSERT_GT(big.meshes[0].primitives[0].positions.size(), 65535u);
    expect_round_trip(big, dir / "grid.glb");
}

TEST(GltfRoundTrip, MemoryAndFileWritersAgree) {
    TempDir dir;
    const Scene room = luxel::testing::box_room();
    luxel::scene::save_gltf(room, dir / "room.glb");
    EXPECT_EQ(read_bytes(dir / "room.glb"),
              luxel::scene::save_gltf_to_memory(room, luxel::scene::GltfContainer::Binary));
    const std::vector<std::uint8_t> text =
        luxel::scene::save_gltf_to_memory(room, luxel::scene::GltfContainer::EmbeddedText);
    luxel::testing::expect_same_scene(room,
                                      luxel::scene::load_gltf_from_memory(text, "room (memory)"));
}

TEST(GltfRoundTrip, LoadedSceneIsConsistent) {
    TempDir dir;
    luxel::scene::save_gltf(luxel::testing::box_room(), dir / "room.glb");
    const Scene room = luxel::scene::load_gltf(dir / "room.glb");
    EXPECT_NO_THROW(room.validate());
    EXPECT_EQ(room.triangle_count(), luxel::testing::box_room().triangle_count());
    // Animated nodes and the children of a dynamic pivot are dynamic; the camera says it is not.
    const auto find = [&room](const std::string& name) {
        for (std::size_t i = 0; i < room.nodes.size(); ++i) {
            if (room.nodes[i].name == name) {
                return static_cast<int>(i);
            }
        }
        return -1;
    };
    EXPECT_TRUE(room.is_dynamic(find("cube")));
    EXPECT_TRUE(room.is_dynamic(find("glass sphere")));
    EXPECT_TRUE(room.is_dynamic(find("door")));
    EXPECT_FALSE(room.is_dynamic(find("room")));
    EXPECT_FALSE(room.is_dynamic(find("camera")));
    EXPECT_FALSE(room.nodes[static_cast<std::size_t>(find("bulb"))].flags.light_enabled);
    EXPECT_EQ(room.nodes[static_cast<std::size_t>(find("bulb"))].flags.light_radius, 0.125f);
    EXPECT_EQ(room.nodes[static_cast<std::size_t>(find("camera"))].flags.raw.at("big"),
              9007199254740993);
}

TEST(GltfRoundTrip, EmissionAndLightColoursAboveOneAreSplitIntoIntensity) {
    Scene scene = luxel::testing::single_triangle();
    luxel::scene::Material hot;
    hot.emissive = {4.0f, 2.0f, 1.0f};
    scene.materials.push_back(hot);
    scene.meshes[0].primitives[0].material = 0;
    luxel::scene::Light light;
    light.color = {3.0f, 1.5f, 0.0f};
    light.intensity = 2.0f;
    scene.lights.push_back(light);
    scene.nodes[0].light = 0;

    TempDir dir;
    luxel::scene::save_gltf(scene, dir / "hot.glb");
    const Scene back = luxel::scene::load_gltf(dir / "hot.glb");
    luxel::testing::expect_near(back.materials[0].emitted_radiance(), {4.0f, 2.0f, 1.0f},
                                "emission");
    EXPECT_FLOAT_EQ(back.materials[0].emissive.r, 1.0f);
    luxel::testing::expect_near(back.lights[0].radiant_intensity(),
                                scene.lights[0].radiant_intensity(), "light");
    const auto result = luxel::testing::run_gltf_validator({dir / "hot.glb"});
    EXPECT_EQ(result.exit_code, 0) << result.output;
}

TEST(GltfValidator, EverythingTheWriterProducesPasses) {
    TempDir dir;
    const Scene room = luxel::testing::box_room();
    luxel::scene::save_gltf(room, dir / "room.glb");
    luxel::scene::save_gltf(room, dir / "room.gltf");
    luxel::scene::save_gltf(room, dir / "embedded.gltf", {.embed_buffers = true});
    luxel::scene::save_gltf(luxel::testing::single_triangle(), dir / "triangle.glb");
    luxel::scene::save_gltf(luxel::testing::grid(260), dir / "grid.glb");
    // A scene that went through the loader once more (what luxel-prep does to levels).
    luxel::scene::save_gltf(luxel::scene::load_gltf(dir / "room.glb"), dir / "resaved.glb");

    const auto result = luxel::testing::run_gltf_validator(
        {dir / "room.glb", dir / "room.gltf", dir / "embedded.gltf", dir / "triangle.glb",
         dir / "grid.glb", dir / "resaved.glb"});
    ASSERT_NE(result.exit_code, 127) << "Node.js is missing (scripts/setup.sh installs it):\n"
                                     << result.output;
    ASSERT_NE(result.exit_code, 2) << "the validator could not run (scripts/setup.sh installs "
                                      "it with npm in tools/):\n"
                                   << result.output;
    EXPECT_EQ(result.exit_code, 0) << result.output;
    EXPECT_NE(result.output.find("room.glb: 0 errors"), std::string::npos) << result.output;
}

TEST(GltfValidator, LightMapUvsWithoutTextureCoordinatesStillValidate) {
    // A mesh exported without TEXCOORD_0 that luxel-prep gave light-map UVs (TEXCOORD_1): the
    // validator wants the sets numbered from 0.
    TempDir dir;
    Scene scene = luxel::testing::single_triangle();
    auto& primitive = scene.meshes[0].primitives[0];
    primitive.texcoords0.clear();
    primitive.texcoords1 = {{0.1f, 0.1f}, {0.9f, 0.1f}, {0.1f, 0.9f}};
    luxel::scene::save_gltf(scene, dir / "uv1-only.glb");
    luxel::testing::expect_every_file_valid({dir / "uv1-only.glb"});
    const Scene loaded = luxel::scene::load_gltf(dir / "uv1-only.glb");
    const auto& back = loaded.meshes[0].primitives[0];
    EXPECT_EQ(back.texcoords1, primitive.texcoords1);
    EXPECT_EQ(back.texcoords0, primitive.texcoords1);  // the same accessor, set 0 too
}

TEST(GltfSave, RejectsWhatItCannotWrite) {
    TempDir dir;
    EXPECT_THROW(luxel::scene::save_gltf(luxel::testing::single_triangle(), dir / "x.obj"),
                 luxel::Error);
    Scene broken = luxel::testing::single_triangle();
    broken.meshes[0].primitives[0].indices[2] = 7;
    try {
        luxel::scene::save_gltf(broken, dir / "broken.glb");
        FAIL() << "an invalid scene was written";
    } catch (const luxel::Error& e) {
        EXPECT_NE(std::string(e.what()).find("broken.glb"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("index 7 out of range"), std::string::npos)
            << e.what();
    }
    EXPECT_THROW(
        luxel::scene::save_gltf(luxel::testing::single_triangle(), dir / "no-such-dir" / "x.glb"),
        luxel::Error);
    // A light whose colour times intensity overflows float is refused with its name, never
    // written as "intensity": null (issue 22).
    Scene bright = luxel::testing::single_triangle();
    luxel::scene::Light light;
    light.name = "sun";
    light.color = glm::vec3(4.0f, 1.0f, 1.0f);
    light.intensity = 3e38f;
    bright.lights.push_back(light);
    try {
        luxel::scene::save_gltf(bright, dir / "bright.glb");
        FAIL() << "an overflowing light was written";
    } catch (const luxel::Error& e) {
        EXPECT_NE(std::string(e.what()).find("sun"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("colour times intensity"), std::string::npos)
            << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "bright.glb"));
}

}  // namespace
