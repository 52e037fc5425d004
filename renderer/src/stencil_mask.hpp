#pragma once

#include "luxel/runtime/gl.hpp"

namespace luxel::renderer {

/// Runs a costly full-screen pass only on the pixels a cheap one picks: `mark()` draws with
/// colour writes off and every fragment it does not discard sets `framebuffer`'s stencil to 1
/// (cleared to 0 first); `shade()` then draws under the test "stencil is 1". The edge filter and
/// the composite's mixing at sky silhouettes use it. A branch in the costly shader would not do
/// it: a software rasteriser such as llvmpipe runs both sides of a branch for its whole block of
/// pixels, while a block the stencil rejects whole is not shaded at all (docs/PERFORMANCE.md,
/// "Shader variants and masked passes"). The framebuffer needs a stencil attachment
/// (FrameTargets::ensure_stencil); the stencil test is off again afterwards.
template <class Mark, class Shade>
void shade_marked(GLuint framebuffer, Mark mark, Shade shade) {
    const GLint clear = 0;
    glStencilMask(0xFF);
    glClearNamedFramebufferiv(framebuffer, GL_STENCIL, 0, &clear);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, 1, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    mark();
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glStencilFunc(GL_EQUAL, 1, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    shade();
    glDisable(GL_STENCIL_TEST);
}

}  // namespace luxel::renderer
