// The luxel-ref executable: errors that name the flag or file at fault, and a tiny run that
// writes a valid EXR frame and JSON light maps.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "luxel/runtime/image.hpp"
#include "run_command.hpp"
#include "temp_dir.hpp"
#include "test_paths.hpp"

namespace {

using namespace luxel;

using luxel::testing::CommandResult;
using luxel::testing::quoted;

CommandResult luxel_ref(const std::string& arguments) {
    return luxel::testing::run_command(luxel::testing::program("luxel-ref"), arguments);
}

TEST(RefCli, ABadFlagIsRejectedByName) {
    const CommandResult run = luxel_ref("--level furnace --bogus 3 -o x.exr");
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.output.find("--bogus"), std::string::npos) << run.output;
}

TEST(RefCli, AMissingLevelIsNamed) {
    luxel::testing::TempDir dir("luxel-ref-cli");
    CommandResult run = luxel_ref("--level no-such-level -o " + quoted(dir / "x.exr"));
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.output.find("no-such-level"), std::string::npos) << run.output;
    run = luxel_ref("--level " + quoted(dir / "missing.glb") + " -o " + quoted(dir / "x.exr"));
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.output.find("missing.glb"), std::string::npos) << run.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "x.exr"));
}

TEST(RefCli, BadValuesAreExplained) {
    CommandResult run = luxel_ref("--level furnace --camera 0,0,0:1,2:60 -o x.exr");
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.output.find("--camera"), std::string::npos) << run.output;
    run = luxel_ref("--level furnace");
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.output.find("-o"), std::string::npos) << run.output;
    run = luxel_ref("--level furnace --spp 0 -o x.exr");
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.output.find("--spp"), std::string::npos) << run.output;
}

// A level within the loaders' lightmap-texels limit can still need more memory for the
// reference's per-texel state than the machine has: luxel-ref counts it once the maps are laid
// out and refuses before allocating it, naming the file and the limit, writing nothing.
TEST(RefCli, LightMapsBeyondTheReferenceMemoryLimitAreRefused) {
    luxel::testing::TempDir dir("luxel-ref-cli");
    const auto frame = dir / "furnace.exr";
    const auto maps = dir / "furnace.json";
    const std::string outputs = " -o " + quoted(frame) + " --lightmaps " + quoted(maps);
    CommandResult run = luxel_ref(
        "--level furnace --spp 1 --passes 1 --width 8 --height 8 "
        "--limit reference-bytes=1k" +
        outputs);
    EXPECT_EQ(run.exit_code, 1) << run.output;
    EXPECT_NE(run.output.find("luxel-ref: error: "), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("furnace.glb"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("reference-bytes"), std::string::npos) << run.output;
    EXPECT_FALSE(std::filesystem::exists(frame));
    EXPECT_FALSE(std::filesystem::exists(maps));
    // The same run within a limit that holds the furnace's texels succeeds.
    run = luxel_ref(
        "--level furnace --spp 1 --passes 1 --width 8 --height 8 "
        "--photons 1000 --indirect-photons 1000 --limit reference-bytes=1G" +
        outputs);
    EXPECT_EQ(run.exit_code, 0) << run.output;
    EXPECT_TRUE(std::filesystem::exists(maps));
}

TEST(RefCli, ATinyRunWritesAFrameAndLightMaps) {
    luxel::testing::TempDir dir("luxel-ref-cli");
    const auto frame = dir / "furnace.exr";
    const auto maps = dir / "furnace.json";
    const CommandResult run = luxel_ref(
        "--level furnace --camera 0,0,0:0,0,-1:70 --width 32 --height 24 --spp 2 "
        "--passes 2 --threads 2 --indirect-photons 200000 -o " +
        quoted(frame) + " --lightmaps " + quoted(maps));
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_NE(run.output.find("pass 2/2"), std::string::npos) << run.output;
    const Image image = read_exr(frame);
    ASSERT_EQ(image.width, 32);
    ASSERT_EQ(image.height, 24);
    // Inside the furnace every pixel sees L = Le / (1 - 0.5) = 2 (noisy at 2 spp).
    double mean = 0.0;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            const glm::vec4 p = image.pixel(x, y);
            ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
            mean += p.x / (32.0 * 24.0);
        }
    }
    EXPECT_NEAR(mean, 2.0, 0.1);
    std::ifstream in(maps);
    const nlohmann::json json = nlohmann::json::parse(in);
    ASSERT_FALSE(json["surfaces"].empty());
    const auto& surface = json["surfaces"][0];
    const std::size_t texels = surface["x"].size();
    EXPECT_GT(texels, 0u);
    for (const char* column :
         {"y", "area", "direct", "direct_se", "indirect", "indirect_se", "caustic", "caustic_se"}) {
        EXPECT_EQ(surface[column].size(), texels) << column;
    }
    EXPECT_EQ(json["samples_per_texel"], 2);
    EXPECT_TRUE(json["relative_standard_error"].contains("indirect"));
}

TEST(RefCli, CausticPixelsAreWrittenAtPixelResolution) {
    luxel::testing::TempDir dir("luxel-ref-cli");
    const auto out = dir / "caustics.exr";
    CommandResult run = luxel_ref("--level caustics --caustic-pixels " + quoted(dir / "c.png"));
    EXPECT_EQ(run.exit_code, 2) << run.output;
    EXPECT_NE(run.output.find("--caustic-pixels"), std::string::npos) << run.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "c.png"));

    // The level's own camera, the caustics alone: no -o frame is traced.
    run = luxel_ref(
        "--level caustics --width 40 --height 30 --photons 2000000 --passes 1 "
        "--threads 2 --caustic-pixels " +
        quoted(out));
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_NE(run.output.find("footprints"), std::string::npos) << run.output;
    const Image image = read_exr(out);
    ASSERT_EQ(image.width, 40);
    ASSERT_EQ(image.height, 30);
    int lit = 0;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            const glm::vec4 p = image.pixel(x, y);
            ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
            ASSERT_GE(std::min({p.x, p.y, p.z}), 0.0f);
            lit += p.x + p.y + p.z > 0.0f ? 1 : 0;
        }
    }
    // The ring's, the sphere's and the pool's caustics cover part of the view, not all of it.
    EXPECT_GT(lit, 10) << "the level's caustics are in view";
    EXPECT_LT(lit, 40 * 30);
}

}  // namespace
