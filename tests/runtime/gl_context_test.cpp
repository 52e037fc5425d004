// EGL and OSMesa each draw a known lit triangle into an FBO; the read-back matches the
// radiometry computed here. Both run on llvmpipe in CI.

#include <cmath>
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "luxel/runtime/gl_context.hpp"
#include "luxel/runtime/gl_objects.hpp"
#include "luxel/runtime/render_target.hpp"
#include "luxel/runtime/shader_library.hpp"

namespace {

using luxel::GlBackend;

struct Vertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec3 albedo;
};

class HeadlessContextTest : public ::testing::TestWithParam<GlBackend> {};

TEST_P(HeadlessContextTest, RendersKnownLitTriangle) {
    luxel::GlContextOptions options;
    options.backend = GetParam();
    options.width = 64;
    options.height = 64;
    auto context = luxel::create_gl_context(options);
    ASSERT_EQ(context->backend(), GetParam());
    EXPECT_FALSE(context->info().renderer.empty());
    EXPECT_NE(context->info().version.find("4.5"), std::string::npos) << context->info().version;

    const luxel::ShaderLibrary shaders;
    const auto program = shaders.build({{luxel::ShaderStage::Vertex, "test_scene/lit.vert"},
                                        {luxel::ShaderStage::Fragment, "test_scene/lit.frag"}});

    // A triangle in the z = 0 plane facing +z, covering the centre of clip space.
    const glm::vec3 albedo(0.8f, 0.5f, 0.2f);
    const glm::vec3 normal(0.0f, 0.0f, 1.0f);
    const Vertex vertices[] = {{{-0.8f, -0.8f, 0.0f}, normal, albedo},
                               {{0.8f, -0.8f, 0.0f}, normal, albedo},
                               {{0.0f, 0.8f, 0.0f}, normal, albedo}};
    auto buffer = luxel::gl::Buffer::create(sizeof vertices, vertices, 0);
    auto vao = luxel::gl::VertexArray::create();
    glVertexArrayVertexBuffer(vao.id(), 0, buffer.id(), 0, sizeof(Vertex));
    for (GLuint a = 0; a < 3; ++a) {
        glEnableVertexArrayAttrib(vao.id(), a);
        glVertexArrayAttribFormat(vao.id(), a, 3, GL_FLOAT, GL_FALSE,
                                  static_cast<GLuint>(a * sizeof(glm::vec3)));
        glVertexArrayAttribBinding(vao.id(), a, 0);
    }

    // A directional light at 53.13 degrees from the normal (cos = 0.6) with irradiance pi W/m^2
    // on a surface facing it, and no ambient: L = albedo / pi * pi * 0.6 = 0.6 * albedo.
    const glm::vec3 to_light = glm::normalize(glm::vec3(0.8f, 0.0f, 0.6f));
    program.set("u_view_projection", glm::mat4(1.0f));
    program.set("u_light", glm::vec4(to_light, 0.0f));
    program.set("u_light_intensity", glm::vec3(glm::pi<float>()));
    program.set("u_ambient_irradiance", glm::vec3(0.0f));

    const luxel::gl::RenderTarget target(64, 64);
    target.bind();
    const float clear[] = {0.1f, 0.2f, 0.3f, 1.0f};
    glClearNamedFramebufferfv(target.framebuffer().id(), GL_COLOR, 0, clear);
    program.use();
    glBindVertexArray(vao.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    luxel::gl::check_error("draw lit triangle");

    const luxel::Image image = target.read_color();
    const glm::vec3 expected = albedo * 0.6f;
    const glm::vec4 centre = image.pixel(32, 32);
    constexpr float tolerance = 1.0f / 255.0f;
    EXPECT_NEAR(centre.r, expected.r, tolerance);
    EXPECT_NEAR(centre.g, expected.g, tolerance);
    EXPECT_NEAR(centre.b, expected.b, tolerance);
    EXPECT_NEAR(centre.a, 1.0f, tolerance);
    // A corner outside the triangle keeps the clear colour.
    const glm::vec4 corner = image.pixel(1, 1);
    EXPECT_NEAR(corner.r, 0.1f, tolerance);
    EXPECT_NEAR(corner.g, 0.2f, tolerance);
    EXPECT_NEAR(corner.b, 0.3f, tolerance);
}

TEST_P(HeadlessContextTest, GlObjectsAreFreedWhenTheirOwnerDies) {
    luxel::GlContextOptions options;
    options.backend = GetParam();
    auto context = luxel::create_gl_context(options);
    GLuint id = 0;
    {
        auto buffer = luxel::gl::Buffer::create(256);
        id = buffer.id();
        ASSERT_TRUE(glIsBuffer(id));
        auto moved = std::move(buffer);
        EXPECT_EQ(buffer.id(),
                  0u);  // NOLINT(bugprone-use-after-move): checking the moved-from state
        EXPECT_EQ(moved.id(), id);
        EXPECT_TRUE(glIsBuffer(id));
        EXPECT_THROW(moved.update(200, 100, nullptr), luxel::Error);
    }
    EXPECT_FALSE(glIsBuffer(id));
}

INSTANTIATE_TEST_SUITE_P(Backends, HeadlessContextTest,
                         ::testing::Values(GlBackend::Egl, GlBackend::OsMesa),
                         [](const auto& test) {
                             return std::string(luxel::backend_name(test.param));
                         });

TEST(GlContextSelection, ParsesBackendNamesAndRejectsUnknownOnes) {
    EXPECT_EQ(luxel::parse_backend("egl"), GlBackend::Egl);
    EXPECT_EQ(luxel::parse_backend("osmesa"), GlBackend::OsMesa);
    EXPECT_EQ(luxel::parse_backend("window"), GlBackend::Window);
    EXPECT_EQ(luxel::parse_backend("auto"), GlBackend::Auto);
    try {
        (void)luxel::parse_backend("vulkan");
        FAIL() << "expected an error";
    } catch (const luxel::Error& e) {
        EXPECT_NE(std::string(e.what()).find("vulkan"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("osmesa"), std::string::npos);
    }
}

TEST(GlContextSelection, AutoWithoutDisplayChoosesHeadless) {
    ::unsetenv("DISPLAY");
    ::unsetenv("WAYLAND_DISPLAY");
    luxel::GlContextOptions options;
    options.backend = GlBackend::Auto;
    auto context = luxel::create_gl_context(options);
    EXPECT_NE(context->backend(), GlBackend::Window);
    EXPECT_FALSE(context->has_window());
}

TEST(GlContextSelection, WindowWithoutDisplayExplainsWhy) {
    ::unsetenv("DISPLAY");
    ::unsetenv("WAYLAND_DISPLAY");
    luxel::GlContextOptions options;
    options.backend = GlBackend::Window;
    try {
        (void)luxel::create_gl_context(options);
        FAIL() << "a window cannot exist without a display";
    } catch (const luxel::GlContextError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("tried"), std::string::npos) << message;
        EXPECT_NE(message.find("window:"), std::string::npos) << message;
        EXPECT_NE(message.find("DISPLAY"), std::string::npos) << message;
    }
}

}  // namespace
