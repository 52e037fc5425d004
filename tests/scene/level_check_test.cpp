// What luxel says at load about a level that lacks a light, a camera or luxel-prep's light-map
// layout (issue 21, "clear words"): one line each, naming the file, in the exact words that
// luxel-sandbox, luxel-ref and luxel-bench print.

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "lacking_levels.hpp"
#include "luxel/scene/level_check.hpp"
#include "temp_dir.hpp"

namespace {

using namespace luxel;
using luxel::testing::saved_as;

std::vector<scene::LevelProblem> problems(const std::vector<scene::LevelDiagnosis>& found) {
    std::vector<scene::LevelProblem> out;
    for (const auto& diagnosis : found) {
        out.push_back(diagnosis.problem);
    }
    return out;
}

TEST(LevelCheck, APreparedLitLevelWithACameraHasNothingToSay) {
    const scene::Scene level = luxel::testing::prepared_cornell();
    EXPECT_TRUE(scene::check_level(level).empty());
    EXPECT_TRUE(scene::is_prepared(level));
    EXPECT_TRUE(scene::has_camera(level));
    EXPECT_TRUE(scene::has_light_or_emission(level));
}

TEST(LevelCheck, NoLightIsOneWarningNamingTheFile) {
    luxel::testing::TempDir dir;
    const std::string file = (dir / "dark.glb").string();
    const scene::Scene level =
        saved_as(luxel::testing::without_light(luxel::testing::prepared_cornell()), file);
    const auto found = scene::check_level(level);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].problem, scene::LevelProblem::NoLight);
    EXPECT_EQ(found[0].message,
              file +
                  ": no light and no emissive material: every frame will be black (add a "
                  "KHR_lights_punctual light or a material with an emissiveFactor)");
}

TEST(LevelCheck, AnEmissiveMaterialIsLightEnough) {
    scene::Scene level = luxel::testing::without_light(luxel::testing::prepared_cornell());
    level.materials[0].emissive = glm::vec3(0.0f, 0.0f, 2.0f);
    EXPECT_TRUE(scene::has_light_or_emission(level));
    EXPECT_TRUE(scene::check_level(level).empty());
    // A material no mesh uses lights nothing.
    level.materials.push_back(level.materials[0]);
    level.materials[0].emissive = glm::vec3(0.0f);
    EXPECT_FALSE(scene::has_light_or_emission(level));
}

TEST(LevelCheck, NoCameraSaysWhichDefaultViewIsUsed) {
    luxel::testing::TempDir dir;
    const std::string file = (dir / "no-camera.glb").string();
    const scene::Scene level =
        saved_as(luxel::testing::without_camera(luxel::testing::prepared_cornell()), file);
    const auto found = scene::check_level(level);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].problem, scene::LevelProblem::NoCamera);
    EXPECT_EQ(found[0].message, file +
                                    ": no camera: using the default view from (0, 1, 3) looking "
                                    "at (0, 1, 0), vertical field of view 60 degrees");
    // A program that does not look through the level's camera is not told.
    scene::LevelCheckOptions options;
    options.uses_camera = false;
    EXPECT_TRUE(scene::check_level(level, options).empty());
}

TEST(LevelCheck, AnUnpreparedLevelIsToldTheCommandToRun) {
    luxel::testing::TempDir dir;
    const std::string file = (dir / "exported.glb").string();
    const scene::Scene level =
        saved_as(luxel::testing::unprepared(luxel::testing::prepared_cornell()), file);
    EXPECT_FALSE(scene::is_prepared(level));
    const auto found = scene::check_level(level);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].problem, scene::LevelProblem::NotPrepared);
    EXPECT_EQ(found[0].message,
              file +
                  ": not prepared for light maps (luxel-prep has not written its light-map "
                  "layout into it): it gets no indirect light; prepare it with: luxel-prep " +
                  file + " -o " + (dir / "exported-prepared.glb").string());
}

TEST(LevelCheck, TheCommandQuotesPathsAShellWouldSplit) {
    EXPECT_EQ(scene::prep_command("levels/my room.glb"),
              "luxel-prep 'levels/my room.glb' -o 'levels/my room-prepared.glb'");
    EXPECT_EQ(scene::prep_command("it's.gltf"),
              "luxel-prep 'it'\\''s.gltf' -o 'it'\\''s-prepared.glb'");
    EXPECT_EQ(scene::prep_command("a/b.gltf"), "luxel-prep a/b.gltf -o a/b-prepared.glb");
}

TEST(LevelCheck, ALevelLackingEverythingGetsEachWarningOnce) {
    const scene::Scene level = luxel::testing::unprepared(luxel::testing::without_camera(
        luxel::testing::without_light(luxel::testing::prepared_cornell())));
    const auto found = scene::check_level(level);
    EXPECT_EQ(problems(found), (std::vector<scene::LevelProblem>{
                                   scene::LevelProblem::NoLight, scene::LevelProblem::NoCamera,
                                   scene::LevelProblem::NotPrepared}));
}

TEST(LevelCheck, OnlyMirrorsAndGlassNeedNoLayout) {
    // luxel-prep light-maps neither (their photons are not stored): a level of glass alone is
    // as prepared as it can be.
    scene::Scene level = luxel::testing::unprepared(luxel::testing::prepared_cornell());
    for (scene::Material& material : level.materials) {
        material.transmission = 1.0f;
    }
    for (scene::Mesh& mesh : level.meshes) {
        for (scene::Primitive& primitive : mesh.primitives) {
            primitive.material = 0;
        }
    }
    EXPECT_TRUE(scene::is_prepared(level));
}

}  // namespace
