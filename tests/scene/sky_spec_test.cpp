// The sky a level asks for (docs/LEVELS.md, "Sky"): --sky's values, the scene's
// extras.luxel.sky with every way it can be wrong, and the sky kept by a save and a load (so
// luxel-prep keeps it).

#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "error_of.hpp"
#include "luxel/scene/gltf.hpp"
#include "luxel/scene/sky.hpp"
#include "temp_dir.hpp"
#include "test_scenes.hpp"

namespace {

using luxel::scene::parse_sky;
using luxel::scene::read_sky_extras;
using luxel::scene::SkySpec;

using luxel::testing::error_of;

TEST(SkySpec, CommandLineValues) {
    EXPECT_EQ(parse_sky("none").kind, SkySpec::Kind::None);
    const SkySpec grey = parse_sky("uniform:0.5");
    EXPECT_EQ(grey.kind, SkySpec::Kind::Uniform);
    EXPECT_EQ(grey.radiance, glm::vec3(0.5f));
    EXPECT_EQ(parse_sky("uniform:0.25,0.5,1").radiance, glm::vec3(0.25f, 0.5f, 1.0f));
    const SkySpec day = parse_sky("daylight:2.5,4");
    EXPECT_EQ(day.kind, SkySpec::Kind::Daylight);
    EXPECT_EQ(day.irradiance, 2.5f);
    EXPECT_EQ(day.turbidity, 4.0f);
    EXPECT_EQ(parse_sky("daylight").irradiance, SkySpec{}.irradiance);
    const SkySpec map = parse_sky("skies/noon.exr");
    EXPECT_EQ(map.kind, SkySpec::Kind::Map);
    EXPECT_EQ(map.map, std::filesystem::path("skies/noon.exr"));
    // describe() writes what parse_sky reads back.
    for (const char* text : {"uniform:0.25,0.5,1", "daylight:2.5,4", "none"}) {
        EXPECT_EQ(parse_sky(luxel::scene::describe(parse_sky(text))), parse_sky(text)) << text;
    }
    for (const char* bad :
         {"uniform", "uniform:", "uniform:1,2", "uniform:-1", "uniform:nan", "uniform:inf",
          "uniform:1,x,3", "daylight:1,2,3", "daylight:", "cloudy", "sky.png", "none:1", ""}) {
        EXPECT_NE(error_of([&] { (void)parse_sky(bad); }), "") << "'" << bad << "'";
    }
    EXPECT_NE(error_of([] { (void)parse_sky("cloudy"); }).find("daylight"), std::string::npos);
}

TEST(SkySpec, AGroundBelowTheHorizonOnTheCommandLineAndInExtras) {
    EXPECT_EQ(parse_sky("daylight:1.5,3,ground=0.2").ground, glm::vec3(0.2f));
    EXPECT_EQ(parse_sky("daylight:1.5,3,ground=0.2").irradiance, 1.5f);
    const SkySpec only = parse_sky("daylight:ground=0.1/0.2/0.3");
    EXPECT_EQ(only.ground, glm::vec3(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(only.irradiance, SkySpec{}.irradiance);
    EXPECT_EQ(parse_sky("uniform:0.5,ground=0.3").ground, glm::vec3(0.3f));
    EXPECT_EQ(parse_sky("uniform:0.5").ground, glm::vec3(0.0f));
    for (const char* text : {"daylight:1.5,3,ground=0.2", "uniform:1,2,3,ground=0.1/0.2/0.3"}) {
        EXPECT_EQ(parse_sky(luxel::scene::describe(parse_sky(text))), parse_sky(text)) << text;
    }
    for (const char* bad : {"daylight:ground=1.5", "daylight:ground=-0.1", "daylight:ground=nan",
                            "daylight:ground=", "daylight:ground=0.1/0.2", "uniform:ground=0.2",
                            "daylight:ground=0.2,3", "uniform:0.5,ground=0.2,1"}) {
        EXPECT_NE(error_of([&] { (void)parse_sky(bad); }), "") << "'" << bad << "'";
    }
    const SkySpec grey =
        read_sky_extras(nlohmann::json::parse(R"({"kind": "daylight", "ground": 0.25})"));
    EXPECT_EQ(grey.ground, glm::vec3(0.25f));
    const SkySpec tinted =
        read_sky_extras(nlohmann::json::parse(R"({"kind": "uniform", "ground": [0.2, 0.3, 0.1]})"));
    EXPECT_EQ(tinted.ground, glm::vec3(0.2f, 0.3f, 0.1f));
    EXPECT_EQ(read_sky_extras(luxel::scene::sky_extras(tinted)), tinted);
    for (const char* bad :
         {R"({"kind": "daylight", "ground": 2})", R"({"kind": "daylight", "ground": -0.5})",
          R"({"kind": "daylight", "ground": [0.2, 0.3]})",
          R"({"kind": "daylight", "ground": "grass"})",
          R"({"kind": "daylight", "ground": [0.2, "0.3", 0.1]})"}) {
        const std::string message =
            error_of([&] { (void)read_sky_extras(nlohmann::json::parse(bad)); });
        EXPECT_NE(message.find("extras.luxel.sky.ground"), std::string::npos)
            << bad << " -> '" << message << "'";
    }
}

TEST(SkySpec, ExtrasAreCheckedFieldByField) {
    const SkySpec uniform = read_sky_extras(
        nlohmann::json::parse(R"({"kind": "uniform", "radiance": [1, 2, 3], "scale": 0.5})"));
    EXPECT_EQ(uniform.radiance, glm::vec3(1.0f, 2.0f, 3.0f));
    EXPECT_EQ(uniform.scale, 0.5f);
    const SkySpec day =
        read_sky_extras(nlohmann::json::parse(R"({"kind": "daylight", "irradiance": 3})"));
    EXPECT_EQ(day.kind, SkySpec::Kind::Daylight);
    EXPECT_EQ(day.irradiance, 3.0f);
    EXPECT_EQ(day.turbidity, SkySpec{}.turbidity);
    const std::pair<const char*, const char*> bad[] = {
        {R"([1, 2])", "must be a JSON object"},
        {R"({})", "extras.luxel.sky.kind"},
        {R"({"kind": 3})", "extras.luxel.sky.kind"},
        {R"({"kind": "uniform", "radiance": [1, 2]})", "extras.luxel.sky.radiance"},
        {R"({"kind": "uniform", "radiance": [1, "2", 3]})", "extras.luxel.sky.radiance"},
        {R"({"kind": "uniform", "radiance": [1, -2, 3]})", "extras.luxel.sky.radiance"},
        {R"({"kind": "uniform", "radiance": [1, 1e300, 3]})", "extras.luxel.sky.radiance"},
        {R"({"kind": "daylight", "turbidity": "hazy"})", "extras.luxel.sky.turbidity"},
        {R"({"kind": "daylight", "irradiance": -1})", "extras.luxel.sky.irradiance"},
        {R"({"kind": "uniform", "scale": -0.5})", "extras.luxel.sky.scale"}};
    for (const auto& [json, field] : bad) {
        const std::string message =
            error_of([&] { (void)read_sky_extras(nlohmann::json::parse(json)); });
        EXPECT_NE(message.find(field), std::string::npos) << json << " -> '" << message << "'";
    }
}

TEST(SkySpec, ALevelKeepsItsSkyThroughSaveAndLoad) {
    luxel::testing::TempDir dir;
    for (const char* text : {"uniform:0.25,0.5,1", "daylight:2.5,4", "daylight:2.5,4,ground=0.2"}) {
        luxel::scene::Scene room = luxel::testing::box_room();
        room.sky = parse_sky(text);
        room.sky.scale = 2.0f;
        luxel::scene::save_gltf(room, dir / "room.glb");
        EXPECT_EQ(luxel::scene::load_gltf(dir / "room.glb").sky, room.sky) << text;
    }
    // A map given by an absolute path (the command line's, or one resolved at load) is not
    // written: a level names its map relative to its folder (tests/scene/sky_map_file_test).
    luxel::scene::Scene room = luxel::testing::box_room();
    room.sky = parse_sky((dir / "noon.exr").string());
    luxel::scene::save_gltf(room, dir / "room.glb");
    EXPECT_EQ(luxel::scene::load_gltf(dir / "room.glb").sky.kind, SkySpec::Kind::None);
}

TEST(SkySpec, AWrongSkyInAFileFailsTheLoadNamingTheFileAndTheField) {
    luxel::testing::TempDir dir;
    luxel::scene::Scene room = luxel::testing::box_room();
    room.sky = parse_sky("uniform:1");
    std::vector<std::uint8_t> bytes =
        luxel::scene::save_gltf_to_memory(room, luxel::scene::GltfContainer::EmbeddedText);
    std::string text(bytes.begin(), bytes.end());
    const std::string good = R"("uniform")";
    const std::size_t at = text.find(good);
    ASSERT_NE(at, std::string::npos) << text.substr(0, 400);
    text.replace(at, good.size(), R"("rainbow")");
    const std::vector<std::uint8_t> broken(text.begin(), text.end());
    const std::string message =
        error_of([&] { (void)luxel::scene::load_gltf_from_memory(broken, "broken.gltf"); });
    EXPECT_NE(message.find("broken.gltf"), std::string::npos) << message;
    EXPECT_NE(message.find("extras.luxel.sky.kind"), std::string::npos) << message;
}

}  // namespace
