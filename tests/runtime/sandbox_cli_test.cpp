// The main job from its command line: --gl egl and --gl osmesa both write a lit PNG and EXR;
// bad flags are clear errors.

#include <sys/wait.h>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "luxel/runtime/image.hpp"
#include "temp_dir.hpp"

namespace {

struct Result {
    int exit_code = -1;
    std::string output;  // stdout and stderr together
};

Result run_sandbox(const std::string& arguments) {
    const std::string command = std::string(LUXEL_SANDBOX_EXECUTABLE) + " " + arguments + " 2>&1";
    Result result;
    FILE* pipe = ::popen(command.c_str(), "r");
    if (pipe == nullptr) {
        return result;
    }
    std::array<char, 4096> buffer{};
    while (std::fgets(buffer.data(), buffer.size(), pipe) != nullptr) {
        result.output += buffer.data();
    }
    const int status = ::pclose(pipe);
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
}

class SandboxHeadless : public ::testing::TestWithParam<std::string> {};

TEST_P(SandboxHeadless, WritesLitPngAndExr) {
    luxel::testing::TempDir out;
    const Result result =
        run_sandbox("--gl " + GetParam() + " --frames 3 --size 96x64 --out " + out.path().string());
    ASSERT_EQ(result.exit_code, 0) << result.output;
    EXPECT_NE(result.output.find("GL renderer:"), std::string::npos) << result.output;
    EXPECT_NE(result.output.find("backend " + GetParam()), std::string::npos) << result.output;

    const luxel::Image exr = luxel::read_exr(out / "test_scene.exr");
    ASSERT_EQ(exr.width, 96);
    ASSERT_EQ(exr.height, 64);
    float brightest = 0.0f;
    std::size_t lit = 0;
    for (float value : exr.rgba) {
        ASSERT_TRUE(std::isfinite(value));
        ASSERT_GE(value, 0.0f);
        brightest = std::max(brightest, value);
    }
    for (int y = 0; y < exr.height; ++y) {
        for (int x = 0; x < exr.width; ++x) {
            lit += exr.pixel(x, y).r > 0.01f ? 1 : 0;
        }
    }
    EXPECT_GT(brightest, 0.1f);
    EXPECT_GT(lit, static_cast<std::size_t>(exr.width * exr.height / 4));
    // The red wall is on the left: there red dominates green.
    const glm::vec4 left = exr.pixel(12, 32);
    EXPECT_GT(left.r, 2.0f * left.g) << left.r << " " << left.g;

    const luxel::Image8 png = luxel::read_png(out / "test_scene.png");
    EXPECT_EQ(png.width, 96);
    EXPECT_EQ(png.height, 64);
}

INSTANTIATE_TEST_SUITE_P(Backends, SandboxHeadless, ::testing::Values("egl", "osmesa"),
                         [](const auto& test) { return test.param; });

TEST(SandboxCli, UnknownGlBackendIsAClearError) {
    const Result result = run_sandbox("--gl vulkan --frames 1");
    EXPECT_NE(result.exit_code, 0);
    EXPECT_NE(result.output.find("vulkan"), std::string::npos) << result.output;
    EXPECT_NE(result.output.find("osmesa"), std::string::npos) << result.output;
}

TEST(SandboxCli, BadSizeAndFramesAreClearErrors) {
    Result result = run_sandbox("--size 640by360");
    EXPECT_NE(result.exit_code, 0);
    EXPECT_NE(result.output.find("WxH"), std::string::npos) << result.output;
    result = run_sandbox("--size 0x10");
    EXPECT_NE(result.exit_code, 0);
    result = run_sandbox("--frames -3");
    EXPECT_NE(result.exit_code, 0);
    EXPECT_NE(result.output.find("--frames"), std::string::npos) << result.output;
}

TEST(SandboxCli, UnwritableOutputDirectoryIsAClearError) {
    luxel::testing::TempDir dir;
    std::FILE* blocker = std::fopen((dir / "blocker").c_str(), "w");
    ASSERT_NE(blocker, nullptr);
    std::fclose(blocker);
    const Result result = run_sandbox("--gl osmesa --frames 1 --size 8x8 --out " +
                                      (dir / "blocker" / "sub").string());
    EXPECT_EQ(result.exit_code, 1) << result.output;
    EXPECT_NE(result.output.find("blocker"), std::string::npos) << result.output;
}

}  // namespace
