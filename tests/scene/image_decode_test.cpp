// Decoding scene images (scene/image_decode): PNGs and JPEGs written here with
// stb_image_write come back as their pixels; empty, foreign, truncated and oversized data give
// a luxel::Error naming the image; the mean linear colour matches the sRGB curve.

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <stb_image_write.h>

#include "luxel/runtime/error.hpp"
#include "luxel/scene/image_decode.hpp"

namespace {

using namespace luxel;
using namespace luxel::scene;

void append_bytes(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<std::uint8_t>*>(context);
    const auto* bytes = static_cast<const std::uint8_t*>(data);
    out->insert(out->end(), bytes, bytes + size);
}

/// `pixels` (rows top first, `channels` per pixel) encoded as a PNG in memory.
std::vector<std::uint8_t> encode_png(int width, int height, int channels,
                                     const std::vector<std::uint8_t>& pixels) {
    std::vector<std::uint8_t> out;
    const int ok = stbi_write_png_to_func(append_bytes, &out, width, height, channels,
                                          pixels.data(), width * channels);
    EXPECT_NE(ok, 0) << "stbi_write_png_to_func failed";
    return out;
}

std::vector<std::uint8_t> encode_jpeg(int width, int height, const std::vector<std::uint8_t>& rgb) {
    std::vector<std::uint8_t> out;
    const int ok = stbi_write_jpg_to_func(append_bytes, &out, width, height, 3, rgb.data(), 100);
    EXPECT_NE(ok, 0) << "stbi_write_jpg_to_func failed";
    return out;
}

/// A width x height RGBA pattern in which every byte differs from its neighbours.
std::vector<std::uint8_t> pattern(int width, int height) {
    std::vector<std::uint8_t> pixels(static_cast<std::size_t>(width * height * 4));
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        pixels[i] = static_cast<std::uint8_t>((i * 37 + 11) % 256);
    }
    return pixels;
}

/// The exact IEC 61966-2-1 decoding, written out here independently of runtime/tone_map.
double srgb_to_linear_exact(int code) {
    const double x = code / 255.0;
    return x <= 0.04045 ? x / 12.92 : std::pow((x + 0.055) / 1.055, 2.4);
}

/// Asserts that decoding `image` throws a luxel::Error whose message names the image and
/// contains `problem`.
void expect_error(const Image& image, int index, const std::string& problem) {
    try {
        (void)decode_image(image, index);
        ADD_FAILURE() << "no error for " << image.name;
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("image " + std::to_string(index) + " '" + image.name + "'"),
                  std::string::npos)
            << message;
        EXPECT_NE(message.find(problem), std::string::npos) << message;
        std::printf("[ figures  ] %s: \"%s\"\n", image.name.c_str(), message.c_str());
    }
}

TEST(ImageDecode, PngComesBackAsItsPixels) {
    const int width = 7;
    const int height = 5;
    const std::vector<std::uint8_t> rgba = pattern(width, height);
    const Image image{"pattern", "image/png", encode_png(width, height, 4, rgba)};
    const DecodedImage decoded = decode_image(image, 0);
    ASSERT_EQ(decoded.width, width);
    ASSERT_EQ(decoded.height, height);
    ASSERT_EQ(decoded.rgba.size(), rgba.size());
    // PNG is lossless: every byte exactly, in the same order (rows top first).
    std::size_t differing = 0;
    for (std::size_t i = 0; i < rgba.size(); ++i) {
        differing += decoded.rgba[i] != rgba[i] ? 1 : 0;
    }
    std::printf("[ figures  ] RGBA PNG %dx%d: %zu of %zu bytes differ\n", width, height, differing,
                rgba.size());
    EXPECT_EQ(differing, 0u);
}

TEST(ImageDecode, RgbAndGreyPngsBecomeOpaqueRgba) {
    const std::vector<std::uint8_t> rgb = {10, 20, 30, 40, 50, 60};
    const DecodedImage colour = decode_image({"rgb", "image/png", encode_png(2, 1, 3, rgb)});
    ASSERT_EQ(colour.rgba.size(), 8u);
    EXPECT_EQ(colour.rgba, (std::vector<std::uint8_t>{10, 20, 30, 255, 40, 50, 60, 255}));

    const std::vector<std::uint8_t> grey = {0, 99, 255};
    const DecodedImage g = decode_image({"grey", "image/png", encode_png(3, 1, 1, grey)});
    ASSERT_EQ(g.rgba.size(), 12u);
    for (int x = 0; x < 3; ++x) {
        for (int c = 0; c < 3; ++c) {
            EXPECT_EQ(g.at(x, 0, c), grey[static_cast<std::size_t>(x)]);
        }
        EXPECT_EQ(g.at(x, 0, 3), 255);
    }
}

TEST(ImageDecode, JpegOfAFlatColourComesBackWithinRounding) {
    const int size = 16;
    std::vector<std::uint8_t> rgb;
    for (int i = 0; i < size * size; ++i) {
        rgb.insert(rgb.end(), {200, 120, 40});
    }
    const DecodedImage decoded = decode_image({"flat", "image/jpeg", encode_jpeg(size, size, rgb)});
    ASSERT_EQ(decoded.width, size);
    ASSERT_EQ(decoded.height, size);
    int worst = 0;
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            for (int c = 0; c < 3; ++c) {
                worst = std::max(worst,
                                 std::abs(decoded.at(x, y, c) - rgb[static_cast<std::size_t>(c)]));
            }
        }
    }
    std::printf("[ figures  ] flat JPEG (quality 100): worst channel error %d codes\n", worst);
    // A flat block keeps only its DC term, quantized with step 1 at quality 100; what is left is
    // the 8-bit rounding of RGB -> YCbCr -> RGB, at most a couple of codes.
    EXPECT_LE(worst, 3);
}

