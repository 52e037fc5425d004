// Direct light and shadows against analytic answers: a point light of power P over a diffuse
// plane gives L = albedo / pi * (P / 4 pi) cos / d^2 at every pixel; a blocker between them
// takes the direct term to zero inside its umbra and changes nothing outside; a shadow map is
// drawn again only when its light or a caster moved.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "luxel/ecs/transform.hpp"
#include "luxel/renderer/frame_renderer.hpp"
#include "render_scenes.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;

constexpr int kSize = 128;
const glm::vec3 kAlbedo(0.6f, 0.5f, 0.4f);
const glm::vec3 kPower(30.0f, 20.0f, 10.0f);
const glm::vec3 kLight(0.0f, 1.5f, 0.0f);

renderer::FrameCamera test_camera() {
    return renderer::FrameCamera::look_at({0.5f, 3.5f, 2.5f}, {0.0f, 0.0f, 0.0f},
                                          {0.0f, 1.0f, 0.0f}, 1.0f, 1.0f);
}

renderer::FrameSettings test_settings(bool filtered = true) {
    renderer::FrameSettings settings;
    settings.width = kSize;
    settings.height = kSize;
    settings.filtered_shadows = filtered;
    settings.wait_for_timings = true;
    // Every covered pixel against the analytic radiance, edges included: no edge filter
    // (tests/render/anti_aliasing_test.cpp tests it).
    settings.anti_aliasing = false;
    return settings;
}

/// The analytic direct radiance at a point of the plane (y = 0, normal +y).
glm::vec3 analytic(const glm::vec3& p) {
    const glm::vec3 to_light = kLight - p;
    const float d2 = glm::dot(to_light, to_light);
    const float cos_theta = to_light.y / std::sqrt(d2);
    const glm::vec3 intensity = kPower / (4.0f * glm::pi<float>());
    return kAlbedo / glm::pi<float>() * intensity * cos_theta / d2;
}

/// A world with the plane, the light and optionally the blocker, lit once. The blocker's
/// triangles are drawn `layers` times over (the same two triangles repeated in its index list).
struct PlaneScene {
    test::RenderWorld world;
    ecs::Entity light;
    ecs::Entity blocker;

    explicit PlaneScene(bool with_blocker, int layers = 1) {
        world.add_mesh(
            test::single_mesh_scene(test::horizontal_square(glm::vec3(0.0f), 2.0f), kAlbedo));
        if (with_blocker) {
            // A 0.4 m square halfway up: its umbra on the plane is the 0.8 m square around
            // the origin.
            scene::Primitive square = test::horizontal_square(glm::vec3(0.0f), 0.2f);
            const std::vector<std::uint32_t> once = square.indices;
            for (int layer = 1; layer < layers; ++layer) {
                square.indices.insert(square.indices.end(), once.begin(), once.end());
            }
            blocker = world.add_mesh(test::single_mesh_scene(std::move(square), glm::vec3(0.5f)),
                                     glm::vec3(0.0f, 0.75f, 0.0f));
        }
        light = world.add_point_light(kLight, kPower);
        world.start();
        world.update();
    }
};

class DirectLight : public ::testing::Test {
  protected:
    void SetUp() override { context_ = test::make_render_context(); }
    void TearDown() override { context_.reset(); }
    std::unique_ptr<GlContext> context_;
};

TEST_F(DirectLight, PointLightOverPlaneMatchesAnalyticRadiance) {
    PlaneScene scene(false);
    renderer::FrameRenderer renderer(scene.world.registry, *scene.world.lighting, test_settings());
    renderer.render(test_camera(), scene.world.time);
    const Image direct = renderer.read(renderer::FrameImage::Direct);
    const Image frame = renderer.read(renderer::FrameImage::Frame);
    const auto positions = test::read_texture(renderer.position_texture(), kSize, kSize);
    int checked = 0;
    float worst = 0.0f;
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
            // Image rows are top first, GL rows bottom first.
            const glm::vec4 p = positions[static_cast<std::size_t>((kSize - 1 - y) * kSize + x)];
            if (p.w == 0.0f) {
                continue;
            }
            const glm::vec3 expected = analytic(glm::vec3(p));
            const glm::vec4 got = direct.pixel(x, y);
            for (int c = 0; c < 3; ++c) {
                const float error = std::abs(got[c] - expected[c]) / expected[c];
                worst = std::max(worst, error);
                ASSERT_LT(error, 0.02f) << "pixel " << x << "," << y << " channel " << c << ": "
                                        << got[c] << " vs analytic " << expected[c];
                // No IIM, no emission, no caustics: the frame is the direct term.
                EXPECT_NEAR(frame.pixel(x, y)[c], got[c], 1e-6f * expected[c]);
            }
            ++checked;
        }
    }
    EXPECT_GT(checked, kSize * kSize / 2) << "the plane should fill most of the view";
    RecordProperty("max_relative_error", std::to_string(worst));
    std::printf("[ figures  ] direct vs analytic: %d pixels, max relative error %.4f%%\n", checked,
                100.0f * worst);
}

