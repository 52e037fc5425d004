// The luxel-ref executable: errors that name the flag or file at fault, and a tiny run that
// writes a valid EXR frame and JSON light maps.

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>

#include <sys/wait.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "luxel/runtime/image.hpp"
#include "temp_dir.hpp"

namespace {

using namespace luxel;

struct CommandResult {
    int exit_code = -1;
    std::string output;  ///< stdout and stderr together
};

CommandResult luxel_ref(const std::string& arguments) {
    const std::string command =
        std::string("'") + LUXEL_REF_EXECUTABLE + "' " + arguments + " 2>&1";
    CommandResult run;
    FILE* pipe = popen(command.c_str(), "r");
    if (pipe == nullptr) {
        return run;
    }
    std::array<char, 4096> chunk{};
    while (std::fgets(chunk.data(), static_cast<int>(chunk.size()), pipe) != nullptr) {
        run.output += chunk.data();
    }
    const int status = pclose(pipe);
    run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return run;
}

std::string quoted(const std::filesystem::path& path) {
    // Appended, not "'" + string: GCC 12 warns (-Wrestrict) on that insert falsely.
    std::string text("'");
    text += path.string();
    text += "'";
    return text;
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

TEST(RefCli, ATinyRunWritesAFrameAndLightMaps) {
    luxel::testing::TempDir dir("luxel-ref-cli");
    const auto frame = dir / "furnace.exr";
    const auto maps = dir / "furnace.json";
    const CommandResult run = luxel_ref(
        "--level furnace --camera 0,0,0:0,0,-1:70 --width 32 --height 24 --spp 2 "
        "--passes 2 --threads 2 -o " +
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

}  // namespace
