#include "luxel/runtime/gl_debug.hpp"

#include <string>

#include "luxel/runtime/error.hpp"
#include "luxel/runtime/gl.hpp"
#include "luxel/runtime/log.hpp"

namespace luxel::gl {

std::string error_name(GLenum code) {
    switch (code) {
        case GL_NO_ERROR:
            return "GL_NO_ERROR";
        case GL_INVALID_ENUM:
            return "GL_INVALID_ENUM";
        case GL_INVALID_VALUE:
            return "GL_INVALID_VALUE";
        case GL_INVALID_OPERATION:
            return "GL_INVALID_OPERATION";
        case GL_INVALID_FRAMEBUFFER_OPERATION:
            return "GL_INVALID_FRAMEBUFFER_OPERATION";
        case GL_OUT_OF_MEMORY:
            return "GL_OUT_OF_MEMORY";
        case GL_STACK_UNDERFLOW:
            return "GL_STACK_UNDERFLOW";
        case GL_STACK_OVERFLOW:
            return "GL_STACK_OVERFLOW";
        default:
            return "GL error " + std::to_string(code);
    }
}

void check_error(const char* what) {
    std::string errors;
    // glGetError can queue several flags; a bounded loop also survives a lost context, which
    // keeps returning GL_CONTEXT_LOST.
    for (int i = 0; i < 16; ++i) {
        const GLenum code = glGetError();
        if (code == GL_NO_ERROR) {
            break;
        }
        errors += errors.empty() ? "" : ", ";
        errors += error_name(code);
    }
    if (!errors.empty()) {
        throw Error(std::string(what) + ": " + errors);
    }
}

namespace {

void GLAD_API_PTR route_to_log(GLenum source, GLenum type, GLuint id, GLenum severity,
                               GLsizei length, const GLchar* text, const void* /*user*/) {
    (void)source;
    (void)type;
    const std::string message(
        text, length > 0 ? static_cast<std::size_t>(length) : std::char_traits<char>::length(text));
    switch (severity) {
        case GL_DEBUG_SEVERITY_HIGH:
            log::error("GL[", id, "] ", message);
            break;
        case GL_DEBUG_SEVERITY_MEDIUM:
            log::warn("GL[", id, "] ", message);
            break;
        case GL_DEBUG_SEVERITY_LOW:
            log::debug("GL[", id, "] ", message);
            break;
        default:
            log::trace("GL[", id, "] ", message);
            break;
    }
}

}  // namespace

bool enable_debug_output() {
    GLint flags = 0;
    glGetIntegerv(GL_CONTEXT_FLAGS, &flags);
    if ((flags & GL_CONTEXT_FLAG_DEBUG_BIT) == 0 || glDebugMessageCallback == nullptr) {
        return false;
    }
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);  // messages arrive on the call that caused them
    glDebugMessageCallback(route_to_log, nullptr);
    glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
    return true;
}

}  // namespace luxel::gl