TEST_F(DirectLight, BlockerShadowsItsUmbraAndNothingElse) {
    for (const bool filtered : {true, false}) {
        PlaneScene open(false);
        PlaneScene blocked(true);
        renderer::FrameRenderer open_renderer(open.world.registry, *open.world.lighting,
                                              test_settings(filtered));
        renderer::FrameRenderer blocked_renderer(blocked.world.registry, *blocked.world.lighting,
                                                 test_settings(filtered));
        open_renderer.render(test_camera(), open.world.time);
        blocked_renderer.render(test_camera(), blocked.world.time);
        const Image lit = open_renderer.read(renderer::FrameImage::Direct);
        const Image shadowed = blocked_renderer.read(renderer::FrameImage::Direct);
        const auto positions =
            test::read_texture(blocked_renderer.position_texture(), kSize, kSize);
        int umbra = 0;
        int outside = 0;
        for (int y = 0; y < kSize; ++y) {
            for (int x = 0; x < kSize; ++x) {
                const glm::vec4 p =
                    positions[static_cast<std::size_t>((kSize - 1 - y) * kSize + x)];
                if (p.w == 0.0f || p.y > 1e-3f) {
                    continue;  // the blocker itself, or nothing
                }
                const float extent = std::max(std::abs(p.x), std::abs(p.z));
                const glm::vec3 expected = analytic(glm::vec3(p));
                for (int c = 0; c < 3; ++c) {
                    if (extent < 0.3f) {
                        EXPECT_LT(shadowed.pixel(x, y)[c], 0.01f * expected[c])
                            << "umbra pixel " << x << "," << y << " filtered " << filtered;
                    } else if (extent > 0.55f) {
                        EXPECT_NEAR(shadowed.pixel(x, y)[c], lit.pixel(x, y)[c],
                                    1e-4f * expected[c])
                            << "lit pixel " << x << "," << y << " filtered " << filtered;
                    }
                }
                umbra += extent < 0.3f ? 1 : 0;
                outside += extent > 0.55f ? 1 : 0;
            }
        }
        EXPECT_GT(umbra, 100) << "the umbra should be in view";
        EXPECT_GT(outside, 2000);
    }
}

/// Counts, over the plane's pixels of `direct`, those inside the blocker's umbra (extent < 0.3 m)
/// that are dark, and checks every lit pixel far outside it against the analytic radiance.
struct UmbraCount {
    int umbra = 0;
    int dark = 0;
    int lit = 0;
};
UmbraCount count_umbra(const Image& direct, const std::vector<glm::vec4>& positions) {
    UmbraCount count;
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
            const glm::vec4 p = positions[static_cast<std::size_t>((kSize - 1 - y) * kSize + x)];
            if (p.w == 0.0f || p.y > 1e-3f) {
                continue;  // the blocker itself, or nothing
            }
            const float extent = std::max(std::abs(p.x), std::abs(p.z));
            const glm::vec3 expected = analytic(glm::vec3(p));
            const glm::vec4 got = direct.pixel(x, y);
            if (extent < 0.3f) {
                ++count.umbra;
                count.dark += got.g < 0.01f * expected.g ? 1 : 0;
            } else if (extent > 0.55f) {
                ++count.lit;
                EXPECT_NEAR(got.g, expected.g, 0.02f * expected.g) << "pixel " << x << "," << y;
            }
        }
    }
    return count;
}

// A level within every load limit can stack geometry on itself: 40,000 coincident quads took
// 7.5 s to draw into one cube shadow map on llvmpipe, 10M coincident triangles over a minute
// in a 64 x 48 G-buffer. Each view has a fill budget (renderer/src/fill_budget.hpp): a blocker
// drawn 10 times over is drawn in full, one drawn 100,000 times over is left out of the
// shadow map and the frame (with a warning), and the rest of the level is still drawn right.
TEST_F(DirectLight, GeometryStackedOnItselfIsLeftOutPastTheFillBudget) {
    {
        PlaneScene scene(true, 10);
        renderer::FrameRenderer renderer(scene.world.registry, *scene.world.lighting,
                                         test_settings());
        renderer.render(test_camera(), scene.world.time);
        EXPECT_EQ(renderer.counters().draws_over_fill_budget, 0u) << "10 layers fit the budget";
        const UmbraCount count =
            count_umbra(renderer.read(renderer::FrameImage::Direct),
                        test::read_texture(renderer.position_texture(), kSize, kSize));
        EXPECT_GT(count.umbra, 100);
        EXPECT_EQ(count.dark, count.umbra) << "the blocker casts its shadow";
        EXPECT_GT(count.lit, 2000);
    }
    PlaneScene scene(true, 100000);
    renderer::FrameRenderer renderer(scene.world.registry, *scene.world.lighting, test_settings());
    renderer.render(test_camera(), scene.world.time);
    // Left out of the shadow map and of the G-buffer, each once.
    EXPECT_EQ(renderer.counters().draws_over_fill_budget, 2u);
    const Image direct = renderer.read(renderer::FrameImage::Direct);
    const UmbraCount count =
        count_umbra(direct, test::read_texture(renderer.position_texture(), kSize, kSize));
    EXPECT_GT(count.umbra, 100) << "the blocker is not in the frame: the plane under it shows";
    EXPECT_EQ(count.dark, 0) << "and it casts no shadow";
    EXPECT_GT(count.lit, 2000);
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
            const glm::vec4 pixel = direct.pixel(x, y);
            ASSERT_TRUE(std::isfinite(pixel.r) && std::isfinite(pixel.g) && std::isfinite(pixel.b))
                << "pixel " << x << "," << y;
        }
    }
    renderer.render(test_camera(), scene.world.time);
    EXPECT_EQ(renderer.counters().draws_over_fill_budget, 3u)
        << "the G-buffer is drawn every frame; the shadow map only when something moved";
}

