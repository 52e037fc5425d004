#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "luxel/runtime/error.hpp"

struct GLFWwindow;

namespace luxel {

/// Which implementation provides the OpenGL 4.5 core context.
enum class GlBackend {
    Auto,    ///< window if DISPLAY/WAYLAND_DISPLAY is set, else EGL, else OSMesa
    Egl,     ///< headless EGL: device platform on a GPU driver, surfaceless platform on Mesa
    OsMesa,  ///< Mesa's off-screen software renderer, the fallback when EGL is unavailable
    Window,  ///< a GLFW window on the desktop
};

[[nodiscard]] std::string_view backend_name(GlBackend backend);
/// Parses auto|egl|osmesa|window; throws luxel::Error listing the valid values otherwise.
[[nodiscard]] GlBackend parse_backend(std::string_view name);

struct GlContextOptions {
    GlBackend backend = GlBackend::Auto;
    int width = 640;   ///< window size; headless contexts render into framebuffer objects
    int height = 360;  ///< of any size, and use this only for their (tiny) default surface
    std::string window_title = "luxel";
    bool window_visible = true;
    /// A debug context with GL messages routed to the log. Defaults on in Debug builds and when
    /// LUXEL_GL_DEBUG=1.
    bool debug = default_debug();

    [[nodiscard]] static bool default_debug();
};

/// What the driver says it is.
struct GlInfo {
    std::string vendor;
    std::string renderer;
    std::string version;
    std::string shading_language;
};

/// Raised when no backend could provide a context. what() lists every attempt and its reason.
class GlContextError : public Error {
  public:
    using Error::Error;
};

/// An OpenGL 4.5 core context, current on the creating thread. Destroy every GL object (see
/// gl_objects.hpp) before the context that made it.
class GlContext {
  public:
    virtual ~GlContext() = default;
    GlContext(const GlContext&) = delete;
    GlContext& operator=(const GlContext&) = delete;

    [[nodiscard]] virtual GlBackend backend() const = 0;
    /// Makes this context current on the calling thread and (re)binds the GL function pointers.
    virtual void make_current() = 0;

    /// Only windows have something to present; the headless backends do nothing here.
    [[nodiscard]] virtual bool has_window() const { return false; }
    virtual void swap_buffers() {}
    virtual void poll_events() {}
    [[nodiscard]] virtual bool should_close() const { return false; }
    /// The window's framebuffer size, or the requested size for headless contexts.
    [[nodiscard]] virtual int framebuffer_width() const = 0;
    [[nodiscard]] virtual int framebuffer_height() const = 0;
    /// The GLFW window behind a Window context (nullptr otherwise), for input handling.
    [[nodiscard]] virtual GLFWwindow* native_window() const { return nullptr; }

    [[nodiscard]] const GlInfo& info() const { return info_; }
    /// How the backend was chosen: for Auto, the attempts that failed before this one.
    [[nodiscard]] const std::vector<std::string>& selection_notes() const { return notes_; }

  protected:
    GlContext() = default;
    /// Called by backends once current: queries GlInfo and enables debug output if asked.
    void finish_initialisation(bool debug);

  private:
    friend std::unique_ptr<GlContext> create_gl_context(const GlContextOptions&);
    GlInfo info_;
    std::vector<std::string> notes_;
};

/// Creates a context with the requested backend (or the first that works, for Auto).
/// Throws GlContextError listing what was tried and why each attempt failed.
[[nodiscard]] std::unique_ptr<GlContext> create_gl_context(const GlContextOptions& options);

}  // namespace luxel
