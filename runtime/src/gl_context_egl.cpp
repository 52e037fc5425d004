// Headless OpenGL through EGL. On a machine with a GPU driver (NVIDIA) the device platform
// gives a context without any window system; on Mesa the surfaceless platform gives llvmpipe
// (or a GPU) without one. Mesa's software "device" is tried last so a real GPU always wins.

#define EGL_NO_X11  // keep Xlib's macros (None, Bool, Status) out of this translation unit
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>
#include <string>
#include <vector>

#include "gl_backends.hpp"
#include "luxel/runtime/log.hpp"

namespace luxel::detail {
namespace {

std::string egl_error_name(EGLint code) {
    switch (code) {
        case EGL_SUCCESS:
            return "EGL_SUCCESS";
        case EGL_NOT_INITIALIZED:
            return "EGL_NOT_INITIALIZED";
        case EGL_BAD_ACCESS:
            return "EGL_BAD_ACCESS";
        case EGL_BAD_ALLOC:
            return "EGL_BAD_ALLOC";
        case EGL_BAD_ATTRIBUTE:
            return "EGL_BAD_ATTRIBUTE";
        case EGL_BAD_CONFIG:
            return "EGL_BAD_CONFIG";
        case EGL_BAD_CONTEXT:
            return "EGL_BAD_CONTEXT";
        case EGL_BAD_DISPLAY:
            return "EGL_BAD_DISPLAY";
        case EGL_BAD_MATCH:
            return "EGL_BAD_MATCH";
        case EGL_BAD_PARAMETER:
            return "EGL_BAD_PARAMETER";
        case EGL_BAD_SURFACE:
            return "EGL_BAD_SURFACE";
        default:
            return "EGL error " + std::to_string(code);
    }
}

bool has_extension(const char* list, const char* name) {
    if (list == nullptr) {
        return false;
    }
    const std::size_t length = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += length) {
        const bool starts = p == list || p[-1] == ' ';
        const bool ends = p[length] == ' ' || p[length] == '\0';
        if (starts && ends) {
            return true;
        }
    }
    return false;
}

template <class Fn>
Fn egl_proc(const char* name) {
    return reinterpret_cast<Fn>(eglGetProcAddress(name));
}

/// A candidate display, with a name for messages.
struct DisplayCandidate {
    std::string name;
    EGLenum platform;
    void* native;
};

std::vector<DisplayCandidate> display_candidates(std::vector<std::string>& notes) {
    std::vector<DisplayCandidate> hardware;
    std::vector<DisplayCandidate> software;
    const char* client_extensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (client_extensions == nullptr) {
        notes.push_back("EGL client extensions unavailable (" + egl_error_name(eglGetError()) +
                        ")");
        return {};
    }

    if (has_extension(client_extensions, "EGL_EXT_platform_device")) {
        auto query_devices = egl_proc<PFNEGLQUERYDEVICESEXTPROC>("eglQueryDevicesEXT");
        auto query_string = egl_proc<PFNEGLQUERYDEVICESTRINGEXTPROC>("eglQueryDeviceStringEXT");
        EGLint count = 0;
        if (query_devices != nullptr && query_devices(0, nullptr, &count) == EGL_TRUE &&
            count > 0) {
            std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
            query_devices(count, devices.data(), &count);
            for (EGLint i = 0; i < count; ++i) {
                const char* extensions =
                    query_string != nullptr
                        ? query_string(devices[static_cast<std::size_t>(i)], EGL_EXTENSIONS)
                        : nullptr;
                const bool is_software = has_extension(extensions, "EGL_MESA_device_software");
                DisplayCandidate candidate{
                    (is_software ? "software device " : "device ") + std::to_string(i),
                    EGL_PLATFORM_DEVICE_EXT, devices[static_cast<std::size_t>(i)]};
                (is_software ? software : hardware).push_back(candidate);
            }
        }
    }
    std::vector<DisplayCandidate> order = hardware;
    if (has_extension(client_extensions, "EGL_MESA_platform_surfaceless")) {
        order.push_back(
            {"surfaceless platform", EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY});
    }
    order.insert(order.end(), software.begin(), software.end());
    if (order.empty()) {
        notes.push_back("EGL offers neither the device nor the surfaceless platform");
    }
    return order;
}

class EglContext final : public GlContext {
  public:
    EglContext(EGLDisplay display, EGLContext context, EGLSurface surface, int width, int height,
               std::string platform)
        : display_(display),
          context_(context),
          surface_(surface),
          width_(width),
          height_(height),
          platform_(std::move(platform)) {}

    ~EglContext() override {
        eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (surface_ != EGL_NO_SURFACE) {
            eglDestroySurface(display_, surface_);
        }
        eglDestroyContext(display_, context_);
        eglTerminate(display_);
        eglReleaseThread();
    }

