#include "luxel/prep/page_images.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace luxel::prep {
namespace {

glm::vec3 hsv_to_rgb(float hue, float saturation, float value) {
    const float h = (hue - std::floor(hue)) * 6.0f;
    const float c = value * saturation;
    const float x = c * (1.0f - std::abs(std::fmod(h, 2.0f) - 1.0f));
    const float m = value - c;
    glm::vec3 rgb;
    switch (static_cast<int>(h)) {
        case 0:
            rgb = {c, x, 0};
            break;
        case 1:
            rgb = {x, c, 0};
            break;
        case 2:
            rgb = {0, c, x};
            break;
        case 3:
            rgb = {0, x, c};
            break;
        case 4:
            rgb = {x, 0, c};
            break;
        default:
            rgb = {c, 0, x};
            break;
    }
    return rgb + m;
}

}  // namespace

glm::vec3 surface_colour(int surface_id) {
    // Golden-ratio steps around the hue circle keep consecutive ids far apart in colour;
    // alternating brightness separates the ids that land on similar hues.
    const float hue = 0.618034f * static_cast<float>(surface_id) + 0.1f;
    const float value = surface_id % 2 == 0 ? 0.95f : 0.7f;
    const glm::vec3 srgb = hsv_to_rgb(hue, 0.7f, value);
    // The picture is written through the sRGB curve; choose colours in sRGB terms.
    return {srgb_to_linear(srgb.r), srgb_to_linear(srgb.g), srgb_to_linear(srgb.b)};
}

Image render_page(const PrepResult& result, int page) {
    const int size = result.page_size;
    // Enlarge small pages to about 256 pixels, in whole pixels per texel.
    const int zoom = std::max(1, 256 / std::max(1, size));
    const glm::vec4 unused(0.02f, 0.02f, 0.02f, 1.0f);
    Image image(size * zoom, size * zoom, unused);
    auto paint = [&](int x, int y, const glm::vec3& colour) {
        for (int dy = 0; dy < zoom; ++dy) {
            for (int dx = 0; dx < zoom; ++dx) {
                image.set_pixel(x * zoom + dx, y * zoom + dy, glm::vec4(colour, 1.0f));
            }
        }
    };
    const int padding = result.padding;
    for (const PreparedNode& node : result.nodes) {
        for (const PreparedSurface& surface : node.surfaces) {
            if (surface.page != page) {
                continue;
            }
            const glm::vec3 colour = surface_colour(surface.id);
            for (const int c : surface.charts) {
                const PlacedChart& placed = node.placed[static_cast<std::size_t>(c)];
                const scene::TexelRect& r = placed.rect;
                const CoverageMask reach = dilate(placed.mask, padding);
                for (int y = 0; y < reach.height; ++y) {
                    for (int x = 0; x < reach.width; ++x) {
                        const int mx = x - padding;
                        const int my = y - padding;
                        const bool covered = mx >= 0 && my >= 0 && mx < r.width && my < r.height &&
                                             placed.mask.at(mx, my);
                        if (covered) {
                            paint(r.x + mx, r.y + my, colour);
                        } else if (reach.at(x, y)) {
                            // The padding ring, dimmer.
                            paint(r.x + mx, r.y + my, colour * 0.25f);
                        }
                    }
                }
            }
        }
    }
    return image;
}

std::vector<std::filesystem::path> write_page_images(const PrepResult& result,
                                                     const std::filesystem::path& stem) {
    std::vector<std::filesystem::path> written;
    ToneMapSettings exact;
    exact.op = ToneMapOperator::Clamp;
    for (int page = 0; page < result.page_count; ++page) {
        std::filesystem::path file = stem;
        file += ".page" + std::to_string(page) + ".png";
        write_png(file, render_page(result, page), exact);
        written.push_back(file);
    }
    return written;
}

}  // namespace luxel::prep
