// The frame's passes as the timings name them (the HUD, report.json's pass_ms, the benchmarks).

#include <array>
#include <string_view>

#include "luxel/renderer/frame_renderer.hpp"

namespace luxel::renderer {

std::string_view name(RenderPass pass) {
    static constexpr std::array<std::string_view, kRenderPassCount> names = {
        "shadows",   "gbuffer",       "direct",    "indirect",    "specular",
        "composite", "anti_aliasing", "sky_edges", "soft_shadows"};
    return names[static_cast<std::size_t>(pass)];
}

double FrameTimings::total() const {
    double sum = 0.0;
    for (double ms : milliseconds) {
        sum += ms;
    }
    return sum;
}

}  // namespace luxel::renderer
