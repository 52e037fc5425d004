#pragma once

#include "luxel/runtime/gl_objects.hpp"
#include "luxel/runtime/image.hpp"

namespace luxel::gl {

/// An off-screen HDR target: RGBA32F colour texture and a 24-bit depth buffer. Headless contexts
/// have no default framebuffer worth drawing into, so every frame is drawn into one of these.
class RenderTarget {
  public:
    RenderTarget() = default;
    /// Throws luxel::Error for a non-positive size or an incomplete framebuffer.
    RenderTarget(int width, int height);

    /// Binds the framebuffer and sets the viewport to the whole target.
    void bind() const;
    [[nodiscard]] int width() const { return width_; }
    [[nodiscard]] int height() const { return height_; }
    [[nodiscard]] const Texture& color() const { return color_; }
    [[nodiscard]] const Framebuffer& framebuffer() const { return framebuffer_; }

    /// Reads the colour attachment back as a linear float image (rows top first).
    [[nodiscard]] Image read_color() const;

  private:
    int width_ = 0;
    int height_ = 0;
    Texture color_;
    Renderbuffer depth_;
    Framebuffer framebuffer_;
};

/// Reads the current read framebuffer's `buffer` (GL_BACK, GL_FRONT, GL_COLOR_ATTACHMENT0...)
/// as float RGBA (rows top first).
[[nodiscard]] Image read_pixels(GLuint framebuffer, GLenum buffer, int width, int height);

}  // namespace luxel::gl
