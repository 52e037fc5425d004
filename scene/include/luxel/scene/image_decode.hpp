#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/scene/scene.hpp"

/// Decoding the PNG and JPEG images a Scene keeps encoded (scene::Image): into 8-bit RGBA for
/// the renderer's textures, and into one mean colour for the albedo that photons bounce with.
namespace luxel::scene {

/// The largest accepted edge. It is checked from the header before any pixel memory exists,
/// so whatever a corrupt or hostile header claims, a decode allocates at most
/// 16384^2 * 4 bytes = 1 GiB (and 16384 is also the smallest GL_MAX_TEXTURE_SIZE luxel's
/// drivers report, so a larger image could not be drawn anyway).
inline constexpr int kMaxImageEdge = 16384;

/// 8-bit RGBA pixels, rows top first: glTF puts UV (0, 0) at the image's top-left corner, so
/// row 0 is v = 0. Colour channels are kept as stored (sRGB-encoded for base-colour textures);
/// images with fewer channels are expanded (grey to RGB, alpha 255).
struct DecodedImage {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba;  ///< width * height * 4

    [[nodiscard]] std::uint8_t at(int x, int y, int channel) const {
        return rgba[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                     static_cast<std::size_t>(x)) *
                        4 +
                    static_cast<std::size_t>(channel)];
    }
};

/// How errors name an image: "image 3 'wood'" (index < 0: "image 'wood'"; no name: the
/// number alone).
[[nodiscard]] std::string image_label(const Image& image, int index);

struct ImageSize {
    int width = 0;
    int height = 0;
};

/// The size a PNG or JPEG's header declares, read without decoding, after the same checks as
/// decode_image up to that point (data, signature, header, 1..kMaxImageEdge per edge): what
/// the loader sums to bound the memory a file's images will take.
[[nodiscard]] ImageSize read_image_size(const Image& image, int index = -1);

/// Decodes a PNG or JPEG to RGBA8. Throws luxel::Error naming the image (image_label) and the
/// problem for empty data, bytes that are neither PNG nor JPEG, undecodable or truncated data,
/// and sizes outside 1..kMaxImageEdge per edge.
[[nodiscard]] DecodedImage decode_image(const Image& image, int index = -1);

/// The linear value of each 8-bit sRGB code (IEC 61966-2-1), computed once: what
/// mean_linear_color and scene::LinearImage read texels through.
[[nodiscard]] const std::array<float, 256>& srgb8_to_linear();

/// The mean linear colour: every texel's sRGB-encoded RGB decoded to linear (IEC 61966-2-1),
/// then averaged. Alpha is ignored: luxel draws every material opaque. An empty image: 0.
[[nodiscard]] glm::vec3 mean_linear_color(const DecodedImage& image);

/// mean_linear_color of scene.images[index]. Each distinct image is decoded once per process:
/// the result is remembered under a hash of the encoded bytes (not the Image's address, which
/// a later scene may reuse), so the photon tracer and the light maps, which both ask per
/// material or per surface, share one decode. Throws luxel::Error for an index out of range
/// and as decode_image does.
[[nodiscard]] glm::vec3 image_mean_linear_color(const Scene& scene, int index);

/// The diffuse albedo the photon tracer and the light maps use for `material`: the base-colour
/// factor clamped to [0, 1], times the mean linear colour of its base-colour texture if it has
/// one (see the definition for why the mean is enough).
[[nodiscard]] glm::vec3 mean_diffuse_albedo(const Scene& scene, const Material& material);

}  // namespace luxel::scene
