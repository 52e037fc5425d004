// A sky map a level names in its own extras (docs/LEVELS.md, "Sky"): read from the level's
// folder, refused from anywhere else by the rules that hold for its buffers and images (no
// "../", no absolute path, no link out, within the file-size limit), and kept by a save only
// where it is named relative to the level.

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "error_of.hpp"
#include "luxel/runtime/image.hpp"
#include "luxel/scene/gltf.hpp"
#include "luxel/scene/sky.hpp"
#include "temp_dir.hpp"
#include "test_scenes.hpp"

namespace {

using luxel::scene::SkySpec;

using luxel::testing::error_of;

/// A small equirectangular map of noise (noise: so that it does not compress, and its size
/// on disk is about its pixels').
void write_map(const std::filesystem::path& file, int width, int height) {
    std::filesystem::create_directories(file.parent_path());
    luxel::Image image(width, height);
    std::mt19937 random(7);
    std::uniform_real_distribution<float> value(0.0f, 2.0f);
    for (float& v : image.rgba) {
        v = value(random);
    }
    luxel::write_exr(file, image);
}

/// The box room with a map sky named `file`, saved as `level`. The text is written here, not
/// by save_gltf, which names no absolute map: a hostile file may.
void save_room_with_map(const std::filesystem::path& level, const std::string& file) {
    luxel::scene::Scene room = luxel::testing::box_room();
    room.sky.kind = SkySpec::Kind::Map;
    room.sky.map = "renamed-below.exr";
    room.sky.scale = 0.5f;
    const std::vector<std::uint8_t> bytes =
        luxel::scene::save_gltf_to_memory(room, luxel::scene::GltfContainer::EmbeddedText);
    std::string text(bytes.begin(), bytes.end());
    const std::string written = "\"renamed-below.exr\"";
    const std::size_t at = text.find(written);
    ASSERT_NE(at, std::string::npos);
    text.replace(at, written.size(), nlohmann::json(file).dump());
    std::ofstream(level, std::ios::binary) << text;
}

TEST(SkyMapFile, ALevelReadsTheMapItNamesBesideIt) {
    luxel::testing::TempDir dir;
    write_map(dir / "skies" / "noon.exr", 16, 8);
    save_room_with_map(dir / "room.gltf", "skies/noon.exr");
    const luxel::scene::Scene loaded = luxel::scene::load_gltf(dir / "room.gltf");
    EXPECT_EQ(loaded.sky.kind, SkySpec::Kind::Map);
    EXPECT_EQ(loaded.sky.scale, 0.5f);
    const std::filesystem::path real = std::filesystem::canonical(dir / "skies" / "noon.exr");
    EXPECT_EQ(loaded.sky.map, real);
    ASSERT_FALSE(loaded.report.external_files.empty());
    EXPECT_EQ(loaded.report.external_files.back(), real);
    // Resolved to a real path, the map is no longer the level's to name: saved elsewhere, the
    // level names none (luxel-prep places a copy beside what it writes: tools/prep/sky_map).
    luxel::scene::save_gltf(loaded, dir / "elsewhere.glb");
    EXPECT_EQ(luxel::scene::load_gltf(dir / "elsewhere.glb").sky.kind, SkySpec::Kind::None);
}

TEST(SkyMapFile, AMapOutsideTheLevelsFolderOrMissingIsAnErrorNamingTheFileAndTheField) {
    luxel::testing::TempDir dir;
    write_map(dir / "outside.exr", 4, 2);
    const std::filesystem::path level_dir = dir / "level";
    std::filesystem::create_directories(level_dir);
    std::filesystem::create_symlink(dir / "outside.exr", level_dir / "link.exr");
    const std::pair<std::string, const char*> cases[] = {
        {"../outside.exr", "outside the file's directory"},
        {(dir / "outside.exr").string(), "outside the file's directory"},
        {"link.exr", "symbolic link to a file outside"},
        {"gone.exr", "does not exist"},
    };
    for (const auto& [file, reason] : cases) {
        save_room_with_map(level_dir / "room.gltf", file);
        const std::string message =
            error_of([&] { (void)luxel::scene::load_gltf(level_dir / "room.gltf"); });
        EXPECT_NE(message.find("room.gltf"), std::string::npos) << file << ": " << message;
        EXPECT_NE(message.find("extras.luxel.sky.file"), std::string::npos) << message;
        EXPECT_NE(message.find(reason), std::string::npos) << file << ": " << message;
    }
    // From memory there is no folder to read it from.
    luxel::scene::Scene named = luxel::testing::box_room();
    named.sky.kind = SkySpec::Kind::Map;
    named.sky.map = "noon.exr";
    const std::vector<std::uint8_t> in_memory =
        luxel::scene::save_gltf_to_memory(named, luxel::scene::GltfContainer::Binary);
    const std::string message =
        error_of([&] { (void)luxel::scene::load_gltf_from_memory(in_memory, "memory.glb"); });
    EXPECT_NE(message.find("memory.glb"), std::string::npos) << message;
    EXPECT_NE(message.find("no directory"), std::string::npos) << message;
}

TEST(SkyMapFile, AMapOverTheFileSizeLimitIsRefusedBeforeItIsRead) {
    luxel::testing::TempDir dir;
    write_map(dir / "big.exr", 256, 128);  // about 500 kB of noise
    save_room_with_map(dir / "room.gltf", "big.exr");
    luxel::scene::LoadOptions limits;
    limits.max_file_size = 64 * 1024;
    ASSERT_LT(std::filesystem::file_size(dir / "room.gltf"), limits.max_file_size);
    ASSERT_GT(std::filesystem::file_size(dir / "big.exr"), limits.max_file_size);
    const std::string message =
        error_of([&] { (void)luxel::scene::load_gltf(dir / "room.gltf", limits); });
    EXPECT_NE(message.find("extras.luxel.sky.file 'big.exr'"), std::string::npos) << message;
    EXPECT_NE(message.find("limit"), std::string::npos) << message;
}

TEST(SkyMapFile, TheExtrasOfAMapAreChecked) {
    const SkySpec map = luxel::scene::read_sky_extras(
        nlohmann::json::parse(R"({"kind": "map", "file": "skies/noon.exr", "scale": 2})"));
    EXPECT_EQ(map.kind, SkySpec::Kind::Map);
    EXPECT_EQ(map.map, std::filesystem::path("skies/noon.exr"));
    EXPECT_EQ(map.scale, 2.0f);
    EXPECT_EQ(luxel::scene::read_sky_extras(luxel::scene::sky_extras(map)), map);
    const std::pair<const char*, const char*> bad[] = {
        {R"({"kind": "map"})", "extras.luxel.sky.file"},
        {R"({"kind": "map", "file": ""})", "extras.luxel.sky.file"},
        {R"({"kind": "map", "file": 3})", "extras.luxel.sky.file"},
        {R"({"kind": "map", "file": "noon.png"})", "not an OpenEXR"},
        {R"({"kind": "map", "file": "noon.exr", "ground": 0.2})", "extras.luxel.sky.ground"},
        {R"({"kind": "map", "file": "noon.exr", "scale": -1})", "extras.luxel.sky.scale"}};
    for (const auto& [json, expected] : bad) {
        const std::string message =
            error_of([&] { (void)luxel::scene::read_sky_extras(nlohmann::json::parse(json)); });
        EXPECT_NE(message.find(expected), std::string::npos) << json << " -> '" << message << "'";
    }
}

}  // namespace
