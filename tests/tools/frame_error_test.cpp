// luxel-frame-error as a user runs it: a frame with one patch wrong against its reference. The
// whole-frame figure hides the patch; the region over it shows it whole.

#include <filesystem>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "luxel/runtime/image.hpp"
#include "run_command.hpp"

namespace {

using luxel::testing::quoted;
using luxel::testing::run_command;

const std::string kTool = LUXEL_FRAME_ERROR_EXECUTABLE;

struct Frames {
    std::filesystem::path dir;
    std::filesystem::path frame;
    std::filesystem::path reference;

    /// A 32 x 24 reference of radiance (1, 2, 3), and the frame: the same with the 8 x 4 patch
    /// x in [8, 16), y in [4, 8) at half.
    explicit Frames(const std::string& name)
        : dir(std::filesystem::temp_directory_path() / ("luxel_frame_error_" + name)) {
        std::filesystem::create_directories(dir);
        luxel::Image truth(32, 24, glm::vec4(1.0f, 2.0f, 3.0f, 1.0f));
        luxel::Image shown = truth;
        for (int y = 4; y < 8; ++y) {
            for (int x = 8; x < 16; ++x) {
                shown.set_pixel(x, y, glm::vec4(0.5f, 1.0f, 1.5f, 1.0f));
            }
        }
        frame = dir / "frame.exr";
        reference = dir / "reference.exr";
        luxel::write_exr(frame, shown);
        luxel::write_exr(reference, truth);
    }
    ~Frames() { std::filesystem::remove_all(dir); }
    Frames(const Frames&) = delete;
    Frames& operator=(const Frames&) = delete;
};

TEST(FrameError, ARegionShowsThePatchTheWholeFrameDilutes) {
    const Frames f("patch");
    const auto r = run_command(kTool, quoted(f.frame) + " " + quoted(f.reference) +
                                          " --region 8,4,16,8 --region 16,8,32,24 --block 2");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    // The patch: every block at half, so relRMSE 50% and the means' ratio 0.5.
    EXPECT_NE(r.output.find("region 8,4,16,8: relRMSE 50.00%, mean ratio 0.5000 (8 blocks of 2x2); "
                            "mean RGB 0.5 1 1.5 against 1 2 3"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("region 16,8,32,24: relRMSE 0.00%, mean ratio 1.0000"),
              std::string::npos)
        << r.output;
    // The whole frame: 32 of 768 pixels at half, sqrt(32 / 768) x 50% = 10.21%.
    EXPECT_NE(r.output.find("whole frame: relRMSE 10.21%, mean ratio 0.9792"), std::string::npos)
        << r.output;
}

TEST(FrameError, BadInputGetsOneLineNamingTheCulprit) {
    const Frames f("bad");
    const std::string pair = quoted(f.frame) + " " + quoted(f.reference);
    auto r = run_command(kTool, pair + " --region 8,4,16");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("--region 8,4,16"), std::string::npos) << r.output;
    r = run_command(kTool, pair + " --region 0,0,40,8");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("not inside the 32x24 frame"), std::string::npos) << r.output;
    r = run_command(kTool, quoted(f.frame) + " " + quoted(f.dir / "missing.exr"));
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find("missing.exr"), std::string::npos) << r.output;
    const auto small = f.dir / "small.exr";
    luxel::write_exr(small, luxel::Image(16, 24, glm::vec4(1.0f)));
    r = run_command(kTool, quoted(f.frame) + " " + quoted(small));
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find("small.exr: 16x24"), std::string::npos) << r.output;
    const auto nan = f.dir / "nan.exr";
    luxel::Image broken(32, 24, glm::vec4(1.0f));
    broken.set_pixel(3, 5, glm::vec4(std::numeric_limits<float>::quiet_NaN()));
    luxel::write_exr(nan, broken);
    r = run_command(kTool, quoted(nan) + " " + quoted(f.reference));
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_NE(r.output.find("nan.exr: pixel 3, 5 is not finite"), std::string::npos) << r.output;
}

}  // namespace
