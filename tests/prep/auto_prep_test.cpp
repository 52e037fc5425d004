// A level luxel-prep never prepared is prepared at load with its pipeline (prep::load_playable,
// what luxel-sandbox, luxel-ref and luxel-bench call): the words it prints, the cache keyed by
// the file's content, the refusal that gives the command to run, and a warm-up that then
// converges instead of stopping without light maps (issue 21).

#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "lacking_levels.hpp"
#include "luxel/ecs/transform_system.hpp"
#include "luxel/lighting/core/lighting_system.hpp"
#include "luxel/prep/auto_prep.hpp"
#include "luxel/runtime/clock.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/runtime/image.hpp"
#include "luxel/world/scene_instance.hpp"
#include "temp_dir.hpp"
#include "test_paths.hpp"
#include "ticking_clock.hpp"

namespace {

using namespace luxel;

struct Unprepared {
    luxel::testing::TempDir dir{"luxel-auto-prep"};
    std::filesystem::path file = dir / "exported.glb";
    std::filesystem::path cache = dir / "cache";
    prep::PlayableLevel settings;

    Unprepared() {
        scene::save_gltf(luxel::testing::unprepared(luxel::testing::prepared_cornell()), file);
        settings.prep.cache_dir = cache;
    }

    /// load_playable's result and what it printed.
    std::shared_ptr<const scene::Scene> load(std::string& printed) const {
        JobSystem jobs(2);
        ::testing::internal::CaptureStderr();
        std::shared_ptr<const scene::Scene> level;
        try {
            level = prep::load_playable(file, settings, jobs);
        } catch (...) {
            printed = ::testing::internal::GetCapturedStderr();
            throw;
        }
        printed = ::testing::internal::GetCapturedStderr();
        return level;
    }

    [[nodiscard]] std::size_t cached_files() const {
        std::size_t count = 0;
        std::error_code ignored;
        for (const auto& entry : std::filesystem::directory_iterator(cache, ignored)) {
            count += entry.path().extension() == ".glb" ? 1 : 0;
        }
        return count;
    }
};

TEST(AutoPrep, AnUnpreparedLevelIsPreparedAtLoadAndCachedByItsContent) {
    const Unprepared level;
    std::string printed;
    const auto prepared = level.load(printed);
    EXPECT_TRUE(scene::is_prepared(*prepared));
    EXPECT_EQ(prepared->source, level.file.string());
    const std::string name = level.file.string();
    EXPECT_NE(printed.find("[luxel warn ] " + name +
                           ": not prepared for light maps (luxel-prep has not written its "
                           "light-map layout into it): preparing it in memory with luxel-prep's "
                           "pipeline (to prepare it for good: luxel-prep " +
                           name + " -o " + (level.dir / "exported-prepared.glb").string() + ")\n"),
              std::string::npos)
        << printed;
    const std::filesystem::path cached =
        level.cache / (prep::content_key(level.file, *prepared, prep::options_within({})) + ".glb");
    EXPECT_NE(printed.find("[luxel info ] " + name + ": prepared for light maps in "),
              std::string::npos)
        << printed;
    EXPECT_NE(printed.find(" texels; cached as " + cached.string() + "\n"), std::string::npos)
        << printed;
    EXPECT_TRUE(std::filesystem::is_regular_file(cached));
    EXPECT_EQ(level.cached_files(), 1u);

    // The second load reads the cache, and says so.
    const auto again = level.load(printed);
    EXPECT_TRUE(scene::is_prepared(*again));
    EXPECT_EQ(again->source, level.file.string());
    EXPECT_NE(printed.find("[luxel info ] " + name +
                           ": light-map layout from the cache: " + cached.string() + "\n"),
              std::string::npos)
        << printed;
    EXPECT_EQ(printed.find("prepared for light maps in"), std::string::npos) << printed;
    EXPECT_EQ(again->meshes.size(), prepared->meshes.size());

    // Another file content is another key: the level is prepared again, beside the first.
    scene::Scene edited = luxel::testing::unprepared(luxel::testing::prepared_cornell());
    edited.nodes[0].translation.y += 0.01f;
    scene::save_gltf(edited, level.file);
    (void)level.load(printed);
    EXPECT_NE(printed.find("prepared for light maps in"), std::string::npos) << printed;
    EXPECT_EQ(level.cached_files(), 2u);
}

// The sky map a level names beside it stays the level's through the cache: the cache's copy
// of the prepared level names no file (it lives in another folder), and the level's own sky is
// taken on the way out of the cache as on the way in.
TEST(AutoPrep, ALevelsSkyMapIsKeptWhenItsPreparationComesFromTheCache) {
    Unprepared level;
    luxel::write_exr(level.dir / "noon.exr", Image(8, 4, glm::vec4(0.5f, 0.6f, 0.9f, 1.0f)));
    scene::Scene with_map = luxel::testing::unprepared(luxel::testing::prepared_cornell());
    with_map.sky.kind = scene::SkySpec::Kind::Map;
    with_map.sky.map = "noon.exr";
    scene::save_gltf(with_map, level.file);
    const std::filesystem::path map = std::filesystem::canonical(level.dir / "noon.exr");
    std::string printed;
    const auto first = level.load(printed);
    EXPECT_NE(printed.find("prepared for light maps in"), std::string::npos) << printed;
    EXPECT_EQ(first->sky.kind, scene::SkySpec::Kind::Map);
    EXPECT_EQ(first->sky.map, map);
    const auto cached = level.load(printed);
    EXPECT_NE(printed.find("light-map layout from the cache"), std::string::npos) << printed;
    EXPECT_EQ(cached->sky.kind, scene::SkySpec::Kind::Map);
    EXPECT_EQ(cached->sky.map, map);
}

TEST(AutoPrep, RefusedItIsAnErrorThatGivesTheCommand) {
    Unprepared level;
    level.settings.prep.enabled = false;
    std::string printed;
    const std::string name = level.file.string();
    try {
        (void)level.load(printed);
        FAIL() << "an unprepared level loaded with auto-prep refused";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()),
                  name +
                      ": not prepared for light maps (luxel-prep has not written its light-map "
                      "layout into it), and --no-auto-prep refuses to prepare it at load; "
                      "prepare it with: luxel-prep " +
                      name + " -o " + (level.dir / "exported-prepared.glb").string() +
                      ", then run that file");
    }
    EXPECT_EQ(level.cached_files(), 0u);
}

