#include "luxel/runtime/gl_context.hpp"

#include <cstdlib>
#include <string>

#include "driver_pinning.hpp"
#include "gl_backends.hpp"
#include "luxel/runtime/gl.hpp"
#include "luxel/runtime/gl_debug.hpp"
#include "luxel/runtime/log.hpp"

namespace luxel {

std::string_view backend_name(GlBackend backend) {
    switch (backend) {
        case GlBackend::Auto:
            return "auto";
        case GlBackend::Egl:
            return "egl";
        case GlBackend::OsMesa:
            return "osmesa";
        case GlBackend::Window:
            return "window";
    }
    return "?";
}

GlBackend parse_backend(std::string_view name) {
    for (GlBackend backend :
         {GlBackend::Auto, GlBackend::Egl, GlBackend::OsMesa, GlBackend::Window}) {
        if (name == backend_name(backend)) {
            return backend;
        }
    }
    throw Error("unknown GL backend '" + std::string(name) +
                "' (expected auto, egl, osmesa or window)");
}

bool GlContextOptions::default_debug() {
    if (const char* env = std::getenv("LUXEL_GL_DEBUG"); env != nullptr && *env != '\0') {
        return std::string_view(env) != "0";
    }
#ifdef LUXEL_GL_DEBUG_DEFAULT
    return true;
#else
    return false;
#endif
}

namespace {

std::string gl_string(GLenum name) {
    const auto* text = reinterpret_cast<const char*>(glGetString(name));
    return text != nullptr ? std::string(text) : std::string("(unknown)");
}

bool display_available() {
    const char* x11 = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    return (x11 != nullptr && *x11 != '\0') || (wayland != nullptr && *wayland != '\0');
}

std::unique_ptr<GlContext> create_backend(GlBackend backend, const GlContextOptions& options) {
    switch (backend) {
        case GlBackend::Egl:
            return detail::create_egl_context(options);
        case GlBackend::OsMesa:
            return detail::create_osmesa_context(options);
        case GlBackend::Window:
            return detail::create_window_context(options);
        case GlBackend::Auto:
            break;
    }
    throw GlContextError("internal: no backend for auto");
}

}  // namespace

void GlContext::finish_initialisation(bool debug) {
    info_.vendor = gl_string(GL_VENDOR);
    info_.renderer = gl_string(GL_RENDERER);
    info_.version = gl_string(GL_VERSION);
    info_.shading_language = gl_string(GL_SHADING_LANGUAGE_VERSION);
    if (debug && !gl::enable_debug_output()) {
        log::debug("GL debug output requested but the context is not a debug context");
    }
}

std::unique_ptr<GlContext> create_gl_context(const GlContextOptions& options) {
    std::vector<GlBackend> order;
    if (options.backend == GlBackend::Auto) {
        if (display_available()) {
            order.push_back(GlBackend::Window);
        }
        order.push_back(GlBackend::Egl);
        order.push_back(GlBackend::OsMesa);
    } else {
        order.push_back(options.backend);
    }

    std::vector<std::string> failures;
    for (GlBackend backend : order) {
        try {
            auto context = create_backend(backend, options);
            detail::pin_gl_driver_modules();
            context->notes_ = failures;
            for (const auto& note : failures) {
                log::info("GL backend skipped: ", note);
            }
            return context;
        } catch (const GlContextError& e) {
            failures.push_back(std::string(backend_name(backend)) + ": " + e.what());
        }
    }
    std::string message = "no OpenGL 4.5 core context could be created; tried:";
    for (const auto& failure : failures) {
        message += "\n  - " + failure;
    }
    throw GlContextError(message);
}

namespace detail {

std::string load_gl_functions(GlProcLoader loader) {
    const int version = gladLoadGL(loader);
    if (version == 0) {
        return "could not load OpenGL entry points";
    }
    const int major = GLAD_VERSION_MAJOR(version);
    const int minor = GLAD_VERSION_MINOR(version);
    if (major < 4 || (major == 4 && minor < 5)) {
        return "context provides OpenGL " + std::to_string(major) + "." + std::to_string(minor) +
               ", luxel needs 4.5 core";
    }
    return {};
}

}  // namespace detail
}  // namespace luxel
