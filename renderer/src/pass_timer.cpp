#include "pass_timer.hpp"

namespace luxel::renderer {

PassTimer::PassTimer() {
    for (FrameQueries& frame : frames_) {
        for (gl::Query& query : frame.queries) {
            query = gl::Query::create(GL_TIMESTAMP);
        }
    }
}

void PassTimer::begin_frame(std::uint64_t frame) {
    current_ = static_cast<std::size_t>(frame % kFramesInFlight);
    FrameQueries& queries = frames_[current_];
    queries.used.fill(false);
    queries.frame = frame;
    queries.pending = true;
}

void PassTimer::begin(RenderPass pass) {
    FrameQueries& queries = frames_[current_];
    const auto index = static_cast<std::size_t>(pass);
    queries.used[index] = true;
    glQueryCounter(queries.queries[2 * index].id(), GL_TIMESTAMP);
}

void PassTimer::end(RenderPass pass) {
    const auto index = static_cast<std::size_t>(pass);
    glQueryCounter(frames_[current_].queries[2 * index + 1].id(), GL_TIMESTAMP);
}

void PassTimer::collect(FrameTimings& out, bool wait) {
    // Newest first: the current frame, then the ones before it.
    for (std::size_t back = 0; back < kFramesInFlight; ++back) {
        FrameQueries& queries = frames_[(current_ + kFramesInFlight - back) % kFramesInFlight];
        if (!queries.pending || queries.frame <= out.frame) {
            continue;
        }
        bool ready = true;
        for (std::size_t pass = 0; pass < kRenderPassCount && ready; ++pass) {
            if (!queries.used[pass]) {
                continue;
            }
            GLint available = GL_FALSE;
            if (!(wait && back == 0)) {
                glGetQueryObjectiv(queries.queries[2 * pass + 1].id(), GL_QUERY_RESULT_AVAILABLE,
                                   &available);
                ready = available == GL_TRUE;
            }
        }
        if (!ready) {
            continue;
        }
        FrameTimings timings;
        timings.frame = queries.frame;
        for (std::size_t pass = 0; pass < kRenderPassCount; ++pass) {
            if (!queries.used[pass]) {
                continue;
            }
            // GL_QUERY_RESULT waits for the result when it is not there yet (wait = true).
            GLuint64 start = 0;
            GLuint64 end = 0;
            glGetQueryObjectui64v(queries.queries[2 * pass].id(), GL_QUERY_RESULT, &start);
            glGetQueryObjectui64v(queries.queries[2 * pass + 1].id(), GL_QUERY_RESULT, &end);
            timings.milliseconds[pass] =
                end > start ? static_cast<double>(end - start) * 1e-6 : 0.0;
        }
        queries.pending = false;
        out = timings;
        return;
    }
}

}  // namespace luxel::renderer
