#include "luxel/runtime/gl_limits.hpp"

#include <algorithm>

#include "luxel/runtime/gl.hpp"

namespace luxel::gl {

int largest_render_target() {
    GLint max_texture = 0;
    GLint max_width = 0;
    GLint max_height = 0;
    GLint max_renderbuffer = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_texture);
    glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &max_width);
    glGetIntegerv(GL_MAX_FRAMEBUFFER_HEIGHT, &max_height);
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_renderbuffer);
    return std::min({max_texture, max_width, max_height, max_renderbuffer});
}

}  // namespace luxel::gl
