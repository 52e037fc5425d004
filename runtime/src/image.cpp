#include "luxel/runtime/image.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>
#include <system_error>

#include <stb_image.h>
#include <stb_image_write.h>
#include <tinyexr.h>

#include "luxel/runtime/error.hpp"
#include "luxel/runtime/pending_file.hpp"

namespace luxel {
namespace {

// Refuse to decode anything larger before allocating for it: a corrupt or hostile header must
// not make us allocate gigabytes. 16384^2 covers every light-map page and frame we write.
constexpr int kMaxImageDimension = 16384;

std::size_t pixel_count(int width, int height) {
    return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
}

void check_dimensions(const std::filesystem::path& path, int width, int height) {
    if (width <= 0 || height <= 0 || width > kMaxImageDimension || height > kMaxImageDimension) {
        throw Error(path.string() + ": image size " + std::to_string(width) + "x" +
                    std::to_string(height) + " is outside 1.." +
                    std::to_string(kMaxImageDimension));
    }
}

void ensure_parent_directory(const std::filesystem::path& path) {
    const auto parent = path.parent_path();
    if (parent.empty()) {
        return;
    }
    std::error_code ec;
    std::filesystem::create_directories(parent, ec);
    if (ec) {
        throw Error(path.string() + ": cannot create directory " + parent.string() + ": " +
                    ec.message());
    }
}

struct ExrMessageDeleter {
    void operator()(const char* message) const { FreeEXRErrorMessage(message); }
};
using ExrMessage = std::unique_ptr<const char, ExrMessageDeleter>;

struct MallocDeleter {
    void operator()(void* memory) const { std::free(memory); }
};

std::string exr_reason(const char* message, int code) {
    return message != nullptr ? std::string(message) : "tinyexr error code " + std::to_string(code);
}

}  // namespace

Image::Image(int w, int h, const glm::vec4& fill) : width(w), height(h) {
    if (w < 0 || h < 0) {
        throw std::invalid_argument("Image: negative size");
    }
    rgba.resize(pixel_count(w, h) * 4);
    for (std::size_t i = 0; i < pixel_count(w, h); ++i) {
        rgba[i * 4 + 0] = fill.r;
        rgba[i * 4 + 1] = fill.g;
        rgba[i * 4 + 2] = fill.b;
        rgba[i * 4 + 3] = fill.a;
    }
}

glm::vec4 Image::pixel(int x, int y) const {
    const std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                           static_cast<std::size_t>(x)) *
                          4;
    return {rgba.at(i), rgba.at(i + 1), rgba.at(i + 2), rgba.at(i + 3)};
}

void Image::set_pixel(int x, int y, const glm::vec4& value) {
    const std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                           static_cast<std::size_t>(x)) *
                          4;
    rgba.at(i) = value.r;
    rgba.at(i + 1) = value.g;
    rgba.at(i + 2) = value.b;
    rgba.at(i + 3) = value.a;
}

void write_exr(const std::filesystem::path& path, const Image& image) {
    if (image.empty() || image.rgba.size() != pixel_count(image.width, image.height) * 4) {
        throw Error(path.string() + ": cannot write an empty or malformed image");
    }
    ensure_parent_directory(path);
    const char* raw_message = nullptr;
    PendingFile pending(path);  // whole or not at all
    const int code = SaveEXR(image.rgba.data(), image.width, image.height, 4,
                             /*save_as_fp16=*/0, pending.path().c_str(), &raw_message);
    const ExrMessage message(raw_message);
    if (code != TINYEXR_SUCCESS) {
        throw Error(path.string() + ": cannot write EXR: " + exr_reason(raw_message, code));
    }
    pending.commit();
}

