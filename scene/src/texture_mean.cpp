#include "luxel/scene/texture_mean.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>

#include "luxel/runtime/error.hpp"
#include "luxel/scene/texel_coverage.hpp"

namespace luxel::scene {
namespace {

std::int64_t wrap(std::int64_t value, std::int64_t size) {
    const std::int64_t r = value % size;
    return r < 0 ? r + size : r;
}

/// The estimate for triangles too large to clip texel by texel: `points` points of the R2
/// low-discrepancy sequence (Roberts' generalised golden ratio), folded into the triangle. Not a
/// regular grid: a grid's spacing can alias with a texture repeated across the triangle (a
/// tiled floor) and pick the same few texels in every tile.
glm::vec3 stratified_mean(const LinearImage& image, const glm::dvec2& a, const glm::dvec2& b,
                          const glm::dvec2& c, std::int64_t points) {
    constexpr double kPlastic = 1.32471795724474602596;  // x^3 = x + 1
    constexpr double kStepU = 1.0 / kPlastic;
    constexpr double kStepV = 1.0 / (kPlastic * kPlastic);
    const std::int64_t count = std::max<std::int64_t>(points, 1);
    glm::dvec3 sum(0.0);
    for (std::int64_t i = 0; i < count; ++i) {
        const auto x = static_cast<double>(i);
        double s = std::fmod(0.5 + kStepU * x, 1.0);
        double q = std::fmod(0.5 + kStepV * x, 1.0);
        if (s + q > 1.0) {
            s = 1.0 - s;
            q = 1.0 - q;
        }
        const glm::dvec2 uv = a + s * (b - a) + q * (c - a);
        sum += glm::dvec3(image.wrapped(static_cast<std::int64_t>(std::floor(uv.x)),
                                        static_cast<std::int64_t>(std::floor(uv.y))));
    }
    return glm::vec3(sum / static_cast<double>(count));
}

}  // namespace

LinearImage::LinearImage(DecodedImage image) : image_(std::move(image)) {
    const std::size_t count = static_cast<std::size_t>(std::max(image_.width, 0)) *
                              static_cast<std::size_t>(std::max(image_.height, 0));
    if (count == 0 || image_.rgba.size() < count * 4) {
        image_ = {};
    }
}

LinearImage::LinearImage(int width, int height, const std::vector<glm::vec3>& texels) {
    if (width > 0 && height > 0 &&
        texels.size() == static_cast<std::size_t>(width) * static_cast<std::size_t>(height)) {
        image_.width = width;
        image_.height = height;
        linear_ = texels;
    }
}

glm::vec3 LinearImage::wrapped(std::int64_t x, std::int64_t y) const {
    if (empty()) {
        return glm::vec3(0.0f);
    }
    const auto index =
        static_cast<std::size_t>(wrap(y, image_.height) * image_.width + wrap(x, image_.width));
    if (!linear_.empty()) {
        return linear_[index];
    }
    const std::array<float, 256>& table = srgb8_to_linear();
    const std::uint8_t* texel = image_.rgba.data() + 4 * index;
    return {table[texel[0]], table[texel[1]], table[texel[2]]};
}

glm::vec3 LinearImage::bilinear(const glm::vec2& uv) const {
    if (empty()) {
        return glm::vec3(0.0f);
    }
    // Only the fraction matters under REPEAT; taking it first keeps the texel indices small
    // (and defined) for any finite UV a file holds.
    const auto fraction = [](float t) {
        const double d = std::isfinite(t) ? static_cast<double>(t) : 0.0;
        return d - std::floor(d);
    };
    const double x = fraction(uv.x) * image_.width - 0.5;
    const double y = fraction(uv.y) * image_.height - 0.5;
    const double x0 = std::floor(x);
    const double y0 = std::floor(y);
    const auto fx = static_cast<float>(x - x0);
    const auto fy = static_cast<float>(y - y0);
    const auto ix = static_cast<std::int64_t>(x0);
    const auto iy = static_cast<std::int64_t>(y0);
    const glm::vec3 top = glm::mix(wrapped(ix, iy), wrapped(ix + 1, iy), fx);
    const glm::vec3 bottom = glm::mix(wrapped(ix, iy + 1), wrapped(ix + 1, iy + 1), fx);
    return glm::mix(top, bottom, fy);
}

std::int64_t texels_per_triangle(std::size_t triangles) {
    const auto share =
        kMaxTexelsPerCall / static_cast<std::int64_t>(std::max<std::size_t>(triangles, 1));
    return std::clamp(share, kMinTexelsPerTriangle, kMaxExactTexels);
}

glm::vec3 mean_over_uv_triangle(const LinearImage& image, glm::dvec2 a, glm::dvec2 b, glm::dvec2 c,
                                std::int64_t budget) {
    if (image.empty()) {
        return glm::vec3(0.0f);
    }
    const glm::dvec2 size(image.width(), image.height());
    a *= size;
    b *= size;
    c *= size;
    const glm::dvec2 low = glm::min(a, glm::min(b, c));
    const glm::dvec2 high = glm::max(a, glm::max(b, c));
    if (!std::isfinite(low.x) || !std::isfinite(low.y) || !std::isfinite(high.x) ||
        !std::isfinite(high.y)) {
        return glm::vec3(0.0f);
    }
    const double area = 0.5 * std::abs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
    if (!(area > 0.0)) {
        return image.wrapped(static_cast<std::int64_t>(std::clamp(std::floor(a.x), -1e15, 1e15)),
                             static_cast<std::int64_t>(std::clamp(std::floor(a.y), -1e15, 1e15)));
    }
    const double columns = std::floor(high.x) - std::floor(low.x) + 1.0;
    const double rows = std::floor(high.y) - std::floor(low.y) + 1.0;
    if (columns * rows > static_cast<double>(std::max<std::int64_t>(budget, 1))) {
        return stratified_mean(image, a, b, c, budget);
    }
    // The texel squares are taken relative to the triangle's first texel, so the clipping
    // stays exact far from the origin (UVs of a tiled surface can be large).
    const glm::dvec2 origin(std::floor(low.x), std::floor(low.y));
    const glm::dvec2 ra = a - origin;
    const glm::dvec2 rb = b - origin;
    const glm::dvec2 rc = c - origin;
    glm::dvec3 sum(0.0);
    double covered = 0.0;
    for (int y = 0; y < static_cast<int>(rows); ++y) {
        for (int x = 0; x < static_cast<int>(columns); ++x) {
            const double inside = triangle_area_in_texel(ra, rb, rc, x, y);
            if (inside > 0.0) {
                sum += glm::dvec3(image.wrapped(static_cast<std::int64_t>(origin.x) + x,
                                                static_cast<std::int64_t>(origin.y) + y)) *
                       inside;
                covered += inside;
            }
        }
    }
    // Dividing by the clipped areas' sum (equal to `area` up to rounding) keeps a constant
    // texture's mean exactly that constant.
    return covered > 0.0 ? glm::vec3(sum / covered) : glm::vec3(0.0f);
}

LinearImage emissive_texels(const Scene& scene, const Material& material) {
    if (material.emissive_image < 0) {
        return {};
    }
    try {
        if (static_cast<std::size_t>(material.emissive_image) >= scene.images.size()) {
            throw Error("image " + std::to_string(material.emissive_image) +
                        " is out of range (the scene has " + std::to_string(scene.images.size()) +
                        " images)");
        }
        return LinearImage(
            decode_image(scene.images[static_cast<std::size_t>(material.emissive_image)],
                         material.emissive_image));
    } catch (const Error& e) {
        throw Error(
            scene.in_file("material '" + material.name + "': emissive texture: " + e.what()));
    }
}

std::vector<glm::vec3> triangle_emission(const Primitive& primitive, const Material& material,
                                         const LinearImage& texels) {
    const glm::vec3 radiance = material.emitted_radiance();
    std::vector<glm::vec3> out(primitive.triangle_count(), radiance);
    if (texels.empty() || primitive.texcoords0.size() != primitive.positions.size()) {
        return out;
    }
    const std::int64_t budget = texels_per_triangle(out.size());
    for (std::size_t t = 0; t < out.size(); ++t) {
        const auto uv = [&](std::size_t k) {
            return glm::dvec2(primitive.texcoords0[primitive.indices[3 * t + k]]);
        };
        out[t] = radiance * mean_over_uv_triangle(texels, uv(0), uv(1), uv(2), budget);
    }
    return out;
}

glm::vec3 mean_emission(const Primitive& primitive, const std::vector<glm::vec3>& per_triangle) {
    glm::dvec3 sum(0.0);
    double total = 0.0;
    const std::size_t count = std::min(per_triangle.size(), primitive.triangle_count());
    for (std::size_t t = 0; t < count; ++t) {
        const glm::dvec3 p0(primitive.positions[primitive.indices[3 * t]]);
        const glm::dvec3 p1(primitive.positions[primitive.indices[3 * t + 1]]);
        const glm::dvec3 p2(primitive.positions[primitive.indices[3 * t + 2]]);
        const double area = 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0));
        if (area > 0.0 && std::isfinite(area)) {
            sum += glm::dvec3(per_triangle[t]) * area;
            total += area;
        }
    }
    return total > 0.0 ? glm::vec3(sum / total) : glm::vec3(0.0f);
}

}  // namespace luxel::scene
