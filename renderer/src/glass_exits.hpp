#pragma once

#include "luxel/renderer/frame_camera.hpp"
#include "luxel/runtime/gl_objects.hpp"
#include "luxel/runtime/program.hpp"
#include "scene_draws.hpp"

namespace luxel {
class ShaderLibrary;
}

namespace luxel::renderer {

/// Where view rays leave closed glass (docs/METHOD.md §8.3, two-surface refraction after
/// Wyman, "An Approximate Image-Space Approach for Interactive Refraction", SIGGRAPH 2005):
/// the nearest back face of every closed transmissive primitive per pixel, its world position
/// and outward normal, which the specular pass searches along each refracted ray for the
/// point where the ray leaves the solid.
///
/// Made only for a frame that draws closed glass: its two targets are allocated on first use
/// at the frame's size and freed by release() when a frame has none.
class GlassExits {
  public:
    explicit GlassExits(const ShaderLibrary& shaders);

    /// Draws the back faces of the closed glass in `draws`; returns false (and draws nothing)
    /// when there is none.
    bool render(const DrawList& draws, const FrameCamera& camera, int width, int height);
    /// Frees the targets.
    void release();

    [[nodiscard]] GLuint position_texture() const { return position_.id(); }
    [[nodiscard]] GLuint normal_texture() const { return normal_.id(); }

    /// Whether `primitive` is closed glass, whose exit this pass finds.
    [[nodiscard]] static bool traced(const DrawPrimitive& primitive);

  private:
    void allocate(int width, int height);

    gl::Program program_;
    gl::Texture position_;  ///< RGBA32F: xyz world position, w = 1 where covered
    gl::Texture normal_;    ///< RGBA16F: xyz outward normal
    gl::Renderbuffer depth_;
    gl::Framebuffer framebuffer_;
    int width_ = 0;
    int height_ = 0;
};

}  // namespace luxel::renderer
