#include "plot.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wold-style-cast"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wshadow"
#include <stb_easy_font.h>
#pragma GCC diagnostic pop

namespace luxel::bench {
namespace {

/// Distinct colours (sRGB) for up to ten curves, then repeated.
constexpr std::array<glm::vec3, 10> kPalette{{{0.12f, 0.47f, 0.71f},
                                              {1.00f, 0.50f, 0.05f},
                                              {0.17f, 0.63f, 0.17f},
                                              {0.84f, 0.15f, 0.16f},
                                              {0.58f, 0.40f, 0.74f},
                                              {0.55f, 0.34f, 0.29f},
                                              {0.89f, 0.47f, 0.76f},
                                              {0.50f, 0.50f, 0.50f},
                                              {0.74f, 0.74f, 0.13f},
                                              {0.09f, 0.75f, 0.81f}}};
constexpr int kTextScale = 2;

/// Draws on an Image in sRGB colours (stored linear, so write_png's encoding gives them back).
class Canvas {
  public:
    Canvas(int width, int height) : image_(width, height, glm::vec4(1.0f)) {}

    void dot(int x, int y, const glm::vec3& srgb) {
        if (x >= 0 && y >= 0 && x < image_.width && y < image_.height) {
            image_.set_pixel(x, y, glm::vec4(linear(srgb), 1.0f));
        }
    }
    void rect(int x0, int y0, int x1, int y1, const glm::vec3& srgb) {
        for (int y = std::max(0, y0); y < std::min(image_.height, y1); ++y) {
            for (int x = std::max(0, x0); x < std::min(image_.width, x1); ++x) {
                dot(x, y, srgb);
            }
        }
    }
    /// Bresenham, `thick` pixels square; dashed: 6 on, 4 off.
    void line(glm::ivec2 a, glm::ivec2 b, const glm::vec3& srgb, int thick = 2,
              bool dashed = false) {
        const int dx = std::abs(b.x - a.x);
        const int dy = -std::abs(b.y - a.y);
        const int sx = a.x < b.x ? 1 : -1;
        const int sy = a.y < b.y ? 1 : -1;
        int error = dx + dy;
        for (int step = 0;; ++step) {
            if (!dashed || step % 10 < 6) {
                rect(a.x - thick / 2, a.y - thick / 2, a.x - thick / 2 + thick,
                     a.y - thick / 2 + thick, srgb);
            }
            if (a == b) {
                break;
            }
            const int e2 = 2 * error;
            if (e2 >= dy) {
                error += dy;
                a.x += sx;
            }
            if (e2 <= dx) {
                error += dx;
                a.y += sy;
            }
        }
    }
    void ring(glm::ivec2 c, int radius, const glm::vec3& srgb) {
        for (int y = -radius - 1; y <= radius + 1; ++y) {
            for (int x = -radius - 1; x <= radius + 1; ++x) {
                const double r = std::sqrt(static_cast<double>(x * x + y * y));
                if (std::abs(r - radius) < 1.0) {
                    dot(c.x + x, c.y + y, srgb);
                }
            }
        }
    }
    /// stb_easy_font's quads, scaled; returns the text's width in pixels.
    int text(int x, int y, const std::string& s, const glm::vec3& srgb) {
        std::vector<char> buffer(s.size() * 300 + 64);
        std::vector<char> copy(s.begin(), s.end());
        copy.push_back('\0');
        const int quads = stb_easy_font_print(0.0f, 0.0f, copy.data(), nullptr, buffer.data(),
                                              static_cast<int>(buffer.size()));
        // Each vertex: x, y, z floats and four colour bytes (16 bytes); four per quad.
        for (int q = 0; q < quads; ++q) {
            float corner[4][2];
            for (int v = 0; v < 4; ++v) {
                std::memcpy(corner[v], buffer.data() + (q * 4 + v) * 16, 2 * sizeof(float));
            }
            const int x0 = x + static_cast<int>(corner[0][0]) * kTextScale;
            const int y0 = y + static_cast<int>(corner[0][1]) * kTextScale;
            const int x1 = x + static_cast<int>(corner[2][0]) * kTextScale;
            const int y1 = y + static_cast<int>(corner[2][1]) * kTextScale;
            rect(std::min(x0, x1), std::min(y0, y1), std::max(x0, x1), std::max(y0, y1), srgb);
        }
        return text_width(s);
    }
    static int text_width(const std::string& s) {
        std::vector<char> copy(s.begin(), s.end());
        copy.push_back('\0');
        return stb_easy_font_width(copy.data()) * kTextScale;
    }
    [[nodiscard]] const Image& image() const { return image_; }

