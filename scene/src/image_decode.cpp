#include "luxel/scene/image_decode.hpp"

#include <algorithm>
#include <array>
#include <climits>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <utility>

#include <stb_image.h>

#include "luxel/runtime/error.hpp"
#include "luxel/runtime/tone_map.hpp"

namespace luxel::scene {
namespace {

bool is_png(const std::vector<std::uint8_t>& bytes) {
    static constexpr std::array<std::uint8_t, 8> kSignature = {0x89, 'P',  'N',  'G',
                                                               0x0D, 0x0A, 0x1A, 0x0A};
    return bytes.size() >= kSignature.size() &&
           std::equal(kSignature.begin(), kSignature.end(), bytes.begin());
}

bool is_jpeg(const std::vector<std::uint8_t>& bytes) {
    return bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF;
}

std::string stb_reason() {
    const char* reason = stbi_failure_reason();
    return reason != nullptr ? std::string(reason) : std::string("unknown reason");
}

struct StbDeleter {
    void operator()(stbi_uc* pixels) const { stbi_image_free(pixels); }
};

/// A 64-bit hash of the encoded bytes, eight at a time (several GB/s: hashing an image is far
/// cheaper than decoding it). Not cryptographic: a deliberate collision could at worst give
/// one texture another's mean colour.
std::uint64_t content_hash(const std::vector<std::uint8_t>& bytes) {
    constexpr std::uint64_t kMultiplier = 0x9E3779B97F4A7C15ull;
    std::uint64_t h = 0xCBF29CE484222325ull ^ (bytes.size() * kMultiplier);
    const auto mix = [&](std::uint64_t word) {
        h ^= word * 0xC2B2AE3D27D4EB4Full;
        h = ((h << 31) | (h >> 33)) * kMultiplier;
    };
    std::size_t i = 0;
    for (; i + 8 <= bytes.size(); i += 8) {
        std::uint64_t word = 0;
        std::memcpy(&word, bytes.data() + i, 8);
        mix(word);
    }
    std::uint64_t tail = 0;
    if (i < bytes.size()) {
        std::memcpy(&tail, bytes.data() + i, bytes.size() - i);
    }
    mix(tail);
    // Murmur3's finalizer: every input bit reaches every output bit.
    h ^= h >> 33;
    h *= 0xFF51AFD7ED558CCDull;
    h ^= h >> 33;
    h *= 0xC4CEB9FE1A85EC53ull;
    h ^= h >> 33;
    return h;
}

/// Means already computed, by (size, content hash). A process sees few distinct textures;
/// past kMaxEntries (a long session loading level after level) the memo starts over rather
/// than grow without bound.
class MeanMemo {
  public:
    static constexpr std::size_t kMaxEntries = 4096;
    using Key = std::pair<std::size_t, std::uint64_t>;

    bool find(const Key& key, glm::vec3& mean) {
        const std::lock_guard lock(mutex_);
        const auto found = means_.find(key);
        if (found == means_.end()) {
            return false;
        }
        mean = found->second;
        return true;
    }
    void store(const Key& key, const glm::vec3& mean) {
        const std::lock_guard lock(mutex_);
        if (means_.size() >= kMaxEntries) {
            means_.clear();
        }
        means_[key] = mean;
    }

  private:
    std::mutex mutex_;
    std::map<Key, glm::vec3> means_;
};

MeanMemo& mean_memo() {
    static MeanMemo memo;
    return memo;
}

}  // namespace

std::string image_label(const Image& image, int index) {
    std::string text = "image";
    if (index >= 0) {
        text += " " + std::to_string(index);
    }
    if (!image.name.empty()) {
        text += " '" + image.name + "'";
    }
    return text;
}

ImageSize read_image_size(const Image& image, int index) {
    const std::string where = image_label(image, index);
    const std::vector<std::uint8_t>& bytes = image.encoded;
    if (bytes.empty()) {
        throw Error(where + ": holds no data (0 bytes)");
    }
    // glTF allows only PNG and JPEG; stb_image would also accept BMP, GIF, PSD and others.
    if (!is_png(bytes) && !is_jpeg(bytes)) {
        throw Error(where + ": is neither PNG nor JPEG (" + std::to_string(bytes.size()) +
                    " bytes without either signature)");
    }
    if (bytes.size() > static_cast<std::size_t>(INT_MAX)) {
        throw Error(where + ": " + std::to_string(bytes.size()) +
                    " bytes of encoded data is more than the decoder accepts");
    }
    const int length = static_cast<int>(bytes.size());
    // The header first, so the size is checked before any pixel memory exists.
    int width = 0;
    int height = 0;
    int channels = 0;
    const char* format = is_png(bytes) ? "PNG" : "JPEG";
    if (stbi_info_from_memory(bytes.data(), length, &width, &height, &channels) == 0) {
        // stb_image's reason here comes from the last format it tried, not from ours.
        throw Error(where + ": cannot read its " + format +
                    " header (corrupt data or an unsupported variant)");
    }
    const auto check_size = [&](int w, int h) {
        if (w < 1 || h < 1 || w > kMaxImageEdge || h > kMaxImageEdge) {
            throw Error(where + ": size " + std::to_string(w) + "x" + std::to_string(h) +
                        " is outside 1.." + std::to_string(kMaxImageEdge) + " per edge");
        }
    };
    check_size(width, height);
    return {width, height};
}

DecodedImage decode_image(const Image& image, int index) {
    const std::string where = image_label(image, index);
    const auto [width, height] = read_image_size(image, index);
    const std::vector<std::uint8_t>& bytes = image.encoded;
    const int length = static_cast<int>(bytes.size());
    const char* format = is_png(bytes) ? "PNG" : "JPEG";
    int channels = 0;
    int decoded_width = 0;
    int decoded_height = 0;
    const std::unique_ptr<stbi_uc, StbDeleter> pixels(stbi_load_from_memory(
        bytes.data(), length, &decoded_width, &decoded_height, &channels, STBI_rgb_alpha));
    if (!pixels) {
        throw Error(where + ": cannot decode " + format + ": " + stb_reason());
    }
    if (decoded_width != width || decoded_height != height) {
        throw Error(where + ": decoded size " + std::to_string(decoded_width) + "x" +
                    std::to_string(decoded_height) + " differs from its header's " +
                    std::to_string(width) + "x" + std::to_string(height));
    }
    DecodedImage out;
    out.width = width;
    out.height = height;
    const std::size_t size = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4;
    out.rgba.assign(pixels.get(), pixels.get() + size);
    return out;
}

const std::array<float, 256>& srgb8_to_linear() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (std::size_t v = 0; v < t.size(); ++v) {
            t[v] = srgb_to_linear(static_cast<float>(v) / 255.0f);
        }
        return t;
    }();
    return table;
}

