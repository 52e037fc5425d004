#pragma once

// Small line plots written as PNG (luxel::Image and write_png): error against ms per frame,
// error against frames after a change. Text by stb_easy_font, lines by Bresenham.

#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/runtime/image.hpp"

namespace luxel::bench {

struct Series {
    std::string label;
    std::vector<glm::dvec2> points;  ///< drawn in order (a curve), each with a marker
    bool dashed = false;
};

struct HorizontalLine {
    double y = 0.0;
    std::string label;
};

struct PlotSpec {
    std::string title;
    std::string x_label;
    std::string y_label;
    std::vector<Series> series;
    /// Marked with rings and joined by a black dashed line (the Pareto front).
    std::vector<glm::dvec2> front;
    std::vector<HorizontalLine> lines;  ///< grey reference levels (a goal, a threshold)
};

/// Renders the plot: linear axes from 0 (or the data's minimum if negative) to a rounded
/// maximum, ticks at 1-2-5 steps, a legend at the right.
[[nodiscard]] Image render_plot(const PlotSpec& spec, int width = 900, int height = 560);
/// render_plot written as an sRGB PNG (no tone mapping: the colours are exact).
void write_plot(const std::filesystem::path& path, const PlotSpec& spec);

/// The points not dominated by any other (lower x and lower y), sorted by x.
[[nodiscard]] std::vector<glm::dvec2> pareto_front(std::vector<glm::dvec2> points);

}  // namespace luxel::bench
