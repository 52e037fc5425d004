#include "frame_targets.hpp"

#include <array>

#include "luxel/runtime/texture_sampling.hpp"

namespace luxel::renderer {
namespace {

gl::Texture target_texture(GLenum format, int width, int height) {
    gl::Texture texture = gl::Texture::create_2d(format, width, height);
    // Every pass reads these with texelFetch, one texel per pixel.
    gl::set_sampling(texture.id(), gl::Sampling::Exact);
    return texture;
}

gl::Framebuffer single_target(const gl::Texture& texture, const char* what) {
    gl::Framebuffer framebuffer = gl::Framebuffer::create();
    framebuffer.attach(GL_COLOR_ATTACHMENT0, texture);
    glNamedFramebufferDrawBuffer(framebuffer.id(), GL_COLOR_ATTACHMENT0);
    framebuffer.check_complete(what);
    return framebuffer;
}

}  // namespace

FrameTargets::FrameTargets(int w, int h, bool anti_aliasing) : width(w), height(h) {
    albedo = target_texture(GL_RGBA16F, w, h);
    normal = target_texture(GL_RGBA16F, w, h);
    position = target_texture(GL_RGBA32F, w, h);
    lightmap = target_texture(GL_RGBA32F, w, h);
    // Radiance scales with the light's power: 32-bit, because half floats stop at 65,504 and
    // lose everything below 6e-8 (docs/STABILITY.md, extreme powers). Albedo, normal and F0
    // are bounded material values and keep 16 bits.
    emission = target_texture(GL_RGBA32F, w, h);
    specular = target_texture(GL_RGBA16F, w, h);
    depth = target_texture(GL_DEPTH32F_STENCIL8, w, h);
    gbuffer = gl::Framebuffer::create();
    const std::array<const gl::Texture*, 6> colours = {&albedo,   &normal,   &position,
                                                       &lightmap, &emission, &specular};
    std::array<GLenum, 6> buffers{};
    for (std::size_t i = 0; i < colours.size(); ++i) {
        buffers[i] = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i);
        gbuffer.attach(buffers[i], *colours[i]);
    }
    gbuffer.attach(GL_DEPTH_STENCIL_ATTACHMENT, depth);
    glNamedFramebufferDrawBuffers(gbuffer.id(), static_cast<GLsizei>(buffers.size()),
                                  buffers.data());
    gbuffer.check_complete("G-buffer");

    direct = target_texture(GL_RGBA32F, w, h);
    direct_target = single_target(direct, "direct target");
    indirect = target_texture(GL_RGBA32F, w, h);
    indirect_target = single_target(indirect, "indirect target");
    specular_term = target_texture(GL_RGBA32F, w, h);
    specular_target = single_target(specular_term, "specular target");
    // The specular term redraws specular objects over the G-buffer's depth.
    specular_target.attach(GL_DEPTH_STENCIL_ATTACHMENT, depth);
    specular_target.check_complete("specular target");
    // The indirect pass reads the G-buffer's stencil of receivers without a light map.
    indirect_target.attach(GL_DEPTH_STENCIL_ATTACHMENT, depth);
    indirect_target.check_complete("indirect target");
    frame = target_texture(GL_RGBA32F, w, h);
    frame_target = single_target(frame, "frame target");
    if (anti_aliasing) {
        composed = target_texture(GL_RGBA32F, w, h);
        gl::set_sampling(composed.id(), gl::Sampling::Filtered);
        composed_target = single_target(composed, "composed target");
        ensure_stencil();
    }
    gl::check_error("FrameTargets");
}

void FrameTargets::ensure_stencil() {
    if (stencil.id() != 0) {
        return;
    }
    stencil = gl::Renderbuffer::create(GL_STENCIL_INDEX8, width, height);
    frame_target.attach(GL_STENCIL_ATTACHMENT, stencil);
    frame_target.check_complete("frame target with a stencil");
    if (composed_target.id() != 0) {
        composed_target.attach(GL_STENCIL_ATTACHMENT, stencil);
        composed_target.check_complete("composed target with a stencil");
    }
}

}  // namespace luxel::renderer
