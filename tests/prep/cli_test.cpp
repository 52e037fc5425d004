// The luxel-prep executable: its command line, report, page pictures, errors that name the
// file or flag at fault, and output that does not depend on --threads.

#include <cstdio>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "luxel/runtime/image.hpp"
#include "luxel/scene/gltf.hpp"
#include "prep_test_support.hpp"
#include "run_command.hpp"
#include "temp_dir.hpp"
#include "test_paths.hpp"

namespace {

using namespace luxel;

using luxel::testing::CommandResult;
using luxel::testing::quoted;

CommandResult luxel_prep(const std::string& arguments) {
    return luxel::testing::run_command(luxel::testing::program("luxel-prep"), arguments);
}

std::vector<char> read_bytes(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(PrepCli, PreparesALevelAndWritesTheReportAndPagePictures) {
    luxel::testing::TempDir dir("luxel-prep-cli");
    const auto output = dir / "cornell.glb";
    const auto report = dir / "cornell.json";
    const CommandResult run =
        luxel_prep(quoted(luxel::testing::level_file("cornell")) + " -o " + quoted(output) +
                   " --texel-size 0.05 --crease-deg 45 --padding 1 --report " + quoted(report));
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_NE(run.output.find("packing efficiency"), std::string::npos) << run.output;
    // Not a terminal: no progress bar, no carriage returns.
    EXPECT_EQ(run.output.find('\r'), std::string::npos);

    const scene::Scene prepared = scene::load_gltf(output);
    EXPECT_TRUE(luxel::testing::check_light_map_pages(prepared, 1).failures.empty());

    std::ifstream in(report);
    const nlohmann::json json = nlohmann::json::parse(in);
    for (const char* key : {"surfaces", "charts", "texels", "pages", "page_size",
                            "packing_efficiency", "stretch", "stage_ms", "nodes", "repairs"}) {
        EXPECT_TRUE(json.contains(key)) << key;
    }
    EXPECT_GE(json["packing_efficiency"].get<double>(), 0.7);
    EXPECT_LE(json["stretch"]["max"].get<double>(), 1.5);
    for (const char* stage :
         {"load", "geometry", "surfaces", "charts", "packing", "output", "save"}) {
        EXPECT_TRUE(json["stage_ms"].contains(stage)) << stage;
    }
    const int pages = json["pages"].get<int>();
    ASSERT_GE(pages, 1);
    for (int page = 0; page < pages; ++page) {
        const auto picture = dir / ("cornell.page" + std::to_string(page) + ".png");
        ASSERT_TRUE(std::filesystem::exists(picture)) << picture;
        const Image8 image = read_png(picture);
        EXPECT_GE(image.width, json["page_size"].get<int>());
        EXPECT_EQ(image.width, image.height);
    }
}

// A level's sky map (named beside it, in its extras) goes with the prepared level: copied
// beside the output as <stem>.sky.exr when the output is in another folder, named where it is
// when the output's folder holds it already.
TEST(PrepCli, ALevelsSkyMapGoesWithThePreparedLevel) {
    luxel::testing::TempDir dir("luxel-prep-sky");
    std::filesystem::create_directories(dir / "source" / "skies");
    std::filesystem::create_directories(dir / "prepared");
    write_exr(dir / "source" / "skies" / "noon.exr",
              Image(8, 4, glm::vec4(1.0f, 0.5f, 0.25f, 1.0f)));
    scene::Scene level = scene::load_gltf(luxel::testing::level_file("cornell"));
    level.sky.kind = scene::SkySpec::Kind::Map;
    level.sky.map = "skies/noon.exr";
    scene::save_gltf(level, dir / "source" / "room.glb");

    const CommandResult moved = luxel_prep(quoted(dir / "source" / "room.glb") + " -o " +
                                           quoted(dir / "prepared" / "room.glb"));
    ASSERT_EQ(moved.exit_code, 0) << moved.output;
    const std::filesystem::path copy = dir / "prepared" / "room.sky.exr";
    EXPECT_NE(moved.output.find("sky map: " + copy.string()), std::string::npos) << moved.output;
    EXPECT_EQ(read_bytes(copy), read_bytes(dir / "source" / "skies" / "noon.exr"));
    const scene::Scene prepared = scene::load_gltf(dir / "prepared" / "room.glb");
    EXPECT_EQ(prepared.sky.kind, scene::SkySpec::Kind::Map);
    EXPECT_EQ(prepared.sky.map, std::filesystem::canonical(copy));

    const CommandResult beside = luxel_prep(quoted(dir / "source" / "room.glb") + " -o " +
                                            quoted(dir / "source" / "room-prepared.glb"));
    ASSERT_EQ(beside.exit_code, 0) << beside.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "source" / "room-prepared.sky.exr"));
    EXPECT_EQ(scene::load_gltf(dir / "source" / "room-prepared.glb").sky.map,
              std::filesystem::canonical(dir / "source" / "skies" / "noon.exr"));
}

