// A GLFW window under Xvfb: opens, clears, swaps, and what the X server shows matches.
// Run through xvfb-run (see tests/runtime/CMakeLists.txt).

#include <cstdlib>
#include <memory>

#include <gtest/gtest.h>

#include "luxel/runtime/gl_context.hpp"
#include "luxel/runtime/render_target.hpp"
#include "x11_screenshot.hpp"

namespace {

TEST(WindowContext, OpensClearsSwapsAndTheScreenShowsIt) {
    ASSERT_NE(std::getenv("DISPLAY"), nullptr) << "run this suite under xvfb-run";
    luxel::GlContextOptions options;
    options.backend = luxel::GlBackend::Window;
    options.width = 96;
    options.height = 64;
    options.window_title = "luxel window test";
    auto context = luxel::create_gl_context(options);
    ASSERT_TRUE(context->has_window());
    ASSERT_NE(context->native_window(), nullptr);
    const int width = context->framebuffer_width();
    const int height = context->framebuffer_height();
    ASSERT_EQ(width, 96);
    ASSERT_EQ(height, 64);

    // Left half orange, right half teal, via scissored clears of the default framebuffer.
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, width, height);
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 0, width / 2, height);
    glClearColor(1.0f, 0.5f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glScissor(width / 2, 0, width - width / 2, height);
    glClearColor(0.0f, 0.5f, 0.5f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
    // The default framebuffer's back buffer holds the clears before the swap...
    const luxel::Image back = luxel::gl::read_pixels(0, GL_BACK, width, height);
    EXPECT_NEAR(back.pixel(10, 10).r, 1.0f, 1.0f / 255.0f);
    EXPECT_NEAR(back.pixel(10, 10).g, 0.5f, 1.0f / 255.0f);
    EXPECT_NEAR(back.pixel(80, 50).b, 0.5f, 1.0f / 255.0f);

    context->swap_buffers();
    glFinish();
    context->poll_events();
    EXPECT_FALSE(context->should_close());

    // ...and what the X server holds for the window.
    const luxel::testing::X11Screenshot shot(context->native_window(), width, height);
    ASSERT_TRUE(shot.valid());
    constexpr double tolerance = 1.5 / 255.0;
    const glm::dvec3 left = shot.rgb(10, 10);
    const glm::dvec3 right = shot.rgb(80, 50);
    EXPECT_NEAR(left.r, 1.0, tolerance);
    EXPECT_NEAR(left.g, 0.5, tolerance);
    EXPECT_NEAR(left.b, 0.0, tolerance);
    EXPECT_NEAR(right.r, 0.0, tolerance);
    EXPECT_NEAR(right.g, 0.5, tolerance);
    EXPECT_NEAR(right.b, 0.5, tolerance);
}

TEST(WindowContext, AutoPrefersAWindowWhenADisplayExists) {
    ASSERT_NE(std::getenv("DISPLAY"), nullptr) << "run this suite under xvfb-run";
    luxel::GlContextOptions options;
    options.backend = luxel::GlBackend::Auto;
    options.window_visible = false;
    auto context = luxel::create_gl_context(options);
    EXPECT_EQ(context->backend(), luxel::GlBackend::Window);
}

}  // namespace