glm::vec3 mean_linear_color(const DecodedImage& image) {
    const std::size_t texels = static_cast<std::size_t>(std::max(image.width, 0)) *
                               static_cast<std::size_t>(std::max(image.height, 0));
    if (texels == 0 || image.rgba.size() < texels * 4) {
        return glm::vec3(0.0f);
    }
    const std::array<float, 256>& linear = srgb8_to_linear();
    // Sums per row, then over rows: a 16384^2 image adds 2^28 terms, more than a float keeps
    // exactly, and the per-row split keeps each partial sum small even in double.
    glm::dvec3 total(0.0);
    for (int y = 0; y < image.height; ++y) {
        glm::dvec3 row(0.0);
        const std::uint8_t* texel = image.rgba.data() + static_cast<std::size_t>(y) *
                                                            static_cast<std::size_t>(image.width) *
                                                            4;
        for (int x = 0; x < image.width; ++x, texel += 4) {
            row += glm::dvec3(linear[texel[0]], linear[texel[1]], linear[texel[2]]);
        }
        total += row;
    }
    return glm::vec3(total / static_cast<double>(texels));
}

glm::vec3 image_mean_linear_color(const Scene& scene, int index) {
    if (index < 0 || static_cast<std::size_t>(index) >= scene.images.size()) {
        throw Error("image " + std::to_string(index) + " is out of range (the scene has " +
                    std::to_string(scene.images.size()) + " images)");
    }
    const Image& image = scene.images[static_cast<std::size_t>(index)];
    const MeanMemo::Key key(image.encoded.size(), content_hash(image.encoded));
    glm::vec3 mean(0.0f);
    if (mean_memo().find(key, mean)) {
        return mean;
    }
    // Decoded outside the lock: two threads meeting the same new image may both decode it,
    // which costs time once but never blocks other images behind a long decode.
    mean = mean_linear_color(decode_image(image, index));
    mean_memo().store(key, mean);
    return mean;
}

glm::vec3 mean_diffuse_albedo(const Scene& scene, const Material& material) {
    glm::vec3 albedo = glm::clamp(glm::vec3(material.base_color), 0.0f, 1.0f);
    if (material.base_color_image < 0) {
        return albedo;
    }
    // Why the texture's mean is enough off screen: photon maps and light maps are much coarser
    // than texture detail (a light-map texel spans many texels of a base-colour texture), and
    // a textured surface's light map stores irradiance, which the renderer multiplies by the
    // per-pixel albedo (texture x factor). The albedo here only decides how much energy the
    // surface reflects into the rest of the scene (photon bounces, the AIM the gather reads),
    // and that must be right on average over the surface: factor x mean linear colour.
    // (A primitive without TEXCOORD_0 draws with the factor alone but still reflects with this
    // mean; glTF does not allow a texture without texture coordinates anyway.)
    try {
        albedo *= image_mean_linear_color(scene, material.base_color_image);
    } catch (const Error& e) {
        // Decoded long after loading (when an instance is made): the scene names its file.
        const auto index = &material - scene.materials.data();
        const bool listed = index >= 0 && static_cast<std::size_t>(index) < scene.materials.size();
        throw Error(scene.in_file("material " + (listed ? std::to_string(index) + " " : "") + "'" +
                                  material.name + "': base-colour texture: " + e.what()));
    }
    return glm::clamp(albedo, 0.0f, 1.0f);
}

}  // namespace luxel::scene