    GlBackend backend() const override { return GlBackend::Egl; }
    void make_current() override {
        eglMakeCurrent(display_, surface_, surface_, context_);
        // glad's pointers are process-wide; another backend may have replaced them.
        (void)load_gl_functions(reinterpret_cast<GlProcLoader>(&eglGetProcAddress));
    }
    int framebuffer_width() const override { return width_; }
    int framebuffer_height() const override { return height_; }

    void initialise(bool debug) {
        finish_initialisation(debug);
        log::debug("EGL context on the ", platform_);
    }

  private:
    EGLDisplay display_;
    EGLContext context_;
    EGLSurface surface_;
    int width_;
    int height_;
    std::string platform_;
};

/// Tries one display; returns the context or throws GlContextError with the reason.
std::unique_ptr<GlContext> try_display(const DisplayCandidate& candidate,
                                       const GlContextOptions& options) {
    EGLDisplay display = eglGetPlatformDisplay(candidate.platform, candidate.native, nullptr);
    if (display == EGL_NO_DISPLAY) {
        throw GlContextError("no display (" + egl_error_name(eglGetError()) + ")");
    }
    EGLint major = 0;
    EGLint minor = 0;
    if (eglInitialize(display, &major, &minor) != EGL_TRUE) {
        throw GlContextError("eglInitialize failed (" + egl_error_name(eglGetError()) + ")");
    }
    // From here the display is initialised; terminate it on every failure path.
    struct TerminateOnFailure {
        EGLDisplay display;
        bool armed = true;
        ~TerminateOnFailure() {
            if (armed) {
                eglTerminate(display);
            }
        }
    } guard{display};

    if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) {
        throw GlContextError("desktop OpenGL not supported by this EGL display");
    }
    const char* extensions = eglQueryString(display, EGL_EXTENSIONS);
    const bool no_config = has_extension(extensions, "EGL_KHR_no_config_context");
    const bool surfaceless = has_extension(extensions, "EGL_KHR_surfaceless_context");

    EGLConfig config = nullptr;
    if (!no_config || !surfaceless) {
        const EGLint config_attributes[] = {EGL_SURFACE_TYPE,
                                            EGL_PBUFFER_BIT,
                                            EGL_RENDERABLE_TYPE,
                                            EGL_OPENGL_BIT,
                                            EGL_RED_SIZE,
                                            8,
                                            EGL_GREEN_SIZE,
                                            8,
                                            EGL_BLUE_SIZE,
                                            8,
                                            EGL_DEPTH_SIZE,
                                            24,
                                            EGL_NONE};
        EGLint count = 0;
        if (eglChooseConfig(display, config_attributes, &config, 1, &count) != EGL_TRUE ||
            count == 0) {
            throw GlContextError("no pbuffer-capable OpenGL config");
        }
    }
    const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                         4,
                                         EGL_CONTEXT_MINOR_VERSION,
                                         5,
                                         EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                         EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                         EGL_CONTEXT_OPENGL_DEBUG,
                                         options.debug ? EGL_TRUE : EGL_FALSE,
                                         EGL_NONE};
    EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attributes);
    if (context == EGL_NO_CONTEXT) {
        throw GlContextError("no OpenGL 4.5 core context (" + egl_error_name(eglGetError()) + ")");
    }
    EGLSurface surface = EGL_NO_SURFACE;
    if (!surfaceless) {
        // Without surfaceless contexts a context needs a drawable: a tiny pbuffer suffices,
        // since luxel draws into framebuffer objects.
        const EGLint pbuffer_attributes[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
        surface = eglCreatePbufferSurface(display, config, pbuffer_attributes);
        if (surface == EGL_NO_SURFACE) {
            eglDestroyContext(display, context);
            throw GlContextError("no pbuffer surface (" + egl_error_name(eglGetError()) + ")");
        }
    }
    if (eglMakeCurrent(display, surface, surface, context) != EGL_TRUE) {
        const std::string reason = egl_error_name(eglGetError());
        if (surface != EGL_NO_SURFACE) {
            eglDestroySurface(display, surface);
        }
        eglDestroyContext(display, context);
        throw GlContextError("eglMakeCurrent failed (" + reason + ")");
    }
    guard.armed = false;  // the context object owns the display now
    auto result = std::make_unique<EglContext>(display, context, surface, options.width,
                                               options.height, candidate.name);
    const std::string load_error =
        load_gl_functions(reinterpret_cast<GlProcLoader>(&eglGetProcAddress));
    if (!load_error.empty()) {
        throw GlContextError(load_error);
    }
    result->initialise(options.debug);
    return result;
}

}  // namespace

std::unique_ptr<GlContext> create_egl_context(const GlContextOptions& options) {
    std::vector<std::string> failures;
    for (const auto& candidate : display_candidates(failures)) {
        try {
            return try_display(candidate, options);
        } catch (const GlContextError& e) {
            failures.push_back(candidate.name + ": " + e.what());
        }
    }
    std::string reason;
    for (const auto& failure : failures) {
        reason += (reason.empty() ? "" : "; ") + failure;
    }
    throw GlContextError(reason.empty() ? "no EGL display found" : reason);
}

}  // namespace luxel::detail
