// A skinned figure's shadow in the frame where the reference integrator puts it (issue 29's
// goal: the direct term's image relRMSE at most 5% over the shadow's region). The figure is the
// one Blender exports (tests/levels/blender/skinned-figure.py), posed mid-stride, when its legs
// are apart and a shadow of the rest pose would show plainly: the frame's shadow maps draw the
// skinned vertices, and the reference traces the same posed mesh in the ray scene.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "luxel/lighting/reference/reference_frame.hpp"
#include "luxel/lighting/reference/reference_scene.hpp"
#include "luxel/renderer/frame_renderer.hpp"
#include "luxel/scene/gltf.hpp"
#include "luxel/world/animation_system.hpp"
#include "luxel/world/skinning.hpp"
#include "render_scenes.hpp"

namespace {

using namespace luxel;

constexpr int kWidth = 480;
constexpr int kHeight = 270;
// The level's own camera (its "Camera" node): 1.9 m up at the open side of the room, pitched
// down by 15.5 degrees, vertical field of view 0.798 rad.
const glm::vec3 kEye(0.2f, 1.9f, 4.6f);
const glm::vec3 kTarget = kEye + glm::vec3(0.0f, -0.2675f, -0.9636f);
constexpr float kFov = 0.7984f;
// The level's point light ("Ceiling lamp").
const glm::vec3 kLamp(0.3f, 2.3f, 0.2f);

/// relRMSE over RGB of `frame` against `reference` within [x0, x1) x [y0, y1), comparing the
/// means of `block` x `block` pixel blocks (as luxel-frame-error --block does).
double region_relrmse(const Image& frame, const Image& reference, int x0, int y0, int x1, int y1,
                      int block = 1) {
    double diff = 0.0;
    double norm = 0.0;
    for (int by = y0; by + block <= y1; by += block) {
        for (int bx = x0; bx + block <= x1; bx += block) {
            glm::dvec3 a(0.0);
            glm::dvec3 b(0.0);
            for (int y = by; y < by + block; ++y) {
                for (int x = bx; x < bx + block; ++x) {
                    a += glm::dvec3(glm::vec3(frame.pixel(x, y)));
                    b += glm::dvec3(glm::vec3(reference.pixel(x, y)));
                }
            }
            diff += glm::dot(a - b, a - b);
            norm += glm::dot(b, b);
        }
    }
    return norm > 0.0 ? std::sqrt(diff / norm) : std::numeric_limits<double>::infinity();
}

struct ShadowBox {
    int x0 = kWidth;
    int y0 = kHeight;
    int x1 = 0;
    int y1 = 0;
    int pixels = 0;
};

TEST(SkinnedShadow, TheFiguresShadowMidStrideIsWhereTheReferencePutsIt) {
    const auto context = test::make_render_context();
    test::RenderWorld world;
    const auto level =
        std::make_shared<scene::Scene>(scene::load_gltf(test::prepared_level("skinned-figure")));
    ASSERT_EQ(level->skins.size(), 1u);
    world::InstantiateOptions options;
    options.play_animations = true;
    world::instantiate(world.registry, level, options);
    // Mid-stride, 0.7 s into the 2 s walk: legs and arms far from the rest pose.
    world::update_animations(world.registry, 0.7);
    world.transforms.update();
    ASSERT_EQ(world::update_skins(world.registry), 1u);
    world.start();
    world.update(1.0, 0.0);  // the posed mesh into the ray scene; the direct term needs no more

    renderer::FrameSettings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    renderer::FrameRenderer renderer(world.registry, *world.lighting, settings);
    renderer.render(renderer::FrameCamera::look_at(kEye, kTarget, {0.0f, 1.0f, 0.0f}, kFov,
                                                   static_cast<float>(kWidth) / kHeight),
                    world.time);
    const Image frame = renderer.read(renderer::FrameImage::Direct);
    const auto positions = test::read_texture(renderer.position_texture(), kWidth, kHeight);

    // The reference: one scattering event per path, so each pixel holds the lamp's light at
    // the surface it sees, shadowed by the posed figure in the ray scene.
    const lighting::reference::ReferenceScene reference_scene =
        lighting::reference::ReferenceScene::from_world(world.lighting->photons(),
                                                        world.lighting->maps());
    lighting::reference::ReferenceFrameSettings reference_settings;
    reference_settings.samples_per_pass = 32;
    reference_settings.paths.max_vertices = 1;
    const auto camera =
        lighting::reference::ReferenceCamera::look_at(kEye, kTarget, kFov, kWidth, kHeight);
    lighting::reference::ReferenceFrame reference(reference_scene, camera, reference_settings);
    reference.run_pass(world.jobs);
    const Image reference_image = reference.image();
    if (const char* dump = std::getenv("LUXEL_RENDER_OUT")) {
        write_exr(std::string(dump) + "/skinned-shadow-frame.exr", frame);
        write_exr(std::string(dump) + "/skinned-shadow-reference.exr", reference_image);
        write_png(std::string(dump) + "/skinned-shadow-frame.png", frame);
        write_png(std::string(dump) + "/skinned-shadow-reference.png", reference_image);
    }

    // The shadow's region, from neither image: the floor pixels (G-buffer) from which the ray
    // to the lamp meets something, the figure being the only thing between floor and lamp.
    const lighting::RayScene& rays = world.lighting->photons().ray_scene();
    ShadowBox box;
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            const glm::vec4& p =
                positions[static_cast<std::size_t>((kHeight - 1 - y) * kWidth + x)];
            if (p.w == 0.0f || std::abs(p.y) > 1e-3f) {
                continue;  // not the floor
            }
            const glm::vec3 from = glm::vec3(p) + glm::vec3(0.0f, 1e-3f, 0.0f);
            const glm::vec3 to_lamp = kLamp - from;
            const float distance = glm::length(to_lamp);
            if (rays.occluded(from, to_lamp / distance, distance)) {
                box.x0 = std::min(box.x0, x);
                box.y0 = std::min(box.y0, y);
                box.x1 = std::max(box.x1, x + 1);
                box.y1 = std::max(box.y1, y + 1);
                ++box.pixels;
            }
        }
    }
    ASSERT_GT(box.pixels, 200) << "the figure casts a shadow the camera sees";
    // With a margin of lit floor around it, so a shadow drawn in the wrong place counts twice:
    // dark where the floor is lit, lit where the reference is dark.
    constexpr int kMargin = 4;
    box.x0 = std::max(0, box.x0 - kMargin);
    box.y0 = std::max(0, box.y0 - kMargin);
    box.x1 = std::min(kWidth, box.x1 + kMargin);
    box.y1 = std::min(kHeight, box.y1 + kMargin);
    // Per pixel the two differ along every edge, a pixel wide (the frame samples its shadow
    // maps once per pixel, the reference jitters 32 samples over it): that aliasing, not the
    // shadow's place, is most of the per-pixel figure, so the goal is checked on 2 x 2 blocks
    // and the per-pixel figure only bounded.
    const double error = region_relrmse(frame, reference_image, box.x0, box.y0, box.x1, box.y1, 2);
    const double per_pixel = region_relrmse(frame, reference_image, box.x0, box.y0, box.x1, box.y1);
    const double whole = region_relrmse(frame, reference_image, 0, 0, kWidth, kHeight, 2);

    // What a shadow of the figure standing (its rest pose) would score against the same
    // reference: the test can tell a shadow that does not follow the joints.
    world.registry.view<world::AnimationPlayer>().each(
        [](world::AnimationPlayer& player) { player.time = 0.0; });
    world::update_animations(world.registry, 0.0);
    world.transforms.update();
    ASSERT_EQ(world::update_skins(world.registry), 1u);
    world.update(1.0, 0.0);
    renderer.render(renderer::FrameCamera::look_at(kEye, kTarget, {0.0f, 1.0f, 0.0f}, kFov,
                                                   static_cast<float>(kWidth) / kHeight),
                    world.time);
    const Image standing = renderer.read(renderer::FrameImage::Direct);
    const double standing_error =
        region_relrmse(standing, reference_image, box.x0, box.y0, box.x1, box.y1, 2);

    std::printf(
        "[ figures  ] shadow region x %d-%d, y %d-%d (%d shadowed floor pixels): direct "
        "relRMSE %.2f%% over 2x2 blocks, %.2f%% per pixel (whole frame %.2f%%); the "
        "standing pose's shadow %.2f%%\n",
        box.x0, box.x1, box.y0, box.y1, box.pixels, 100.0 * error, 100.0 * per_pixel, 100.0 * whole,
        100.0 * standing_error);
    EXPECT_LT(error, 0.05) << "issue 29: the direct term within 5% over the shadow's region";
    EXPECT_LT(per_pixel, 0.08);
    EXPECT_LT(whole, 0.05);
    EXPECT_GT(standing_error, 5.0 * error)
        << "a shadow that stays in the rest pose should score far worse";
}

}  // namespace
