// What the FeaturePlan allows and the toggles select: a scene without lights allocates no
// shadow maps and runs no shadow or direct pass; a light brings one map, switching it off
// frees it; each term's toggle removes exactly that term; the linear frame reads back as EXR
// without loss.

#include <cmath>
#include <filesystem>
#include <memory>

#include <gtest/gtest.h>

#include "luxel/ecs/transform.hpp"
#include "luxel/renderer/frame_renderer.hpp"
#include "luxel/runtime/gl_objects.hpp"
#include "luxel/runtime/image.hpp"
#include "render_scenes.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;

constexpr int kSize = 64;

renderer::FrameCamera camera() {
    return renderer::FrameCamera::look_at({0.5f, 3.5f, 2.5f}, glm::vec3(0.0f), {0.0f, 1.0f, 0.0f},
                                          1.0f, 1.0f);
}

renderer::FrameSettings settings() {
    renderer::FrameSettings s;
    s.width = kSize;
    s.height = kSize;
    s.wait_for_timings = true;
    // The frame pixel by pixel against the sum of its terms: no edge filter, which mixes
    // neighbours at edges (tests/render/anti_aliasing_test.cpp tests it).
    s.anti_aliasing = false;
    return s;
}

double sum(const Image& image) {
    double total = 0.0;
    for (std::size_t i = 0; i < image.rgba.size(); ++i) {
        total += i % 4 == 3 ? 0.0 : static_cast<double>(image.rgba[i]);
    }
    return total;
}

class Passes : public ::testing::Test {
  protected:
    void SetUp() override { context_ = test::make_render_context(); }
    void TearDown() override { context_.reset(); }
    std::unique_ptr<GlContext> context_;
};

TEST_F(Passes, NoLightsNoShadowMaps) {
    test::RenderWorld world;
    world.add_mesh(
        test::single_mesh_scene(test::horizontal_square(glm::vec3(0.0f), 2.0f), glm::vec3(0.5f)));
    world.start();
    world.update();
    renderer::FrameRenderer renderer(world.registry, *world.lighting, settings());
    const renderer::FrameTimings& timings = renderer.render(camera(), world.time);
    EXPECT_FALSE(world.lighting->plan().shadows());
    EXPECT_EQ(renderer.shadow_map_count(), 0u);
    EXPECT_EQ(renderer.counters().shadow_maps, 0u);
    EXPECT_EQ(timings[renderer::RenderPass::Shadows], 0.0) << "the shadow pass must not run";
    EXPECT_EQ(timings[renderer::RenderPass::Direct], 0.0) << "the direct pass must not run";
    EXPECT_GT(timings[renderer::RenderPass::GBuffer], 0.0)
        << "timer queries measure the passes that run";
    EXPECT_EQ(sum(renderer.read(renderer::FrameImage::Direct)), 0.0);

    // A light: one map, and light on the plane.
    const ecs::Entity light = world.add_point_light({0.0f, 1.5f, 0.0f}, glm::vec3(20.0f));
    world.update();
    renderer.render(camera(), world.time);
    EXPECT_EQ(renderer.shadow_map_count(), 1u);
    EXPECT_GT(sum(renderer.read(renderer::FrameImage::Direct)), 0.0);

    // Switched off: its map is freed and the plane is dark again.
    world.registry.patch<PointLight>(light, [](PointLight& l) { l.enabled = false; });
    world.update();
    renderer.render(camera(), world.time);
    EXPECT_EQ(renderer.shadow_map_count(), 0u);
    EXPECT_EQ(sum(renderer.read(renderer::FrameImage::Frame)), 0.0);
}

