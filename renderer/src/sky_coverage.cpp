#include "sky_coverage.hpp"

#include <algorithm>
#include <array>

#include "fill_budget.hpp"
#include "luxel/runtime/gl_limits.hpp"
#include "luxel/runtime/shader_library.hpp"
#include "luxel/runtime/texture_sampling.hpp"

namespace luxel::renderer {

SkyCoverage::SkyCoverage(const ShaderLibrary& shaders)
    : program_(shaders.build({{ShaderStage::Vertex, "render/mesh.vert"},
                              {ShaderStage::Fragment, "render/coverage.frag"}})) {}

bool SkyCoverage::render(const DrawList& draws, const glm::mat4& view_projection, int width,
                         int height) {
    scale_ = std::min(kScale, gl::largest_render_target() / std::max({width, height, 1}));
    if (scale_ < 2) {
        return false;  // one sample a pixel would add nothing to the frame's own
    }
    const int w = width * scale_;
    const int h = height * scale_;
    if (!mask_ || w != width_ || h != height_) {
        mask_ = gl::Texture::create_2d(GL_R8, w, h);
        gl::set_sampling(mask_.id(), gl::Sampling::Exact);
        target_ = gl::Framebuffer::create();
        target_.attach(GL_COLOR_ATTACHMENT0, mask_);
        glNamedFramebufferDrawBuffer(target_.id(), GL_COLOR_ATTACHMENT0);
        target_.check_complete("sky coverage target");
        width_ = w;
        height_ = h;
    }
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, target_.id());
    glViewport(0, 0, w, h);
    const std::array<float, 4> sky = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearNamedFramebufferfv(target_.id(), GL_COLOR, 0, sky.data());
    // Every surface covers what it covers, whatever is in front: no depth test. Single-sided
    // primitives are culled as in the G-buffer, so the mask agrees with what the frame shows.
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    program_.use();
    program_.set("u_view_projection", view_projection);
    FillBudget budget(static_cast<double>(w) * static_cast<double>(h));
    draw_in_view(
        draws, view_projection, w, h, budget, [](const DrawItem&) { return true; },
        [&](const DrawItem& item) { bind_draw_item(program_, item); },
        [&](const DrawItem& item, const DrawPrimitive& primitive) {
            cull_as_material(item, primitive.material);
            draw_primitive(*primitive.range);
        });
    glDisable(GL_CULL_FACE);
    glFrontFace(GL_CCW);
    return true;
}

}  // namespace luxel::renderer
