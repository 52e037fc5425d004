// luxel-sandbox headless: 60 frames of the sandbox level on EGL and on OSMesa write frames and a
// report with every field; with a fixed camera, frames differ where objects move and not where
// nothing does; bad flags and a missing level are clear errors.

#include <cmath>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "luxel/runtime/image.hpp"
#include "run_sandbox.hpp"
#include "temp_dir.hpp"

namespace {

using luxel::testing::run_sandbox;

class SandboxHeadless : public ::testing::TestWithParam<std::string> {};

TEST_P(SandboxHeadless, SixtyFramesWriteFramesAndACompleteReport) {
    luxel::testing::TempDir out;
    const auto result =
        run_sandbox("--gl " + GetParam() + " --frames 60 --size 160x90 --png-every 20 --out " +
                    out.path().string());
    ASSERT_EQ(result.exit_code, 0) << result.output;
    EXPECT_NE(result.output.find("frame"), std::string::npos) << result.output;
    for (const char* name :
         {"frame_0000.png", "frame_0020.png", "frame_0040.png", "frame_0059.png"}) {
        const luxel::Image8 png = luxel::read_png(out / name);
        EXPECT_EQ(png.width, 160) << name;
        EXPECT_EQ(png.height, 90) << name;
    }
    std::ifstream in(out / "report.json");
    ASSERT_TRUE(in.good());
    const nlohmann::json report = nlohmann::json::parse(in);
    EXPECT_EQ(report["frames"].get<int>(), 60);
    EXPECT_EQ(report["info"]["level"].get<std::string>(), "sandbox");
    EXPECT_EQ(report["info"]["gl_backend"].get<std::string>(), GetParam());
    EXPECT_FALSE(report["info"]["gl_renderer"].get<std::string>().empty());
    for (const char* field : {"median", "p95", "max"}) {
        EXPECT_GT(report["frame_ms"][field].get<double>(), 0.0) << field;
        EXPECT_GE(report["lighting_ms"][field].get<double>(), 0.0) << field;
    }
    EXPECT_DOUBLE_EQ(report["lighting_ms"]["budget_ms"].get<double>(), 4.0);
    EXPECT_TRUE(report["lighting_ms"].contains("frames_over_budget"));
    for (const char* pass : {"shadows", "gbuffer", "direct", "indirect", "composite"}) {
        EXPECT_TRUE(report["pass_ms"].contains(pass)) << pass;
    }
    for (const char* counter : {"photons_traced", "texels_gathered", "aim_texels", "work_units",
                                "units_pending", "stored_hits", "caustic_photons_traced"}) {
        EXPECT_TRUE(report["counters"].contains(counter)) << counter;
    }
    // Sixty frames of a moving level at 4 ms: photons were traced and texels gathered.
    EXPECT_GT(report["counters"]["photons_traced"]["total"].get<double>(), 0.0);
    EXPECT_GT(report["counters"]["texels_gathered"]["total"].get<double>(), 0.0);
}

INSTANTIATE_TEST_SUITE_P(Backends, SandboxHeadless, ::testing::Values("egl", "osmesa"),
                         [](const auto& test) { return test.param; });

/// Mean absolute difference of two linear frames over a rectangle.
double difference(const luxel::Image& a, const luxel::Image& b, int x0, int y0, int x1, int y1) {
    double sum = 0.0;
    int count = 0;
    for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
            const glm::vec4 d = a.pixel(x, y) - b.pixel(x, y);
            sum += std::abs(d.r) + std::abs(d.g) + std::abs(d.b);
            ++count;
        }
    }
    return count > 0 ? sum / count : 0.0;
}

TEST(SandboxFrames, DifferWhereObjectsMoveAndNotWhereNothingDoes) {
    // The Cornell box from its own camera, lighting paused (budget 0): the cube slides and the
    // sphere orbits over the floor, the light and the ceiling stay put.
    luxel::testing::TempDir out;
    const auto result = run_sandbox(
        "--level cornell --gl egl --frames 31 --size 128x128 --camera fixed --budget-ms 0 "
        "--exr --png-every 0 --out " +
        out.path().string());
    ASSERT_EQ(result.exit_code, 0) << result.output;
    const luxel::Image first = luxel::read_exr(out / "frame_0001.exr");
    const luxel::Image later = luxel::read_exr(out / "frame_0030.exr");
    ASSERT_EQ(first.width, 128);
    double total = 0.0;
    for (float v : first.rgba) {
        ASSERT_TRUE(std::isfinite(v));
        total += v;
    }
    ASSERT_GT(total, 0.0) << "the frame is black";
    // The lower half holds the floor, the cube and the sphere; the top rows the ceiling.
    const double moving = difference(first, later, 0, 64, 128, 128);
    const double still = difference(first, later, 16, 0, 112, 12);
    EXPECT_GT(moving, 1e-4);
    EXPECT_LT(still, 1e-6) << "moving " << moving;
}

TEST(SandboxCli, BadFlagsAndMissingLevelsAreClearErrors) {
    auto result = run_sandbox("--gl vulkan --frames 1");
    EXPECT_NE(result.exit_code, 0);
    EXPECT_NE(result.output.find("vulkan"), std::string::npos) << result.output;
    result = run_sandbox("--size 640by360");
    EXPECT_NE(result.exit_code, 0);
    EXPECT_NE(result.output.find("WxH"), std::string::npos) << result.output;
    result = run_sandbox("--frames -3");
    EXPECT_NE(result.exit_code, 0);
    EXPECT_NE(result.output.find("--frames"), std::string::npos) << result.output;
    result = run_sandbox("--budget-ms -1");
    EXPECT_NE(result.exit_code, 0);
    result = run_sandbox("--terms direct,sparkles");
    EXPECT_NE(result.exit_code, 0);
    EXPECT_NE(result.output.find("sparkles"), std::string::npos) << result.output;
    result = run_sandbox("--level no-such-level --frames 1");
    EXPECT_EQ(result.exit_code, 1) << result.output;
    EXPECT_NE(result.output.find("no-such-level"), std::string::npos) << result.output;
    luxel::testing::TempDir dir;
    std::ofstream(dir / "broken.glb") << "not a glTF file";
    result = run_sandbox("--gl osmesa --frames 1 --level " + (dir / "broken.glb").string());
    EXPECT_EQ(result.exit_code, 1) << result.output;
    EXPECT_NE(result.output.find("broken.glb"), std::string::npos) << result.output;
}

TEST(SandboxCli, UnwritableOutputDirectoryIsAClearError) {
    luxel::testing::TempDir dir;
    std::ofstream(dir / "blocker") << "x";
    const auto result = run_sandbox("--gl osmesa --frames 1 --size 8x8 --out " +
                                    (dir / "blocker" / "sub").string());
    EXPECT_EQ(result.exit_code, 1) << result.output;
    EXPECT_NE(result.output.find("blocker"), std::string::npos) << result.output;
}

}  // namespace