Image read_exr(const std::filesystem::path& path) {
    if (!std::filesystem::is_regular_file(path)) {
        throw Error(path.string() + ": no such file");
    }
    // Read the header first so the image size is checked before any pixel memory exists.
    EXRVersion version{};
    int code = ParseEXRVersionFromFile(&version, path.c_str());
    if (code != TINYEXR_SUCCESS) {
        throw Error(path.string() + ": not an OpenEXR file (tinyexr error code " +
                    std::to_string(code) + ")");
    }
    if (version.multipart != 0 || version.non_image != 0) {
        throw Error(path.string() + ": multi-part and deep EXR files are not supported");
    }
    EXRHeader header;
    InitEXRHeader(&header);
    const char* raw_message = nullptr;
    code = ParseEXRHeaderFromFile(&header, &version, path.c_str(), &raw_message);
    const ExrMessage header_message(raw_message);
    if (code != TINYEXR_SUCCESS) {
        throw Error(path.string() + ": bad EXR header: " + exr_reason(raw_message, code));
    }
    const int header_width = header.data_window.max_x - header.data_window.min_x + 1;
    const int header_height = header.data_window.max_y - header.data_window.min_y + 1;
    FreeEXRHeader(&header);
    check_dimensions(path, header_width, header_height);

    float* raw_pixels = nullptr;
    int width = 0;
    int height = 0;
    raw_message = nullptr;
    code = LoadEXR(&raw_pixels, &width, &height, path.c_str(), &raw_message);
    const ExrMessage load_message(raw_message);
    const std::unique_ptr<float, MallocDeleter> pixels(raw_pixels);
    if (code != TINYEXR_SUCCESS || pixels == nullptr) {
        throw Error(path.string() + ": cannot read EXR: " + exr_reason(raw_message, code));
    }
    check_dimensions(path, width, height);
    Image image;
    image.width = width;
    image.height = height;
    image.rgba.assign(pixels.get(), pixels.get() + pixel_count(width, height) * 4);
    return image;
}

void write_png(const std::filesystem::path& path, const Image& image,
               const ToneMapSettings& tone_map_settings) {
    if (image.empty() || image.rgba.size() != pixel_count(image.width, image.height) * 4) {
        throw Error(path.string() + ": cannot write an empty or malformed image");
    }
    ensure_parent_directory(path);
    std::vector<std::uint8_t> encoded(pixel_count(image.width, image.height) * 3);
    for (std::size_t i = 0; i < pixel_count(image.width, image.height); ++i) {
        const glm::vec3 linear(image.rgba[i * 4], image.rgba[i * 4 + 1], image.rgba[i * 4 + 2]);
        const glm::vec3 display = tone_map(linear, tone_map_settings);
        for (int c = 0; c < 3; ++c) {
            const float value = linear_to_srgb(display[c]) * 255.0f + 0.5f;
            encoded[i * 3 + static_cast<std::size_t>(c)] =
                static_cast<std::uint8_t>(std::clamp(value, 0.0f, 255.0f));
        }
    }
    PendingFile pending(path);  // whole or not at all
    if (stbi_write_png(pending.path().c_str(), image.width, image.height, 3, encoded.data(),
                       image.width * 3) == 0) {
        throw Error(path.string() + ": cannot write PNG");
    }
    pending.commit();
}

Image8 read_png(const std::filesystem::path& path) {
    if (!std::filesystem::is_regular_file(path)) {
        throw Error(path.string() + ": no such file");
    }
    int width = 0;
    int height = 0;
    int channels = 0;
    if (stbi_info(path.c_str(), &width, &height, &channels) == 0) {
        throw Error(path.string() + ": not a readable image: " + stbi_failure_reason());
    }
    check_dimensions(path, width, height);
    struct StbDeleter {
        void operator()(stbi_uc* memory) const { stbi_image_free(memory); }
    };
    const std::unique_ptr<stbi_uc, StbDeleter> pixels(
        stbi_load(path.c_str(), &width, &height, &channels, 0));
    if (!pixels) {
        throw Error(path.string() + ": cannot decode PNG: " + stbi_failure_reason());
    }
    Image8 image;
    image.width = width;
    image.height = height;
    image.channels = channels;
    image.data.assign(pixels.get(), pixels.get() + pixel_count(width, height) *
                                                       static_cast<std::size_t>(channels));
    return image;
}

float metered_exposure(const Image& image, int stride) {
    const int step = std::max(stride, 1);
    double log_sum = 0.0;
    std::size_t count = 0;
    for (int y = 0; y < image.height; y += step) {
        for (int x = 0; x < image.width; x += step) {
            const glm::vec4 p = image.pixel(x, y);
            const double seen = luminance(glm::dvec3(glm::vec3(p)));
            if (std::isfinite(seen) && seen > 1e-6) {
                log_sum += std::log(1e-4 + seen);
                ++count;
            }
        }
    }
    if (count == 0) {
        return 1.0f;
    }
    const double average = std::exp(log_sum / static_cast<double>(count));
    return static_cast<float>(std::clamp(kExposureKey / average, 1e-3, 1e4));
}

}  // namespace luxel
