// PNG and EXR round trips, tone mapping, and unreadable files.

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>

#include <gtest/gtest.h>

#include "luxel/runtime/error.hpp"
#include "luxel/runtime/image.hpp"
#include "temp_dir.hpp"

namespace {

luxel::Image gradient(int width, int height) {
    luxel::Image image(width, height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const float u = static_cast<float>(x) / static_cast<float>(width - 1);
            const float v = static_cast<float>(y) / static_cast<float>(height - 1);
            image.set_pixel(x, y, {u, v, 1.0f - u * v, 0.5f + 0.5f * u});
        }
    }
    return image;
}

TEST(ExrRoundTrip, PreservesEveryBit) {
    luxel::testing::TempDir dir;
    luxel::Image image = gradient(37, 23);
    // Values a linear HDR frame may hold: huge, tiny, negative, denormal, exact zero.
    image.set_pixel(0, 0, {65504.0f * 1000.0f, 1e-30f, -3.5f, 0.0f});
    image.set_pixel(1, 0, {std::numeric_limits<float>::denorm_min(), 1.0f / 3.0f, 1e20f, 1.0f});
    luxel::write_exr(dir / "frame.exr", image);
    const luxel::Image back = luxel::read_exr(dir / "frame.exr");
    ASSERT_EQ(back.width, image.width);
    ASSERT_EQ(back.height, image.height);
    ASSERT_EQ(back.rgba.size(), image.rgba.size());
    EXPECT_EQ(std::memcmp(back.rgba.data(), image.rgba.data(), image.rgba.size() * sizeof(float)),
              0);
}

TEST(PngRoundTrip, PreservesValuesWithinQuantisation) {
    luxel::testing::TempDir dir;
    const luxel::Image image = gradient(64, 32);
    luxel::write_png(dir / "frame.png", image, {luxel::ToneMapOperator::Clamp, 1.0f});
    const luxel::Image8 back = luxel::read_png(dir / "frame.png");
    ASSERT_EQ(back.width, 64);
    ASSERT_EQ(back.height, 32);
    ASSERT_EQ(back.channels, 3);
    for (int y = 0; y < back.height; ++y) {
        for (int x = 0; x < back.width; ++x) {
            const glm::vec4 original = image.pixel(x, y);
            for (int c = 0; c < 3; ++c) {
                const float encoded = luxel::linear_to_srgb(original[c]) * 255.0f;
                // Rounded to the nearest code: within half a step of the exact encoding.
                EXPECT_NEAR(static_cast<float>(back.at(x, y, c)), encoded, 0.5f + 1e-3f)
                    << "pixel " << x << "," << y << " channel " << c;
            }
        }
    }
}

TEST(ToneMap, CurvesAreMonotoneBoundedAndSafe) {
    for (auto op : {luxel::ToneMapOperator::Clamp, luxel::ToneMapOperator::Reinhard,
                    luxel::ToneMapOperator::Aces}) {
        float previous = -1.0f;
        for (float x = 0.0f; x < 100.0f; x = x * 1.5f + 0.01f) {
            const float y = luxel::tone_map(glm::vec3(x), {op, 1.0f}).r;
            EXPECT_GE(y, previous);
            EXPECT_GE(y, 0.0f);
            EXPECT_LE(y, 1.0f);
            previous = y;
        }
        const glm::vec3 nan_in =
            luxel::tone_map(glm::vec3(std::nanf(""), -1.0f, INFINITY), {op, 1.0f});
        EXPECT_EQ(nan_in.r, 0.0f);
        EXPECT_EQ(nan_in.g, 0.0f);
        EXPECT_EQ(nan_in.b, 1.0f);
    }
    EXPECT_NEAR(luxel::tone_map(glm::vec3(1.0f), {luxel::ToneMapOperator::Reinhard, 1.0f}).r, 0.5f,
                1e-6f);
    for (float v = 0.0f; v <= 1.0f; v += 0.01f) {
        EXPECT_NEAR(luxel::srgb_to_linear(luxel::linear_to_srgb(v)), v, 1e-5f);
    }
}

TEST(ImageErrors, MissingAndCorruptFilesNameTheFile) {
    luxel::testing::TempDir dir;
    const auto missing = dir / "missing.exr";
    try {
        (void)luxel::read_exr(missing);
        FAIL();
    } catch (const luxel::Error& e) {
        EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos);
    }
    const auto not_exr = dir / "text.exr";
    std::ofstream(not_exr) << "this is not an image";
    try {
        (void)luxel::read_exr(not_exr);
        FAIL();
    } catch (const luxel::Error& e) {
        EXPECT_NE(std::string(e.what()).find("text.exr"), std::string::npos) << e.what();
    }
    // A PNG cut short after its header.
    luxel::write_png(dir / "good.png", gradient(16, 16));
    std::ifstream good(dir / "good.png", std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(good)), std::istreambuf_iterator<char>());
    std::ofstream(dir / "cut.png", std::ios::binary) << bytes.substr(0, 40);
    EXPECT_THROW((void)luxel::read_png(dir / "cut.png"), luxel::Error);
    EXPECT_THROW((void)luxel::read_png(dir / "missing.png"), luxel::Error);
}

TEST(ImageErrors, HugeDeclaredSizeIsRefusedBeforeAllocating) {
    luxel::testing::TempDir dir;
    // A valid PNG signature and IHDR declaring 100000 x 100000 pixels, and no data.
    const unsigned char header[] = {0x89, 'P',  'N', 'G', '\r', '\n', 0x1a, '\n', 0,    0,    0,
                                    13,   'I',  'H', 'D', 'R',  0x00, 0x01, 0x86, 0xA0, 0x00, 0x01,
                                    0x86, 0xA0, 8,   2,   0,    0,    0,    0,    0,    0,    0};
    std::ofstream(dir / "huge.png", std::ios::binary)
        .write(reinterpret_cast<const char*>(header), sizeof header);
    try {
        (void)luxel::read_png(dir / "huge.png");
        FAIL();
    } catch (const luxel::Error& e) {
        EXPECT_NE(std::string(e.what()).find("huge.png"), std::string::npos) << e.what();
    }
}

TEST(ImageErrors, WritingIntoAnUnwritablePlaceIsAnError) {
    luxel::testing::TempDir dir;
    std::ofstream(dir / "file") << "x";
    // A path whose parent is a regular file cannot be created.
    EXPECT_THROW(luxel::write_exr(dir / "file" / "frame.exr", gradient(4, 4)), luxel::Error);
    EXPECT_THROW(luxel::write_png(dir / "frame.png", luxel::Image{}), luxel::Error);
}

}  // namespace
