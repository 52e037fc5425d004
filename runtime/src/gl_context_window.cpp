// A desktop window through GLFW, for the interactive sandbox and the window tests (Xvfb).

#define GLFW_INCLUDE_NONE  // GL comes from glad, not from GLFW's choice of header
#include <GLFW/glfw3.h>

#include <mutex>
#include <string>

#include "gl_backends.hpp"

namespace luxel::detail {
namespace {

// GLFW is process-global: initialised with the first window and terminated with the last.
std::mutex& glfw_mutex() {
    static std::mutex mutex;
    return mutex;
}
int glfw_users = 0;
std::string last_glfw_error;

void record_glfw_error(int code, const char* description) {
    last_glfw_error = std::string(description != nullptr ? description : "unknown") + " (" +
                      std::to_string(code) + ")";
}

void acquire_glfw() {
    const std::lock_guard lock(glfw_mutex());
    if (glfw_users == 0) {
        glfwSetErrorCallback(record_glfw_error);
        last_glfw_error.clear();
        if (glfwInit() != GLFW_TRUE) {
            throw GlContextError("GLFW could not initialise: " + (last_glfw_error.empty()
                                                                      ? std::string("no display?")
                                                                      : last_glfw_error));
        }
    }
    ++glfw_users;
}

void release_glfw() {
    const std::lock_guard lock(glfw_mutex());
    if (--glfw_users == 0) {
        glfwTerminate();
    }
}

class WindowContext final : public GlContext {
  public:
    explicit WindowContext(GLFWwindow* window) : window_(window) {}
    ~WindowContext() override {
        glfwDestroyWindow(window_);
        release_glfw();
    }

    GlBackend backend() const override { return GlBackend::Window; }
    void make_current() override {
        glfwMakeContextCurrent(window_);
        (void)load_gl_functions(reinterpret_cast<GlProcLoader>(&glfwGetProcAddress));
    }
    bool has_window() const override { return true; }
    void swap_buffers() override { glfwSwapBuffers(window_); }
    void poll_events() override { glfwPollEvents(); }
    bool should_close() const override { return glfwWindowShouldClose(window_) == GLFW_TRUE; }
    int framebuffer_width() const override {
        int width = 0;
        int height = 0;
        glfwGetFramebufferSize(window_, &width, &height);
        return width;
    }
    int framebuffer_height() const override {
        int width = 0;
        int height = 0;
        glfwGetFramebufferSize(window_, &width, &height);
        return height;
    }
    GLFWwindow* native_window() const override { return window_; }
    void initialise(bool debug) { finish_initialisation(debug); }

  private:
    GLFWwindow* window_;
};

}  // namespace

std::unique_ptr<GlContext> create_window_context(const GlContextOptions& options) {
    acquire_glfw();
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, options.debug ? GLFW_TRUE : GLFW_FALSE);
    glfwWindowHint(GLFW_VISIBLE, options.window_visible ? GLFW_TRUE : GLFW_FALSE);
    glfwWindowHint(GLFW_DEPTH_BITS, 24);
    last_glfw_error.clear();
    GLFWwindow* window = glfwCreateWindow(options.width, options.height,
                                          options.window_title.c_str(), nullptr, nullptr);
    if (window == nullptr) {
        const std::string reason = "no window with an OpenGL 4.5 core context: " +
                                   (last_glfw_error.empty() ? "unknown" : last_glfw_error);
        release_glfw();
        throw GlContextError(reason);
    }
    auto context = std::make_unique<WindowContext>(window);
    glfwMakeContextCurrent(window);
    const std::string load_error =
        load_gl_functions(reinterpret_cast<GlProcLoader>(&glfwGetProcAddress));
    if (!load_error.empty()) {
        throw GlContextError(load_error);
    }
    glfwSwapInterval(0);  // the engine paces frames itself; vsync would distort measurements
    context->initialise(options.debug);
    return context;
}

}  // namespace luxel::detail
