// luxel-sandbox in a GLFW window under a private X server (xvfb-run): it opens, runs 30 frames,
// and its last frame is not blank.

#include <gtest/gtest.h>

#include "luxel/runtime/image.hpp"
#include "run_sandbox.hpp"
#include "temp_dir.hpp"

namespace {

TEST(SandboxWindow, RunsThirtyFramesAndItsScreenshotIsNotBlank) {
    luxel::testing::TempDir out;
    const auto result = luxel::testing::run_sandbox(
        "--gl window --frames 30 --size 320x180 --out " + out.path().string());
    ASSERT_EQ(result.exit_code, 0) << result.output;
    const luxel::Image8 shot = luxel::read_png(out / "window_last.png");
    ASSERT_EQ(shot.width, 320);
    ASSERT_EQ(shot.height, 180);
    int lit = 0;
    int brightest = 0;
    for (int y = 0; y < shot.height; ++y) {
        for (int x = 0; x < shot.width; ++x) {
            const int v = shot.at(x, y, 0) + shot.at(x, y, 1) + shot.at(x, y, 2);
            lit += v > 30 ? 1 : 0;
            brightest = std::max(brightest, v);
        }
    }
    EXPECT_GT(lit, shot.width * shot.height / 4) << "most of the frame is black";
    EXPECT_GT(brightest, 200);
}

}  // namespace