TEST_F(Passes, TogglesRemoveExactlyTheirTerm) {
    test::RenderWorld world;
    const ecs::Entity plane = world.add_mesh(
        test::single_mesh_scene(test::horizontal_square(glm::vec3(0.0f), 2.0f), glm::vec3(0.5f)));
    world.registry.emplace<LightmappedSurface>(plane, test::whole_page_layout(16, 16.0));
    // A ceiling over the floor, so light bounces between them: indirect light on both.
    const ecs::Entity ceiling =
        world.add_mesh(test::single_mesh_scene(
                           test::horizontal_square(glm::vec3(0.0f), 2.0f, false), glm::vec3(0.7f)),
                       glm::vec3(0.0f, 2.0f, 0.0f));
    world.registry.emplace<LightmappedSurface>(ceiling, test::whole_page_layout(16, 16.0));
    world.add_point_light({0.0f, 1.5f, 0.0f}, glm::vec3(20.0f));
    world.start();
    // Enough frames for photons, an AIM and a gathered IIM.
    for (int i = 0; i < 30; ++i) {
        world.update();
    }
    renderer::FrameRenderer renderer(world.registry, *world.lighting, settings());
    // From the side, between floor and ceiling.
    const renderer::FrameCamera side = renderer::FrameCamera::look_at(
        {3.5f, 1.0f, 0.5f}, {0.0f, 0.8f, 0.0f}, {0.0f, 1.0f, 0.0f}, 1.2f, 1.0f);
    renderer.render(side, world.time + 100.0);
    const Image direct = renderer.read(renderer::FrameImage::Direct);
    const Image indirect = renderer.read(renderer::FrameImage::Indirect);
    const Image all = renderer.read(renderer::FrameImage::Frame);
    ASSERT_GT(sum(direct), 0.0);
    ASSERT_GT(sum(indirect), 0.0) << "the IIM should hold light after 30 updates";
    for (std::size_t i = 0; i < all.rgba.size(); i += 4) {
        EXPECT_NEAR(all.rgba[i], direct.rgba[i] + indirect.rgba[i], 1e-5f * all.rgba[i]);
    }

    renderer.set_terms({.direct = false});
    renderer.render(side, world.time + 100.0);
    const Image without_direct = renderer.read(renderer::FrameImage::Frame);
    renderer.set_terms({.indirect = false});
    renderer.render(side, world.time + 100.0);
    const Image without_indirect = renderer.read(renderer::FrameImage::Frame);
    for (std::size_t i = 0; i < all.rgba.size(); ++i) {
        if (i % 4 == 3) {
            continue;
        }
        EXPECT_NEAR(without_direct.rgba[i], indirect.rgba[i], 1e-6f + 1e-6f * all.rgba[i]);
        EXPECT_NEAR(without_indirect.rgba[i], direct.rgba[i], 1e-6f + 1e-6f * all.rgba[i]);
    }

    // The linear frame as EXR, bit for bit.
    const auto path = std::filesystem::path(::testing::TempDir()) / "luxel_render_frame.exr";
    write_exr(path, all);
    const Image back = read_exr(path);
    ASSERT_EQ(back.rgba.size(), all.rgba.size());
    for (std::size_t i = 0; i < all.rgba.size(); ++i) {
        ASSERT_EQ(back.rgba[i], all.rgba[i]) << "value " << i;
    }
    std::filesystem::remove(path);
}

TEST_F(Passes, CausticInputIsIrradianceTimesAlbedoOverPi) {
    test::RenderWorld world;
    world.add_mesh(test::single_mesh_scene(test::horizontal_square(glm::vec3(0.0f), 2.0f),
                                           glm::vec3(0.8f, 0.4f, 0.2f)));
    world.start();
    world.update();
    renderer::FrameRenderer renderer(world.registry, *world.lighting, settings());
    // A uniform caustic irradiance of 2 W/m^2 over the whole screen.
    gl::Texture caustics = gl::Texture::create_2d(GL_RGBA32F, kSize, kSize);
    std::vector<glm::vec4> values(static_cast<std::size_t>(kSize * kSize), glm::vec4(2.0f));
    glTextureSubImage2D(caustics.id(), 0, 0, 0, kSize, kSize, GL_RGBA, GL_FLOAT, values.data());
    renderer.set_caustics({caustics.id(), true});
    renderer.render(camera(), world.time);
    const Image frame = renderer.read(renderer::FrameImage::Frame);
    const Image albedo = renderer.read(renderer::FrameImage::Albedo);
    int covered = 0;
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
            if (albedo.pixel(x, y).r == 0.0f) {
                EXPECT_EQ(frame.pixel(x, y).r, 0.0f) << "no surface, no caustic";
                continue;
            }
            ++covered;
            const glm::vec3 expected = glm::vec3(0.8f, 0.4f, 0.2f) * 2.0f / 3.14159265f;
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(frame.pixel(x, y)[c], expected[c], 2e-3f * expected[c]);
            }
        }
    }
    EXPECT_GT(covered, kSize * kSize / 2);
    renderer.set_terms({.caustics = false});
    renderer.render(camera(), world.time);
    EXPECT_EQ(sum(renderer.read(renderer::FrameImage::Frame)), 0.0);
    renderer.set_terms({});
    renderer.set_caustics({});
    renderer.render(camera(), world.time);
    EXPECT_EQ(sum(renderer.read(renderer::FrameImage::Frame)), 0.0);
}

