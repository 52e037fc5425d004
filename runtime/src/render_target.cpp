#include "luxel/runtime/render_target.hpp"

#include <cstring>

#include "luxel/runtime/error.hpp"

namespace luxel::gl {

RenderTarget::RenderTarget(int width, int height)
    : width_(width),
      height_(height),
      color_(Texture::create_2d(GL_RGBA32F, width, height)),
      depth_(Renderbuffer::create(GL_DEPTH_COMPONENT24, width, height)),
      framebuffer_(Framebuffer::create()) {
    framebuffer_.attach(GL_COLOR_ATTACHMENT0, color_);
    framebuffer_.attach(GL_DEPTH_ATTACHMENT, depth_);
    framebuffer_.check_complete("RenderTarget");
}

void RenderTarget::bind() const {
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
    glViewport(0, 0, width_, height_);
}

Image RenderTarget::read_color() const {
    return read_pixels(framebuffer_.id(), GL_COLOR_ATTACHMENT0, width_, height_);
}

Image read_pixels(GLuint framebuffer, GLenum buffer, int width, int height) {
    Image image(width, height);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
    glReadBuffer(buffer);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadnPixels(0, 0, width, height, GL_RGBA, GL_FLOAT,
                  static_cast<GLsizei>(image.rgba.size() * sizeof(float)), image.rgba.data());
    check_error("read_pixels");
    // GL's first row is the bottom one; files and Image keep the top row first.
    const std::size_t row = static_cast<std::size_t>(width) * 4;
    std::vector<float> swap(row);
    for (int y = 0; y < height / 2; ++y) {
        float* top = image.rgba.data() + static_cast<std::size_t>(y) * row;
        float* bottom = image.rgba.data() + static_cast<std::size_t>(height - 1 - y) * row;
        std::memcpy(swap.data(), top, row * sizeof(float));
        std::memcpy(top, bottom, row * sizeof(float));
        std::memcpy(bottom, swap.data(), row * sizeof(float));
    }
    return image;
}

}  // namespace luxel::gl
