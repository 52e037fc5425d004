// The sky behind the level (issue 20): where the frame draws nothing, a view shows the sky's
// radiance along each pixel's ray. Seen from outside the `furnace` sphere under a uniform sky of
// radiance L, every pixel that misses the sphere shows L exactly when its ray points above the
// horizon and nothing below it; without a sky the background stays black.

#include <cmath>
#include <cstdio>
#include <memory>

#include <gtest/gtest.h>

#include "luxel/lighting/components.hpp"
#include "luxel/renderer/frame_renderer.hpp"
#include "luxel/scene/gltf.hpp"
#include "luxel/world/scene_instance.hpp"
#include "render_scenes.hpp"

namespace {

using namespace luxel;

constexpr int kWidth = 64;
constexpr int kHeight = 48;

struct Counts {
    int sky = 0;     ///< background pixels above the horizon showing exactly L
    int ground = 0;  ///< background pixels below it showing exactly 0
    int wrong = 0;
};

Counts render_background(const std::optional<scene::SkySpec>& sky, const glm::vec3& radiance) {
    auto context = test::make_render_context();
    test::RenderWorld world;
    world.load_level("furnace", sky);
    world.start();
    world.update(1e9);
    renderer::FrameSettings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    renderer::FrameRenderer renderer(world.registry, *world.lighting, settings);
    // 6 m from the unit sphere: it covers the middle of the frame, the sky the rest.
    const glm::vec3 eye(0.0f, 0.0f, 6.0f);
    const renderer::FrameCamera camera =
        renderer::FrameCamera::look_at(eye, glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f), 1.2f,
                                       static_cast<float>(kWidth) / kHeight);
    renderer.render(camera, world.time);
    const Image frame = renderer.read(renderer::FrameImage::Frame);
    const glm::mat4 inverse = glm::inverse(camera.projection * camera.view);
    Counts counts;
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            // Rows top first: the pixel's ray, as the composite computes it.
            const glm::vec2 ndc(2.0f * (static_cast<float>(x) + 0.5f) / kWidth - 1.0f,
                                1.0f - 2.0f * (static_cast<float>(y) + 0.5f) / kHeight);
            const glm::vec4 far = inverse * glm::vec4(ndc, 0.5f, 1.0f);
            const glm::vec3 ray = glm::normalize(glm::vec3(far) / far.w - eye);
            // Misses the unit sphere by a pixel's width or more (0.02 rad here).
            const glm::vec3 closest = eye - glm::dot(eye, ray) * ray;
            if (glm::length(closest) < 1.15f) {
                continue;
            }
            const glm::vec4 shown = frame.pixel(x, y);
            // A ray within a few texels of the horizon may blend the two rows.
            if (std::abs(ray.y) < 0.02f) {
                continue;
            }
            const glm::vec3 expected = ray.y > 0.0f ? radiance : glm::vec3(0.0f);
            const bool right = glm::all(
                glm::lessThanEqual(glm::abs(glm::vec3(shown) - expected), glm::vec3(1e-5f)));
            if (!right) {
                ++counts.wrong;
                if (counts.wrong <= 3) {
                    std::printf("pixel (%d, %d) ray y %.3f shows %g %g %g, expected %g %g %g\n", x,
                                y, ray.y, shown.r, shown.g, shown.b, expected.r, expected.g,
                                expected.b);
                }
            } else if (ray.y > 0.0f) {
                ++counts.sky;
            } else {
                ++counts.ground;
            }
        }
    }
    return counts;
}

TEST(SkyFrame, TheBackgroundShowsTheSkyAboveTheHorizonAndNothingBelow) {
    const glm::vec3 radiance(0.25f, 0.5f, 1.0f);
    const Counts counts = render_background(scene::parse_sky("uniform:0.25,0.5,1"), radiance);
    std::printf(
        "[ figures  ] uniform sky behind the furnace: %d sky pixels, %d ground pixels, "
        "%d wrong\n",
        counts.sky, counts.ground, counts.wrong);
    EXPECT_EQ(counts.wrong, 0);
    EXPECT_GT(counts.sky, 500);
    EXPECT_GT(counts.ground, 500);
}

TEST(SkyFrame, WithoutASkyTheBackgroundIsBlack) {
    const Counts counts = render_background(std::nullopt, glm::vec3(0.0f));
    EXPECT_EQ(counts.wrong, 0);
    EXPECT_GT(counts.sky + counts.ground, 1000);
}

}  // namespace
