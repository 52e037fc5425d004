#pragma once

#include <array>
#include <cstdint>

#include "luxel/renderer/frame_renderer.hpp"
#include "luxel/runtime/gl_objects.hpp"

namespace luxel::renderer {

/// GPU time per render pass from GL_TIMESTAMP queries (a pair per pass; timestamps rather than
/// GL_TIME_ELAPSED because elapsed-time queries cannot overlap and a pass may want to nest).
/// Queries of kFramesInFlight frames rotate, so reading the results of an older frame never
/// stalls the pipeline; collect(wait = true) blocks for the newest frame instead.
class PassTimer {
  public:
    PassTimer();

    void begin_frame(std::uint64_t frame);
    void begin(RenderPass pass);
    void end(RenderPass pass);
    /// Updates `out` with the newest frame whose queries are all available (with `wait`, the
    /// frame just recorded). Leaves `out` unchanged when none is.
    void collect(FrameTimings& out, bool wait);

  private:
    static constexpr std::size_t kFramesInFlight = 3;
    struct FrameQueries {
        std::array<gl::Query, 2 * kRenderPassCount> queries;
        std::array<bool, kRenderPassCount> used{};
        std::uint64_t frame = 0;
        bool pending = false;
    };

    std::array<FrameQueries, kFramesInFlight> frames_;
    std::size_t current_ = 0;
};

}  // namespace luxel::renderer
