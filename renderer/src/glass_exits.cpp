#include "glass_exits.hpp"

#include <array>

#include "luxel/runtime/shader_library.hpp"
#include "luxel/runtime/texture_sampling.hpp"

namespace luxel::renderer {

GlassExits::GlassExits(const ShaderLibrary& shaders)
    : program_(shaders.build({{ShaderStage::Vertex, "render/mesh.vert"},
                              {ShaderStage::Fragment, "render/glass_exit.frag"}})) {}

bool GlassExits::traced(const DrawPrimitive& primitive) {
    // transmittance.a counts the surfaces a view ray crosses: 2 for a closed solid.
    return primitive.range->index_count > 0 && primitive.material.specular.a > 0.0f &&
           primitive.material.transmittance.a >= 2.0f;
}

void GlassExits::allocate(int width, int height) {
    if (width == width_ && height == height_ && framebuffer_.id() != 0) {
        return;
    }
    position_ = gl::Texture::create_2d(GL_RGBA32F, width, height);
    gl::set_sampling(position_.id(), gl::Sampling::Exact);
    normal_ = gl::Texture::create_2d(GL_RGBA16F, width, height);
    gl::set_sampling(normal_.id(), gl::Sampling::Exact);
    depth_ = gl::Renderbuffer::create(GL_DEPTH_COMPONENT32F, width, height);
    framebuffer_ = gl::Framebuffer::create();
    framebuffer_.attach(GL_COLOR_ATTACHMENT0, position_);
    framebuffer_.attach(GL_COLOR_ATTACHMENT1, normal_);
    framebuffer_.attach(GL_DEPTH_ATTACHMENT, depth_);
    const std::array<GLenum, 2> buffers = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(framebuffer_.id(), 2, buffers.data());
    framebuffer_.check_complete("glass exit target");
    width_ = width;
    height_ = height;
}

void GlassExits::release() {
    framebuffer_ = {};
    depth_ = {};
    position_ = {};
    normal_ = {};
    width_ = 0;
    height_ = 0;
}

bool GlassExits::render(const DrawList& draws, const FrameCamera& camera, int width, int height) {
    bool any = false;
    for (const DrawPrimitive& primitive : draws.primitives) {
        any = any || traced(primitive);
    }
    if (!any) {
        release();
        return false;
    }
    allocate(width, height);
    const GLuint fbo = framebuffer_.id();
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    glViewport(0, 0, width, height);
    const std::array<float, 4> zero = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearNamedFramebufferfv(fbo, GL_COLOR, 0, zero.data());
    glClearNamedFramebufferfv(fbo, GL_COLOR, 1, zero.data());
    const float far = 1.0f;
    glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &far);
    // Not against the G-buffer's depth: the far side counts wherever something stands in
    // front of it.
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_FRONT);
    program_.use();
    program_.set("u_view_projection", camera.projection * camera.view);
    program_.set("u_camera", camera.position);
    for (const DrawItem& item : draws.items) {
        bool bound = false;
        for (std::size_t i = item.first; i < item.first + item.count; ++i) {
            const DrawPrimitive& primitive = draws.primitives[i];
            if (!traced(primitive)) {
                continue;
            }
            if (!bound) {
                bind_draw_item(program_, item);
                // glTF's front faces wind counter-clockwise; a mirroring transform turns them.
                glFrontFace(item.mirrored ? GL_CW : GL_CCW);
                bound = true;
            }
            draw_primitive(*primitive.range);
        }
    }
    glCullFace(GL_BACK);
    glDisable(GL_CULL_FACE);
    glDisable(GL_DEPTH_TEST);
    gl::check_error("GlassExits");
    return true;
}

}  // namespace luxel::renderer
