#pragma once

// The one way luxel code reaches OpenGL: the GL 4.5 core loader generated at build time by glad.
// Function pointers are loaded by GlContext when it is created; include this, never <GL/gl.h>.
#include <glad/gl.h>

#include <string>

namespace luxel::gl {

/// Throws luxel::Error naming `what` if glGetError reports anything (drains all pending errors).
void check_error(const char* what);

/// Human-readable name of a GL error code (GL_INVALID_ENUM, ...).
[[nodiscard]] std::string error_name(GLenum code);

}  // namespace luxel::gl