TEST(PrepCli, OutputDoesNotDependOnThreads) {
    luxel::testing::TempDir dir("luxel-prep-cli");
    for (const std::string threads : {"1", "2"}) {
        const CommandResult run =
            luxel_prep(quoted(luxel::testing::level_file("two-rooms")) + " -o " +
                       quoted(dir / ("out" + threads + ".glb")) + " --threads " + threads);
        ASSERT_EQ(run.exit_code, 0) << run.output;
    }
    EXPECT_TRUE(read_bytes(dir / "out1.glb") == read_bytes(dir / "out2.glb"));
}

TEST(PrepCli, BadInputIsAClearErrorNamingTheFile) {
    luxel::testing::TempDir dir("luxel-prep-cli");
    const auto missing = dir / "missing.glb";
    CommandResult run = luxel_prep(quoted(missing) + " -o " + quoted(dir / "out.glb"));
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.output.find("missing.glb"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("error"), std::string::npos) << run.output;

    const auto garbage = dir / "garbage.glb";
    std::ofstream(garbage) << "glTF? not really";
    run = luxel_prep(quoted(garbage) + " -o " + quoted(dir / "out.glb"));
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.output.find("garbage.glb"), std::string::npos) << run.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.glb"));
}

// --limit reaches luxel-prep's own checks: the triangles it copies, and the light-map texels
// of the level it writes (what the loaders would refuse); the file is named, nothing written.
TEST(PrepCli, LoadLimitsBoundWhatLuxelPrepCopiesAndWrites) {
    luxel::testing::TempDir dir("luxel-prep-cli");
    const auto output = dir / "cornell.glb";
    const std::string input = quoted(luxel::testing::level_file("cornell"));
    for (const char* limit : {"prep-triangles", "lightmap-texels"}) {
        const CommandResult run =
            luxel_prep(input + " -o " + quoted(output) + " --limit " + std::string(limit) + "=1k");
        EXPECT_EQ(run.exit_code, 1) << run.output;
        EXPECT_NE(run.output.find("cornell.glb: "), std::string::npos) << run.output;
        EXPECT_NE(run.output.find(limit), std::string::npos) << run.output;
        EXPECT_FALSE(std::filesystem::exists(output));
    }
}

TEST(PrepCli, BadFlagsAreClearErrorsNamingTheFlag) {
    luxel::testing::TempDir dir("luxel-prep-cli");
    const std::string files =
        quoted(luxel::testing::level_file("cornell")) + " -o " + quoted(dir / "out.glb");
    const std::pair<const char*, const char*> cases[] = {
        {"--texel-size 0", "--texel-size"},
        {"--texel-size abc", "--texel-size"},
        {"--crease-deg 181", "--crease-deg"},
        {"--padding -2", "--padding"},
        {"--page-size 1", "--page-size"},
        {"--threads -1", "--threads"},
        {"--min-texels-across -1", "--min-texels-across"},
        {"--texel-budget -5", "--texel-budget"},
        {"--hidden-texel-scale 0.5", "--hidden-texel-scale"},
        {"--hidden-texel-scale 65", "--hidden-texel-scale"},
    };
    for (const auto& [flags, mention] : cases) {
        const CommandResult run = luxel_prep(files + " " + flags);
        EXPECT_NE(run.exit_code, 0) << flags;
        EXPECT_NE(run.output.find(mention), std::string::npos) << flags << ": " << run.output;
    }
    const CommandResult no_output = luxel_prep(quoted(luxel::testing::level_file("cornell")));
    EXPECT_NE(no_output.exit_code, 0);
    EXPECT_NE(no_output.output.find("--output"), std::string::npos) << no_output.output;
}

TEST(PrepCli, EmptySceneIsPreparedWithAWarning) {
    luxel::testing::TempDir dir("luxel-prep-cli");
    const auto empty = dir / "empty.gltf";
    scene::save_gltf(scene::Scene{}, empty, {.embed_buffers = true});
    const CommandResult run = luxel_prep(quoted(empty) + " -o " + quoted(dir / "out.glb"));
    EXPECT_EQ(run.exit_code, 0) << run.output;
    EXPECT_NE(run.output.find("warning"), std::string::npos) << run.output;
    EXPECT_TRUE(std::filesystem::exists(dir / "out.glb"));
}

}  // namespace