  private:
    static glm::vec3 linear(const glm::vec3& srgb) {
        return {srgb_to_linear(srgb.x), srgb_to_linear(srgb.y), srgb_to_linear(srgb.z)};
    }
    Image image_;
};

double nice_step(double range) {
    const double raw = range / 5.0;
    const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
    for (const double m : {1.0, 2.0, 5.0}) {
        if (m * magnitude >= raw) {
            return m * magnitude;
        }
    }
    return 10.0 * magnitude;
}

std::string label_of(double v, double step) {
    char buffer[32];
    const int decimals = step >= 1.0 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
    std::snprintf(buffer, sizeof(buffer), "%.*f", decimals, v);
    return buffer;
}

}  // namespace

Image render_plot(const PlotSpec& spec, int width, int height) {
    Canvas canvas(width, height);
    glm::dvec2 lo(0.0);
    glm::dvec2 hi(0.0);
    bool any = false;
    const auto extend = [&](const glm::dvec2& p) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y)) {
            return;
        }
        lo = glm::min(lo, p);
        hi = any ? glm::max(hi, p) : glm::max(p, glm::dvec2(0.0));
        any = true;
    };
    for (const Series& s : spec.series) {
        for (const glm::dvec2& p : s.points) {
            extend(p);
        }
    }
    for (const HorizontalLine& l : spec.lines) {
        extend({lo.x, l.y});
    }
    if (!(hi.x > lo.x)) {
        hi.x = lo.x + 1.0;
    }
    if (!(hi.y > lo.y)) {
        hi.y = lo.y + 1.0;
    }
    const glm::dvec2 step(nice_step(hi.x - lo.x), nice_step(hi.y - lo.y));
    hi = glm::ceil(hi / step) * step;
    lo = glm::floor(lo / step) * step;

    const int left = 80;
    const int right = width - 260;
    const int top = 50;
    const int bottom = height - 60;
    const auto to_pixel = [&](const glm::dvec2& p) {
        const glm::dvec2 t = (p - lo) / (hi - lo);
        return glm::ivec2(left + static_cast<int>(std::lround(t.x * (right - left))),
                          bottom - static_cast<int>(std::lround(t.y * (bottom - top))));
    };
    const glm::vec3 black(0.0f);
    const glm::vec3 grid(0.88f);
    for (double x = lo.x; x <= hi.x + 0.5 * step.x; x += step.x) {
        const int px = to_pixel({x, lo.y}).x;
        canvas.line({px, top}, {px, bottom}, grid, 1);
        const std::string text = label_of(x, step.x);
        canvas.text(px - Canvas::text_width(text) / 2, bottom + 8, text, black);
    }
    for (double y = lo.y; y <= hi.y + 0.5 * step.y; y += step.y) {
        const int py = to_pixel({lo.x, y}).y;
        canvas.line({left, py}, {right, py}, grid, 1);
        const std::string text = label_of(y, step.y);
        canvas.text(left - 8 - Canvas::text_width(text), py - 6, text, black);
    }
    canvas.line({left, top}, {left, bottom}, black, 1);
    canvas.line({left, bottom}, {right, bottom}, black, 1);
    canvas.text(left + 40, 10, spec.title, black);
    canvas.text((left + right) / 2 - Canvas::text_width(spec.x_label) / 2, bottom + 32,
                spec.x_label, black);
    canvas.text(8, top - 20, spec.y_label, black);

    for (const HorizontalLine& l : spec.lines) {
        const int py = to_pixel({lo.x, l.y}).y;
        canvas.line({left, py}, {right, py}, glm::vec3(0.45f), 1, true);
        canvas.text(right - Canvas::text_width(l.label) - 4, py - 16, l.label, glm::vec3(0.35f));
    }
    for (std::size_t i = 1; i < spec.front.size(); ++i) {
        canvas.line(to_pixel(spec.front[i - 1]), to_pixel(spec.front[i]), black, 1, true);
    }
    for (const glm::dvec2& p : spec.front) {
        canvas.ring(to_pixel(p), 8, black);
    }
    int legend_y = top;
    for (std::size_t i = 0; i < spec.series.size(); ++i) {
        const Series& s = spec.series[i];
        const glm::vec3 colour = kPalette[i % kPalette.size()];
        for (std::size_t k = 0; k < s.points.size(); ++k) {
            if (k > 0) {
                canvas.line(to_pixel(s.points[k - 1]), to_pixel(s.points[k]), colour, 2, s.dashed);
            }
            const glm::ivec2 p = to_pixel(s.points[k]);
            if (s.points.size() < 40) {
                canvas.rect(p.x - 3, p.y - 3, p.x + 4, p.y + 4, colour);
            }
        }
        canvas.rect(right + 16, legend_y + 4, right + 36, legend_y + 10, colour);
        canvas.text(right + 42, legend_y, s.label, black);
        legend_y += 22;
    }
    if (!spec.front.empty()) {
        canvas.ring({right + 26, legend_y + 7}, 6, black);
        canvas.text(right + 42, legend_y, "Pareto front", black);
    }
    return canvas.image();
}

void write_plot(const std::filesystem::path& path, const PlotSpec& spec) {
    ToneMapSettings exact;
    exact.op = ToneMapOperator::Clamp;
    exact.exposure = 1.0f;
    write_png(path, render_plot(spec), exact);
}

std::vector<glm::dvec2> pareto_front(std::vector<glm::dvec2> points) {
    std::erase_if(points, [](const glm::dvec2& p) { return !std::isfinite(p.x + p.y); });
    std::sort(points.begin(), points.end(), [](const glm::dvec2& a, const glm::dvec2& b) {
        return a.x < b.x || (a.x == b.x && a.y < b.y);
    });
    std::vector<glm::dvec2> front;
    for (const glm::dvec2& p : points) {
        if (front.empty() || p.y < front.back().y) {
            front.push_back(p);
        }
    }
    return front;
}

}  // namespace luxel::bench
