#pragma once

#include <glm/glm.hpp>

#include "luxel/runtime/gl_objects.hpp"
#include "luxel/runtime/program.hpp"
#include "scene_draws.hpp"

namespace luxel {
class ShaderLibrary;
}

namespace luxel::renderer {

/// How much of each pixel shows the sky, for the silhouettes of geometry against it
/// (docs/METHOD.md §8.6). The frame samples each pixel at its centre; a reference averages the
/// pixel's area. Against a sky tens of times brighter than the walls (a window in daylight) the
/// one-pixel border of every opening then carries most of the frame's error, and the edge
/// filter cannot recover it where an edge runs along the pixel grid, since a single sample per
/// pixel does not say where inside the pixel the edge is. This pass draws every surface once
/// more, without shading, at kScale x kScale sub-samples a pixel into an 8-bit mask; the
/// composite mixes the sky into a surface pixel and the surfaces into a sky pixel by the
/// fraction the mask gives. It exists only while the frame has a sky.
class SkyCoverage {
  public:
    static constexpr int kScale = 4;

    explicit SkyCoverage(const ShaderLibrary& shaders);

    /// Draws `draws` as seen through `view_projection` into a (scale width) x (scale height)
    /// mask, allocated on first use and again when the size changes. The scale is kScale, or
    /// less where the GL's largest texture or framebuffer would not hold it (a frame wider than
    /// 4,096 pixels on a 16,384 limit); below 2 there is no mask and it returns false. The
    /// caller restores GL state (FrameRenderer's StateGuard).
    bool render(const DrawList& draws, const glm::mat4& view_projection, int width, int height);

    /// The mask: R8, 1 where a surface covers the sub-sample.
    [[nodiscard]] GLuint texture() const { return mask_.id(); }
    /// Sub-samples per pixel along each axis in the last mask.
    [[nodiscard]] int scale() const { return scale_; }

  private:
    gl::Program program_;
    gl::Texture mask_;
    gl::Framebuffer target_;
    int width_ = 0;
    int height_ = 0;
    int scale_ = kScale;
};

}  // namespace luxel::renderer