/// One frame of `scene` (its lighting updated, then drawn); returns the shadow maps drawn in it.
std::size_t next_frame(PlaneScene& scene, renderer::FrameRenderer& renderer) {
    scene.world.update();
    renderer.render(test_camera(), scene.world.time);
    return renderer.counters().shadow_maps_drawn;
}

TEST_F(DirectLight, ShadowMapsAreRedrawnOnlyWhenLightOrCasterMoves) {
    PlaneScene scene(true);
    renderer::FrameRenderer renderer(scene.world.registry, *scene.world.lighting, test_settings());
    const auto frame = [&] { return next_frame(scene, renderer); };
    EXPECT_EQ(frame(), 1u) << "a new light's map is drawn";
    EXPECT_EQ(frame(), 0u) << "nothing moved";
    EXPECT_EQ(frame(), 0u);
    scene.world.registry.patch<ecs::Transform>(scene.blocker,
                                               [](ecs::Transform& t) { t.translation.x += 0.3f; });
    EXPECT_EQ(frame(), 1u) << "a caster in range moved";
    EXPECT_EQ(frame(), 0u);
    scene.world.registry.patch<ecs::Transform>(scene.light,
                                               [](ecs::Transform& t) { t.translation.z += 0.1f; });
    EXPECT_EQ(frame(), 1u) << "the light moved";
    EXPECT_EQ(frame(), 0u);
    scene.world.registry.patch<PointLight>(scene.light, [](PointLight& l) { l.power *= 2.0f; });
    EXPECT_EQ(frame(), 0u) << "a brighter light casts the same shadow";
    EXPECT_EQ(renderer.shadow_map_count(), 1u);
    EXPECT_EQ(renderer.counters().shadow_map_renders, 3u);
}

// Every light's map is a layer of one array per shape (renderer/src/shadow_layers.hpp), which
// grows by doubling as lights arrive: the maps it held are copied, not drawn again, and still
// shadow right. Four more point lights under the plane (they light its back, so they add
// nothing to the frame but each takes a cube layer: 1 -> 2 -> 4 -> 8), then all but the first
// switched off (their layers freed; the array stays while the first light's map is in it).
TEST_F(DirectLight, ShadowMapsSurviveTheirArrayGrowing) {
    PlaneScene scene(true);
    renderer::FrameRenderer renderer(scene.world.registry, *scene.world.lighting, test_settings());
    const auto frame = [&] { return next_frame(scene, renderer); };
    const auto positions = [&] {
        return test::read_texture(renderer.position_texture(), kSize, kSize);
    };
    ASSERT_EQ(frame(), 1u);
    const UmbraCount before = count_umbra(renderer.read(renderer::FrameImage::Direct), positions());
    std::vector<ecs::Entity> below;
    for (int i = 0; i < 4; ++i) {
        below.push_back(scene.world.add_point_light(
            glm::vec3(-0.6f + 0.4f * static_cast<float>(i), -1.0f, 0.0f), kPower));
        EXPECT_EQ(frame(), 1u) << "only the new light's map is drawn, light " << i;
    }
    EXPECT_EQ(renderer.shadow_map_count(), 5u);
    const UmbraCount after = count_umbra(renderer.read(renderer::FrameImage::Direct), positions());
    EXPECT_GT(before.umbra, 100);
    EXPECT_EQ(after.umbra, before.umbra);
    EXPECT_EQ(after.dark, after.umbra) << "the first light's map, copied, still casts the umbra";
    EXPECT_EQ(before.dark, before.umbra);
    for (const ecs::Entity light : below) {
        scene.world.registry.patch<PointLight>(light, [](PointLight& l) { l.enabled = false; });
    }
    EXPECT_EQ(frame(), 0u);
    EXPECT_EQ(renderer.shadow_map_count(), 1u);
    const UmbraCount last = count_umbra(renderer.read(renderer::FrameImage::Direct), positions());
    EXPECT_EQ(last.dark, last.umbra);
}

}  // namespace
