#pragma once

// Internal to runtime: the backends behind create_gl_context. Each backend lives in its own
// translation unit so that platform headers (EGL, OSMesa's GL/gl.h, GLFW) never meet glad's.

#include <memory>
#include <string>

#include "luxel/runtime/gl_context.hpp"

namespace luxel::detail {

using GlProc = void (*)();
using GlProcLoader = GlProc (*)(const char*);

/// Loads the GL 4.5 core entry points through `loader` for the current context. Returns an
/// empty string on success, otherwise why it failed (for example the context's GL version).
[[nodiscard]] std::string load_gl_functions(GlProcLoader loader);

/// Each throws GlContextError with the reason (one line) when it cannot make a context.
[[nodiscard]] std::unique_ptr<GlContext> create_egl_context(const GlContextOptions& options);
[[nodiscard]] std::unique_ptr<GlContext> create_osmesa_context(const GlContextOptions& options);
[[nodiscard]] std::unique_ptr<GlContext> create_window_context(const GlContextOptions& options);

}  // namespace luxel::detail
