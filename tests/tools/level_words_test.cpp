// A level that lacks a light, a camera or luxel-prep's light-map layout runs to the end in
// luxel-sandbox, luxel-ref and luxel-bench (exit 0), and each says so once at load in the same
// words, naming the file (issue 21, "clear words"); an unprepared one is prepared at load, or
// with --no-auto-prep refused with the command to run. The words themselves are pinned in
// tests/scene/level_check_test.cpp and tests/prep/auto_prep_test.cpp; here the programs must
// print them.

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "lacking_levels.hpp"
#include "luxel/scene/level_check.hpp"
#include "run_command.hpp"
#include "temp_dir.hpp"
#include "test_paths.hpp"

namespace {

using namespace luxel;
using luxel::testing::CommandResult;
using luxel::testing::quoted;
using luxel::testing::run_command;

std::size_t count(const std::string& text, const std::string& what) {
    std::size_t found = 0;
    for (std::size_t at = text.find(what); at != std::string::npos;
         at = text.find(what, at + what.size())) {
        ++found;
    }
    return found;
}

/// The warning line luxel::log writes for `problem` of the level saved as `file`.
std::string warning(const scene::Scene& level, scene::LevelProblem problem) {
    return "[luxel warn ] " + scene::diagnosis_text(level, problem) + "\n";
}

struct LackingLevel {
    luxel::testing::TempDir dir{"luxel-level-words"};
    std::filesystem::path file;
    scene::Scene level;

    LackingLevel(const scene::Scene& source, const std::string& name)
        : file(dir / name), level(luxel::testing::saved_as(source, dir / name)) {}
};

CommandResult sandbox(const LackingLevel& lacking, const std::string& more = "") {
    return run_command(luxel::testing::program("luxel-sandbox"),
                       "--gl egl --frames 2 --size 64x36 --threads 2 --level " +
                           quoted(lacking.file) + " --out " + quoted(lacking.dir / "out") + more);
}

CommandResult ref(const LackingLevel& lacking, const std::string& more = "") {
    return run_command(luxel::testing::program("luxel-ref"),
                       "--spp 1 --passes 1 --width 16 --height 12 --photons 1000 "
                       "--indirect-photons 1000 --threads 2 --level " +
                           quoted(lacking.file) + " -o " + quoted(lacking.dir / "ref.exr") + more);
}

TEST(LevelWords, ALevelWithoutLightIsNamedOnceAndItsWarmUpStopsSayingWhy) {
    const LackingLevel dark(luxel::testing::without_light(luxel::testing::prepared_cornell()),
                            "dark.glb");
    const std::string expected = warning(dark.level, scene::LevelProblem::NoLight);
    const CommandResult run = sandbox(dark);
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_EQ(count(run.output, expected), 1u) << run.output;
    EXPECT_EQ(count(run.output, "[luxel warn ] "), 2u) << run.output;  // and the warm-up's
    EXPECT_NE(run.output.find("[luxel warn ] " + dark.file.string() +
                              ": lighting warm-up stopped after 1 update ("),
              std::string::npos)
        << run.output;
    EXPECT_NE(run.output.find(" ms): no progress possible (no light in the scene: no lighting "
                              "work)\n"),
              std::string::npos)
        << run.output;
    const CommandResult reference = ref(dark);
    ASSERT_EQ(reference.exit_code, 0) << reference.output;
    EXPECT_EQ(count(reference.output, expected), 1u) << reference.output;
}

TEST(LevelWords, ALevelWithoutACameraIsShownFromTheDefaultViewItNames) {
    const LackingLevel open(luxel::testing::without_camera(luxel::testing::prepared_cornell()),
                            "no-camera.glb");
    const std::string expected = warning(open.level, scene::LevelProblem::NoCamera);
    const CommandResult run = sandbox(open, " --warm-up-ms 0");
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_EQ(count(run.output, expected), 1u) << run.output;
    // luxel-ref used to refuse it; it now renders the same default view and says so.
    const CommandResult reference = ref(open);
    ASSERT_EQ(reference.exit_code, 0) << reference.output;
    EXPECT_EQ(count(reference.output, expected), 1u) << reference.output;
    EXPECT_TRUE(std::filesystem::exists(open.dir / "ref.exr"));
    // So does luxel-bench's image error.
    const CommandResult bench = run_command(
        luxel::testing::program("luxel-bench"),
        "--budgets 8 --frames 2 --change none --ref-photons 100000 --ref-caustic-photons 50000 "
        "--ref-spp 1 --image 16x12 --image-spp 1 --threads 2 --level " +
            quoted(open.file) + " --out " + quoted(open.dir / "bench"));
    ASSERT_EQ(bench.exit_code, 0) << bench.output;
    EXPECT_EQ(count(bench.output, expected), 1u) << bench.output;
}

TEST(LevelWords, AnUnpreparedLevelIsPreparedAtLoadOrRefusedWithTheCommand) {
    const LackingLevel exported(luxel::testing::unprepared(luxel::testing::prepared_cornell()),
                                "exported.glb");
    const std::string cache = " --prep-cache " + quoted(exported.dir / "cache");
    const std::string unprepared = scene::not_prepared_text(exported.level);
    const std::string command = scene::prep_command(exported.file);
    ASSERT_NE(command.find("luxel-prep " + exported.file.string() + " -o "), std::string::npos);
    const std::string preparing = "[luxel warn ] " + unprepared +
                                  ": preparing it in memory with luxel-prep's pipeline (to "
                                  "prepare it for good: " +
                                  command + ")\n";
    CommandResult run = sandbox(exported, cache + " --warm-up-ms 0");
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_EQ(count(run.output, preparing), 1u) << run.output;
    EXPECT_EQ(count(run.output, "[luxel warn ] "), 1u) << run.output;
    EXPECT_EQ(count(run.output,
                    "[luxel info ] " + exported.file.string() + ": prepared for light maps in "),
              1u)
        << run.output;
    // luxel-ref and luxel-bench prepare the same way: here they find what the sandbox cached.
    const std::string from_cache =
        "[luxel info ] " + exported.file.string() + ": light-map layout from the cache: ";
    run = ref(exported, cache);
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_EQ(count(run.output, preparing), 1u) << run.output;
    EXPECT_EQ(count(run.output, from_cache), 1u) << run.output;

    // Refused, it is an error that gives the command, in every program.
    const std::string refused = unprepared +
                                ", and --no-auto-prep refuses to prepare it at load; prepare it "
                                "with: " +
                                command + ", then run that file\n";
    run = sandbox(exported, " --no-auto-prep");
    EXPECT_EQ(run.exit_code, 1) << run.output;
    EXPECT_EQ(count(run.output, "luxel-sandbox: error: " + refused), 1u) << run.output;
    run = ref(exported, " --no-auto-prep");
    EXPECT_EQ(run.exit_code, 1) << run.output;
    EXPECT_EQ(count(run.output, "luxel-ref: error: " + refused), 1u) << run.output;
    run = run_command(luxel::testing::program("luxel-bench"),
                      "--no-auto-prep --no-image --level " + quoted(exported.file) + " --out " +
                          quoted(exported.dir / "bench"));
    EXPECT_EQ(run.exit_code, 1) << run.output;
    EXPECT_EQ(count(run.output, "luxel-bench: error: " + refused), 1u) << run.output;
}

}  // namespace
