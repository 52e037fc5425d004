#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/scene/image_decode.hpp"
#include "luxel/scene/scene.hpp"

/// Integrals of a material texture over a triangle's UVs: what an emissive texture emits from
/// each part of a mesh (the photons and the light maps cannot sample a texture per pixel, but
/// they can emit each part's mean from where it is).
namespace luxel::scene {

/// An image read as linear RGB (sRGB decoded, IEC 61966-2-1), row 0 at v = 0 as in
/// DecodedImage. It keeps the 8-bit texels and decodes each on reading: a float copy of the
/// largest image the loader accepts (2^28 pixels) would take 3 GiB.
class LinearImage {
  public:
    LinearImage() = default;
    explicit LinearImage(DecodedImage image);
    /// An image of the given linear values, as tests and generated textures make them.
    LinearImage(int width, int height, const std::vector<glm::vec3>& texels);

    [[nodiscard]] int width() const { return image_.width; }
    [[nodiscard]] int height() const { return image_.height; }
    [[nodiscard]] bool empty() const { return image_.width <= 0 || image_.height <= 0; }
    /// Texel (x, y) under glTF's default REPEAT wrap (any integers). An empty image: 0.
    [[nodiscard]] glm::vec3 wrapped(std::int64_t x, std::int64_t y) const;
    /// The image at `uv` as a GL sampler with LINEAR filtering and REPEAT wrap reads it (glTF's
    /// defaults): the four nearest texels' centres, bilinearly. A non-finite UV reads as 0.
    [[nodiscard]] glm::vec3 bilinear(const glm::vec2& uv) const;

  private:
    DecodedImage image_;
    std::vector<glm::vec3> linear_;  // only for the values constructor
};

/// The most texel lookups one mean_over_uv_triangle call makes by default: a triangle whose
/// bounding box spans more texel squares than its budget (a floor tiling a texture many times)
/// is estimated from that many low-discrepancy points instead of clipped exactly, so the cost
/// per triangle is bounded whatever a file's UVs say.
inline constexpr std::int64_t kMaxExactTexels = 4096;
/// What all the triangles of one call to triangle_emission (or one emitter's pieces) may cost
/// together, in texel lookups: each gets its share, at least kMinTexelsPerTriangle.
inline constexpr std::int64_t kMaxTexelsPerCall = std::int64_t{1} << 22;
inline constexpr std::int64_t kMinTexelsPerTriangle = 64;

/// The per-triangle budget for `triangles` triangles sharing kMaxTexelsPerCall.
[[nodiscard]] std::int64_t texels_per_triangle(std::size_t triangles);

/// The mean of `image` over the triangle with UVs (a, b, c), each texel constant over its
/// square (the renderer filters between texels, which over a region wider than a texel changes
/// nothing on average): the texels' values weighted by the triangle's area in each
/// (triangle_area_in_texel), with REPEAT wrap, when its bounding box spans at most `budget`
/// texel squares; else the mean of `budget` low-discrepancy points over it. A triangle with no
/// UV area: the texel under a. Non-finite UVs: 0.
[[nodiscard]] glm::vec3 mean_over_uv_triangle(const LinearImage& image, glm::dvec2 a, glm::dvec2 b,
                                              glm::dvec2 c, std::int64_t budget = kMaxExactTexels);

/// The image a material's emissive texture samples, linear; empty when it has none. Throws
/// luxel::Error naming the scene's file, the material and the image if it does not decode.
[[nodiscard]] LinearImage emissive_texels(const Scene& scene, const Material& material);

/// Per triangle of `primitive`, the area-weighted mean of what its material emits: emitted
/// radiance times the emissive texture's mean over the triangle's TEXCOORD_0 (untextured, or
/// without TEXCOORD_0: emitted radiance), W/(m^2 sr). `texels` is emissive_texels' result.
[[nodiscard]] std::vector<glm::vec3> triangle_emission(const Primitive& primitive,
                                                       const Material& material,
                                                       const LinearImage& texels);

/// The area-weighted mean of `per_triangle` over the primitive's triangles (their areas in the
/// primitive's own coordinates): what the surface emits on average. No area: 0.
[[nodiscard]] glm::vec3 mean_emission(const Primitive& primitive,
                                      const std::vector<glm::vec3>& per_triangle);

}  // namespace luxel::scene
