// luxel-frame-error as a user runs it: a frame with one patch wrong against its reference. The
// whole-frame figure hides the patch; the region over it shows it whole.

#include <filesystem>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "luxel/runtime/image.hpp"
#include "run_command.hpp"
#include "test_paths.hpp"

namespace {

using luxel::testing::quoted;
using luxel::testing::run_command;

const std::string kTool = luxel::testing::program("luxel-frame-error");

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

// --picture: frame | reference | difference at one exposure; the patch, darker in the frame,
// is blue in the difference panel and black elsewhere.
TEST(FrameError, APictureShowsThePatchInTheDifferencePanel) {
    const Frames f("picture");
    const std::filesystem::path picture = f.dir / "picture.png";
    const auto r = run_command(kTool, quoted(f.frame) + " " + quoted(f.reference) + " --picture " +
                                          quoted(picture) + " --zoom 2 --exposure 0.1");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const luxel::Image8 png = luxel::read_png(picture);
    ASSERT_EQ(png.width, 3 * 32 * 2 + 2 * 4);
    ASSERT_EQ(png.height, 24 * 2);
    const int difference = 2 * (32 * 2 + 4);  // the third panel's left edge
    // Inside the patch (x 8-16, y 4-8 at zoom 2): blue, no red.
    EXPECT_GT(png.at(difference + 2 * 12, 2 * 6, 2), 0);
    EXPECT_EQ(png.at(difference + 2 * 12, 2 * 6, 0), 0);
    // Outside it: black.
    EXPECT_EQ(png.at(difference + 2 * 24, 2 * 16, 2), 0);
    // The frame and the reference panels agree outside the patch and differ inside it.
    EXPECT_EQ(png.at(2 * 24, 2 * 16, 1), png.at(32 * 2 + 4 + 2 * 24, 2 * 16, 1));
    EXPECT_LT(png.at(2 * 12, 2 * 6, 1), png.at(32 * 2 + 4 + 2 * 12, 2 * 6, 1));
    // A zoom whose picture would pass 64 Mpixels is refused (exit 2, no file) before the
    // picture is allocated: 400 x 240 at 16x would be 3 x 24.6 Mpixels.
    const luxel::Image large(400, 240, glm::vec4(1.0f));
    luxel::write_exr(f.dir / "large.exr", large);
    const std::filesystem::path big = f.dir / "big.png";
    const auto refused =
        run_command(kTool, quoted(f.dir / "large.exr") + " " + quoted(f.dir / "large.exr") +
                               " --picture " + quoted(big) + " --zoom 16");
    EXPECT_EQ(refused.exit_code, 2) << refused.output;
    EXPECT_NE(refused.output.find("would exceed 64 Mpixels"), std::string::npos) << refused.output;
    EXPECT_FALSE(std::filesystem::exists(big));
}

// --crop: the picture of a corner only, at the whole reference's exposure; a crop outside the
// frame or not four numbers is a usage error (exit 2) and leaves no file.
TEST(FrameError, ACropPicturesOnlyItsPixels) {
    const Frames f("crop");
    const std::filesystem::path picture = f.dir / "crop.png";
    const auto r = run_command(kTool, quoted(f.frame) + " " + quoted(f.reference) + " --picture " +
                                          quoted(picture) + " --crop 8,4,20,10 --zoom 3");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const luxel::Image8 png = luxel::read_png(picture);
    ASSERT_EQ(png.width, 3 * 12 * 3 + 2 * 4);
    ASSERT_EQ(png.height, 6 * 3);
    const int difference = 2 * (12 * 3 + 4);
    // The crop's first 8 x 4 pixels are the patch (blue in the difference), the rest is not.
    EXPECT_GT(png.at(difference + 3 * 2, 3 * 1, 2), 0);
    EXPECT_EQ(png.at(difference + 3 * 10, 3 * 1, 2), 0);
    EXPECT_EQ(png.at(difference + 3 * 2, 3 * 5, 2), 0);
    for (const std::string bad : {"8,4,40,10", "8,4,8,10", "8,4,20"}) {
        const std::filesystem::path none = f.dir / "none.png";
        const auto refused =
            run_command(kTool, quoted(f.frame) + " " + quoted(f.reference) + " --picture " +
                                   quoted(none) + " --crop " + bad);
        EXPECT_EQ(refused.exit_code, 2) << bad << ": " << refused.output;
        EXPECT_NE(refused.output.find("--crop " + bad), std::string::npos) << refused.output;
        EXPECT_FALSE(std::filesystem::exists(none)) << bad;
    }
}

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
