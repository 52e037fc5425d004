#include "luxel/runtime/gl_state_guard.hpp"

namespace luxel::gl {
namespace {

void set_enabled(GLenum capability, bool enabled) {
    if (enabled) {
        glEnable(capability);
    } else {
        glDisable(capability);
    }
}

}  // namespace

StateGuard::StateGuard() {
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_framebuffer_);
    glGetIntegerv(GL_VIEWPORT, viewport_.data());
    glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vertex_array_);
    glGetIntegerv(GL_DEPTH_FUNC, &depth_func_);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &depth_mask_);
    glGetIntegerv(GL_CLIP_ORIGIN, &clip_origin_);
    glGetIntegerv(GL_CLIP_DEPTH_MODE, &clip_depth_mode_);
    glGetIntegerv(GL_FRONT_FACE, &front_face_);
    glGetIntegerv(GL_CULL_FACE_MODE, &cull_face_mode_);
    depth_test_ = glIsEnabled(GL_DEPTH_TEST) == GL_TRUE;
    cull_face_ = glIsEnabled(GL_CULL_FACE) == GL_TRUE;
    blend_ = glIsEnabled(GL_BLEND) == GL_TRUE;
    scissor_test_ = glIsEnabled(GL_SCISSOR_TEST) == GL_TRUE;
    for (GLenum i = 0; i < clip_distances_.size(); ++i) {
        clip_distances_[i] = glIsEnabled(GL_CLIP_DISTANCE0 + i) == GL_TRUE;
    }
}

StateGuard::~StateGuard() {
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(draw_framebuffer_));
    glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
    glUseProgram(static_cast<GLuint>(program_));
    glBindVertexArray(static_cast<GLuint>(vertex_array_));
    glDepthFunc(static_cast<GLenum>(depth_func_));
    glDepthMask(depth_mask_);
    glClipControl(static_cast<GLenum>(clip_origin_), static_cast<GLenum>(clip_depth_mode_));
    glFrontFace(static_cast<GLenum>(front_face_));
    glCullFace(static_cast<GLenum>(cull_face_mode_));
    set_enabled(GL_DEPTH_TEST, depth_test_);
    set_enabled(GL_CULL_FACE, cull_face_);
    set_enabled(GL_BLEND, blend_);
    set_enabled(GL_SCISSOR_TEST, scissor_test_);
    for (GLenum i = 0; i < clip_distances_.size(); ++i) {
        set_enabled(GL_CLIP_DISTANCE0 + i, clip_distances_[i]);
    }
}

}  // namespace luxel::gl
