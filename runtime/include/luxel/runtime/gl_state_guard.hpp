#pragma once

#include <array>

#include "luxel/runtime/gl.hpp"

namespace luxel::gl {

/// Records the GL state the gather passes change and restores it on destruction, so a
/// gatherer can run in the middle of a frame without the renderer re-establishing its own
/// state: framebuffer, viewport, program, vertex array, depth test/function/mask, clip control
/// (the gather uses reversed depth in [0, 1]), face culling, blending, scissor test and the
/// four clip distances.
class StateGuard {
  public:
    StateGuard();
    ~StateGuard();
    StateGuard(const StateGuard&) = delete;
    StateGuard& operator=(const StateGuard&) = delete;

  private:
    GLint draw_framebuffer_ = 0;
    std::array<GLint, 4> viewport_{};
    GLint program_ = 0;
    GLint vertex_array_ = 0;
    GLint depth_func_ = GL_LESS;
    GLboolean depth_mask_ = GL_TRUE;
    GLint clip_origin_ = GL_LOWER_LEFT;
    GLint clip_depth_mode_ = GL_NEGATIVE_ONE_TO_ONE;
    GLint front_face_ = GL_CCW;
    GLint cull_face_mode_ = GL_BACK;
    bool depth_test_ = false;
    bool cull_face_ = false;
    bool blend_ = false;
    bool scissor_test_ = false;
    std::array<bool, 4> clip_distances_{};
};

}  // namespace luxel::gl
