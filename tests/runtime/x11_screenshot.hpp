#pragma once

#include <glm/glm.hpp>

struct GLFWwindow;

namespace luxel::testing {

/// The window's pixels as the X server holds them (what a user sees), as linear-in-code values
/// in [0,1]: no sRGB decoding. Kept in its own file because Xlib's macros (None, Bool, Status)
/// collide with GoogleTest's names.
class X11Screenshot {
  public:
    X11Screenshot(GLFWwindow* window, int width, int height);
    ~X11Screenshot();
    X11Screenshot(const X11Screenshot&) = delete;
    X11Screenshot& operator=(const X11Screenshot&) = delete;

    [[nodiscard]] bool valid() const { return image_ != nullptr; }
    [[nodiscard]] glm::dvec3 rgb(int x, int y) const;

  private:
    void* image_ = nullptr;  // XImage*
};

}  // namespace luxel::testing
