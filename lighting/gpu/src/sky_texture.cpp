#include "luxel/lighting/gpu/sky_texture.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/constants.hpp>

namespace luxel::lighting {
namespace {

/// Texels per full turn and per half turn at least: a grid coarser than this (a uniform sky
/// is 1 x 2 cells) is repeated cell by cell up to it. The texture is read without filtering, so
/// a direction reads its cell's radiance, as SkyRadiance::radiance (and so luxel-ref) does: a
/// bilinear filter had blended a texel's width across every cell's edge, and across the
/// horizon, where the daylight sky meets its ground with a step, it drew a 4-pixel gradient
/// where the reference has one edge (docs/RESULTS.md, "Frame 0 at the main job's
/// resolution").
constexpr int kMinWidth = 512;
constexpr int kMinHeight = 256;

bool same(const std::vector<RadianceAtlas::Sky>& a, const std::vector<RadianceAtlas::Sky>& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](const auto& x, const auto& y) {
        return x.radiance == y.radiance && x.scale == y.scale;
    });
}

/// One sky's cells times its scale, each repeated to at least kMinWidth x kMinHeight texels.
std::vector<glm::vec3> texels_of(const SkyRadiance& sky, float scale, int& width, int& height) {
    const int repeat_x = std::max(1, (kMinWidth + sky.width() - 1) / sky.width());
    const int repeat_y = std::max(1, (kMinHeight + sky.height() - 1) / sky.height());
    width = sky.width() * repeat_x;
    height = sky.height() * repeat_y;
    std::vector<glm::vec3> texels(static_cast<std::size_t>(width) *
                                  static_cast<std::size_t>(height));
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t cell =
                static_cast<std::size_t>(y / repeat_y) * static_cast<std::size_t>(sky.width()) +
                static_cast<std::size_t>(x / repeat_x);
            texels[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                   static_cast<std::size_t>(x)] = sky.cells()[cell] * scale;
        }
    }
    return texels;
}

/// Several skies summed, each looked up at the centre of every texel of a 1024 x 512 grid.
std::vector<glm::vec3> sum_of(const RadianceAtlas& atlas, int& width, int& height) {
    width = 2 * kMinWidth;
    height = 2 * kMinHeight;
    const double pi = glm::pi<double>();
    std::vector<glm::vec3> texels(static_cast<std::size_t>(width) *
                                  static_cast<std::size_t>(height));
    for (int y = 0; y < height; ++y) {
        const double theta = pi * (y + 0.5) / height;
        for (int x = 0; x < width; ++x) {
            const double phi = 2.0 * pi * (x + 0.5) / width;
            const glm::vec3 direction(static_cast<float>(std::sin(theta) * std::cos(phi)),
                                      static_cast<float>(std::cos(theta)),
                                      static_cast<float>(std::sin(theta) * std::sin(phi)));
            texels[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                   static_cast<std::size_t>(x)] = atlas.sky(direction);
        }
    }
    return texels;
}

}  // namespace

bool SkyTexture::sync(const RadianceAtlas& atlas) {
    if (same(shown_, atlas.skies)) {
        return present();
    }
    shown_ = atlas.skies;
    ++changes_;
    texture_ = gl::Texture();
    if (shown_.empty()) {
        return false;
    }
    int width = 0;
    int height = 0;
    const std::vector<glm::vec3> texels =
        shown_.size() == 1 && shown_[0].radiance != nullptr
            ? texels_of(*shown_[0].radiance, shown_[0].scale, width, height)
            : sum_of(atlas, width, height);
    texture_ = gl::Texture::create_2d(GL_RGB32F, width, height);
    glTextureSubImage2D(texture_.id(), 0, 0, 0, width, height, GL_RGB, GL_FLOAT, texels.data());
    glTextureParameteri(texture_.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(texture_.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    // Azimuth wraps around; the poles do not.
    glTextureParameteri(texture_.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(texture_.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return true;
}

}  // namespace luxel::lighting