TEST_F(Passes, ACausticStageIsCompositedIntoTheFrameItWasDrawnFor) {
    test::RenderWorld world;
    world.add_mesh(test::single_mesh_scene(test::horizontal_square(glm::vec3(0.0f), 2.0f),
                                           glm::vec3(0.8f, 0.4f, 0.2f)));
    world.start();
    world.update();
    renderer::FrameRenderer renderer(world.registry, *world.lighting, settings());
    // Frame n's stage fills the caustic irradiance with n W/m^2; it must see frame n's depth
    // (the square drawn in the middle of the screen) and show up in frame n itself.
    gl::Texture caustics = gl::Texture::create_2d(GL_RGBA32F, kSize, kSize);
    int calls = 0;
    float centre_depth = -1.0f;
    renderer.set_caustic_stage([&](const renderer::FrameCamera&, GLuint depth) {
        ++calls;
        EXPECT_EQ(depth, renderer.depth_texture());
        glGetTextureSubImage(depth, 0, kSize / 2, kSize / 2, 0, 1, 1, 1, GL_DEPTH_COMPONENT,
                             GL_FLOAT, sizeof(float), &centre_depth);
        const std::vector<glm::vec4> values(static_cast<std::size_t>(kSize * kSize),
                                            glm::vec4(static_cast<float>(calls)));
        glTextureSubImage2D(caustics.id(), 0, 0, 0, kSize, kSize, GL_RGBA, GL_FLOAT, values.data());
        return renderer::CausticInput{caustics.id(), true};
    });
    for (int frame = 1; frame <= 3; ++frame) {
        renderer.render(camera(), world.time);
        EXPECT_EQ(calls, frame) << "one call per frame";
        EXPECT_GT(centre_depth, 0.0f);
        EXPECT_LT(centre_depth, 1.0f) << "the stage sees this frame's geometry";
        const Image image = renderer.read(renderer::FrameImage::Frame);
        const float expected = 0.8f * static_cast<float>(frame) / 3.14159265f;
        EXPECT_NEAR(image.pixel(kSize / 2, kSize / 2).r, expected, 2e-3f * expected)
            << "frame " << frame << " shows its own caustics";
    }
    // Caustics switched off: the stage is not called.
    renderer.set_terms({.caustics = false});
    renderer.render(camera(), world.time);
    EXPECT_EQ(calls, 3);
    renderer.set_terms({});
    renderer.set_caustic_stage({});
    renderer.set_caustics({});
    renderer.render(camera(), world.time);
    EXPECT_EQ(calls, 3);
    EXPECT_EQ(sum(renderer.read(renderer::FrameImage::Frame)), 0.0);
}

TEST_F(Passes, OfTwoFacesBackToBackTheOneFacingTheCameraIsDrawn) {
    // A wall between two rooms is two single-sided faces in one plane: red facing up, blue
    // facing down. From above every covered pixel must be red (glTF's single-sided faces show
    // their front only), not whichever face won the depth test; from below, blue. As
    // double-sided materials both would show and fight, so the faces here are single-sided.
    test::RenderWorld world;
    world.add_mesh(test::single_mesh_scene(test::horizontal_square(glm::vec3(0.0f), 2.0f, true),
                                           glm::vec3(0.8f, 0.1f, 0.1f)));
    world.add_mesh(test::single_mesh_scene(test::horizontal_square(glm::vec3(0.0f), 2.0f, false),
                                           glm::vec3(0.1f, 0.1f, 0.8f)));
    world.start();
    world.update();
    renderer::FrameRenderer renderer(world.registry, *world.lighting, settings());
    for (const bool above : {true, false}) {
        const glm::vec3 eye = above ? glm::vec3(0.5f, 3.5f, 2.5f) : glm::vec3(0.5f, -3.5f, 2.5f);
        renderer.render(
            renderer::FrameCamera::look_at(eye, glm::vec3(0.0f), {0.0f, 1.0f, 0.0f}, 1.0f, 1.0f),
            world.time);
        const Image albedo = renderer.read(renderer::FrameImage::Albedo);
        int covered = 0;
        int wrong = 0;
        for (int y = 0; y < kSize; ++y) {
            for (int x = 0; x < kSize; ++x) {
                const glm::vec4 a = albedo.pixel(x, y);
                if (a.r == 0.0f && a.b == 0.0f) {
                    continue;
                }
                ++covered;
                wrong += (above ? a.r < a.b : a.b < a.r) ? 1 : 0;
            }
        }
        std::printf(
            "[ figures  ] back-to-back faces seen from %s: %d of %d pixels show the back "
            "face\n",
            above ? "above" : "below", wrong, covered);
        EXPECT_GT(covered, kSize * kSize / 4);
        EXPECT_EQ(wrong, 0);
    }
}

}  // namespace
