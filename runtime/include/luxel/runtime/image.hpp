#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/runtime/tone_map.hpp"

namespace luxel {

/// A linear RGBA float image, rows stored top first (the file convention, not GL's).
struct Image {
    int width = 0;
    int height = 0;
    std::vector<float> rgba;  ///< width * height * 4

    Image() = default;
    Image(int w, int h, const glm::vec4& fill = glm::vec4(0.0f));

    [[nodiscard]] glm::vec4 pixel(int x, int y) const;
    void set_pixel(int x, int y, const glm::vec4& value);
    [[nodiscard]] bool empty() const { return width == 0 || height == 0; }
};

/// An 8-bit image as stored in a PNG (sRGB-encoded values), rows top first.
struct Image8 {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::vector<std::uint8_t> data;

    [[nodiscard]] std::uint8_t at(int x, int y, int channel) const {
        return data[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                     static_cast<std::size_t>(x)) *
                        static_cast<std::size_t>(channels) +
                    static_cast<std::size_t>(channel)];
    }
};

/// Writes 32-bit float RGBA OpenEXR (lossless: read_exr returns the same bits).
/// Throws luxel::Error naming the file on failure.
void write_exr(const std::filesystem::path& path, const Image& image);
/// Reads an OpenEXR file as RGBA float (missing channels: colour 0, alpha 1).
[[nodiscard]] Image read_exr(const std::filesystem::path& path);

/// Tone-maps, sRGB-encodes and writes an 8-bit RGB PNG.
void write_png(const std::filesystem::path& path, const Image& image,
               const ToneMapSettings& tone_map = {});
/// Reads a PNG as 8-bit values (any channel count the file has).
[[nodiscard]] Image8 read_png(const std::filesystem::path& path);

/// The grey a metered exposure maps the log-average luminance to: a little under the
/// photographic 0.18, since luxel's interiors are mostly pale walls.
inline constexpr double kExposureKey = 0.12;

/// The exposure that maps the log-average luminance of `image`'s lit pixels to kExposureKey,
/// as a camera's meter would, reading every `stride`-th pixel in each direction. Black pixels
/// are the sky or the void beyond an open level, not a dark surface: metering them would
/// expose the lit part to white, so they are left out. An image with nothing lit: 1.
[[nodiscard]] float metered_exposure(const Image& image, int stride = 1);

}  // namespace luxel
