// Mesa's off-screen renderer: a GL 4.5 core context (gallium llvmpipe) that draws into a buffer
// we own, with no display and no EGL. It is the fallback when EGL cannot give a context.
// This file includes OSMesa's GL/gl.h, so it must not include glad (see gl_backends.hpp).

#include <GL/osmesa.h>

#include <cstdint>
#include <vector>

#include "gl_backends.hpp"

namespace luxel::detail {
namespace {

class OsMesaContext final : public GlContext {
  public:
    OsMesaContext(OSMesaContext context, int width, int height)
        : context_(context),
          width_(width),
          height_(height),
          // OSMesa needs colour memory for its default framebuffer; luxel renders into FBOs,
          // so this only has to exist.
          buffer_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4) {}

    ~OsMesaContext() override { OSMesaDestroyContext(context_); }

    GlBackend backend() const override { return GlBackend::OsMesa; }
    void make_current() override {
        bind();
        (void)load_gl_functions(reinterpret_cast<GlProcLoader>(&OSMesaGetProcAddress));
    }
    int framebuffer_width() const override { return width_; }
    int framebuffer_height() const override { return height_; }

    bool bind() {
        return OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, width_, height_) ==
               GL_TRUE;
    }
    void initialise(bool debug) { finish_initialisation(debug); }

  private:
    OSMesaContext context_;
    int width_;
    int height_;
    std::vector<std::uint8_t> buffer_;
};

}  // namespace

std::unique_ptr<GlContext> create_osmesa_context(const GlContextOptions& options) {
    const int attributes[] = {OSMESA_FORMAT,
                              OSMESA_RGBA,
                              OSMESA_DEPTH_BITS,
                              24,
                              OSMESA_PROFILE,
                              OSMESA_CORE_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION,
                              4,
                              OSMESA_CONTEXT_MINOR_VERSION,
                              5,
                              0};
    OSMesaContext raw = OSMesaCreateContextAttribs(attributes, nullptr);
    if (raw == nullptr) {
        throw GlContextError("OSMesaCreateContextAttribs refused an OpenGL 4.5 core context");
    }
    const int width = options.width > 0 ? options.width : 1;
    const int height = options.height > 0 ? options.height : 1;
    auto context = std::make_unique<OsMesaContext>(raw, width, height);
    if (!context->bind()) {
        throw GlContextError("OSMesaMakeCurrent failed");
    }
    // OSMesaGetProcAddress's OSMESAproc is void(*)(), the same shape as GlProc.
    const std::string load_error =
        load_gl_functions(reinterpret_cast<GlProcLoader>(&OSMesaGetProcAddress));
    if (!load_error.empty()) {
        throw GlContextError(load_error);
    }
    context->initialise(options.debug);
    return context;
}

}  // namespace luxel::detail
