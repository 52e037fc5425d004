#include "x11_screenshot.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#define GLFW_EXPOSE_NATIVE_X11
#include <GLFW/glfw3native.h>
#include <X11/Xlib.h>
#include <X11/Xutil.h>

namespace luxel::testing {
namespace {

double channel(unsigned long pixel, unsigned long mask) {
    unsigned long value = pixel & mask;
    while (mask != 0 && (mask & 1ul) == 0) {
        mask >>= 1;
        value >>= 1;
    }
    return mask == 0 ? 0.0 : static_cast<double>(value) / static_cast<double>(mask);
}

}  // namespace

X11Screenshot::X11Screenshot(GLFWwindow* window, int width, int height) {
    Display* display = glfwGetX11Display();
    XSync(display, False);  // the swap's drawing requests reach the server first
    image_ = XGetImage(display, glfwGetX11Window(window), 0, 0, static_cast<unsigned>(width),
                       static_cast<unsigned>(height), AllPlanes, ZPixmap);
}

X11Screenshot::~X11Screenshot() {
    if (image_ != nullptr) {
        XDestroyImage(static_cast<XImage*>(image_));
    }
}

glm::dvec3 X11Screenshot::rgb(int x, int y) const {
    auto* image = static_cast<XImage*>(image_);
    const unsigned long pixel = XGetPixel(image, x, y);
    return {channel(pixel, image->red_mask), channel(pixel, image->green_mask),
            channel(pixel, image->blue_mask)};
}

}  // namespace luxel::testing