TEST(AutoPrep, APreparedLevelIsLoadedAsItIs) {
    luxel::testing::TempDir dir("luxel-auto-prep");
    prep::PlayableLevel settings;
    settings.prep.cache_dir = dir / "cache";
    settings.prep.enabled = false;  // never needed
    const std::filesystem::path file =
        luxel::testing::source_dir() / "assets" / "levels" / "prepared" / "cornell.glb";
    JobSystem jobs(2);
    ::testing::internal::CaptureStderr();
    const auto level = prep::load_playable(file, settings, jobs);
    const std::string printed = ::testing::internal::GetCapturedStderr();
    EXPECT_TRUE(scene::is_prepared(*level));
    EXPECT_EQ(printed, "");
    EXPECT_FALSE(std::filesystem::exists(dir / "cache"));
}

using luxel::testing::TickingClock;

TEST(AutoPrep, TheWarmUpOfAnUnpreparedLevelConvergesOncePrepared) {
    const Unprepared level;
    std::string printed;
    ecs::Registry registry;
    const world::SceneInstance instance = world::instantiate(registry, level.load(printed));
    ecs::TransformSystem(registry).update();
    JobSystem jobs(2);
    TickingClock clock;
    lighting::LightingConfig config;
    config.photons.selective.groups = 16;
    config.photons.selective.per_group = 8;
    config.gather.rays_per_texel = 8;
    config.texels_per_gather_unit = 4096;
    lighting::LightingSystem lighting(registry, jobs, config, clock);
    const lighting::WarmUpResult result = lighting.warm_up(0.0, 1e6);
    EXPECT_EQ(result.end, lighting::WarmUpEnd::Converged) << lighting::describe(result);
    EXPECT_GT(lighting.maps().counters().texels_gathered, 0u);
    EXPECT_LT(result.updates, 1000);
}

}  // namespace