TEST(ImageDecode, BadDataGivesAnErrorNamingTheImage) {
    const std::vector<std::uint8_t> png = encode_png(16, 16, 4, pattern(16, 16));
    ASSERT_GT(png.size(), 100u);

    expect_error({"empty", "image/png", {}}, 3, "0 bytes");

    std::vector<std::uint8_t> garbage(256);
    for (std::size_t i = 0; i < garbage.size(); ++i) {
        garbage[i] = static_cast<std::uint8_t>((i * 131 + 7) % 251);
    }
    expect_error({"garbage", "image/png", garbage}, 4, "neither PNG nor JPEG");

    // A PNG signature followed by garbage: no readable header.
    std::vector<std::uint8_t> bad_header(png.begin(), png.begin() + 8);
    bad_header.insert(bad_header.end(), garbage.begin(), garbage.end());
    expect_error({"bad header", "image/png", bad_header}, 5, "header");

    // Cut in the middle of the image data: the header reads, the pixels do not.
    const std::vector<std::uint8_t> truncated(png.begin(),
                                              png.begin() + static_cast<long>(png.size() / 2));
    expect_error({"truncated", "image/png", truncated}, 6, "cannot decode PNG");
}

TEST(ImageDecode, SizesBeyondTheLimitAreRefusedBeforeDecoding) {
    // A real PNG one texel wider than the limit (64 KiB of pixels, cheap to write).
    const int wide = kMaxImageEdge + 1;
    std::vector<std::uint8_t> row(static_cast<std::size_t>(wide), 128);
    expect_error({"too wide", "image/png", encode_png(wide, 1, 1, row)}, 7,
                 "outside 1.." + std::to_string(kMaxImageEdge));

    // A header claiming 0 x 1: IHDR's width is bytes 16..19 of the file.
    std::vector<std::uint8_t> zero = encode_png(1, 1, 4, pattern(1, 1));
    zero[16] = zero[17] = zero[18] = zero[19] = 0;
    try {
        (void)decode_image({"zero width", "image/png", zero}, 8);
        ADD_FAILURE() << "a 0-pixel-wide PNG decoded";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("image 8 'zero width'"), std::string::npos)
            << e.what();
        std::printf("[ figures  ] zero width: \"%s\"\n", e.what());
    }
}

TEST(ImageDecode, MeanLinearColourFollowsTheSrgbCurve) {
    // Four texels of known sRGB codes; alpha must not matter.
    const std::vector<std::uint8_t> rgba = {255, 0,   128, 255, 0,  255, 64, 0,
                                            128, 128, 128, 17,  10, 200, 30, 255};
    Scene scene;
    scene.images.push_back({"known", "image/png", encode_png(2, 2, 4, rgba)});
    glm::dvec3 expected(0.0);
    for (std::size_t t = 0; t < 4; ++t) {
        for (int c = 0; c < 3; ++c) {
            expected[c] += srgb_to_linear_exact(rgba[t * 4 + static_cast<std::size_t>(c)]) / 4.0;
        }
    }
    const glm::vec3 mean = mean_linear_color(decode_image(scene.images[0], 0));
    std::printf("[ figures  ] mean linear colour %.6f %.6f %.6f (exact %.6f %.6f %.6f)\n", mean.r,
                mean.g, mean.b, expected.r, expected.g, expected.b);
    for (int c = 0; c < 3; ++c) {
        // The runtime decodes in float (pow in single precision): 1e-5 relative is ~100 float
        // ulps, far below a code step (>= 0.4% relative above code 10) yet far above rounding.
        EXPECT_NEAR(mean[c], expected[c], 1e-5 * expected[c]) << "channel " << c;
    }
    // The memoised form gives the same value, twice (the second from the memo).
    EXPECT_EQ(image_mean_linear_color(scene, 0), mean);
    EXPECT_EQ(image_mean_linear_color(scene, 0), mean);

    // The albedo photons use: factor x mean, and the factor alone without a texture.
    Material material;
    material.base_color = glm::vec4(0.5f, 1.0f, 0.25f, 1.0f);
    EXPECT_EQ(mean_diffuse_albedo(scene, material), glm::vec3(0.5f, 1.0f, 0.25f));
    material.base_color_image = 0;
    const glm::vec3 albedo = mean_diffuse_albedo(scene, material);
    for (int c = 0; c < 3; ++c) {
        EXPECT_FLOAT_EQ(albedo[c], material.base_color[c] * mean[c]);
    }
    EXPECT_THROW((void)image_mean_linear_color(scene, 1), Error);
}

TEST(ImageDecode, AnUndecodableTextureNamesItsMaterial) {
    Scene scene;
    scene.images.push_back({"broken", "image/png", {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A}});
    Material material;
    material.name = "wall paint";
    material.base_color_image = 0;
    try {
        (void)mean_diffuse_albedo(scene, material);
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("material 'wall paint'"), std::string::npos) << message;
        EXPECT_NE(message.find("image 0 'broken'"), std::string::npos) << message;
    }
}

}  // namespace
