// Anti-aliasing of the frame's geometric edges (docs/METHOD.md §8.4), against what a box
// filter over each pixel gives: the same renderer at 8 x 8 samples per pixel without
// anti-aliasing, averaged per pixel (as luxel-ref averages jittered samples). The edges of a
// lit plane against the void and of a tilted blocker in front of it are in view. The pass must
// bring the frame closer to the box-filtered one, near the edges as a whole and not only on
// average, and copy every pixel away from an edge exactly; without it no pass runs.

#include <cmath>
#include <cstdio>
#include <memory>

#include <gtest/gtest.h>
#include <glm/gtc/quaternion.hpp>

#include "luxel/ecs/transform.hpp"
#include "luxel/renderer/frame_renderer.hpp"
#include "render_scenes.hpp"

namespace {

using namespace luxel;

constexpr int kSize = 96;
constexpr int kSupersample = 8;  ///< samples per pixel edge of the box-filtered frame

renderer::FrameCamera test_camera() {
    // Off every axis, so the square's edges and the blocker's run slanted across the image.
    return renderer::FrameCamera::look_at({1.1f, 2.6f, 1.9f}, {0.1f, 0.0f, -0.2f},
                                          {0.0f, 1.0f, 0.0f}, 1.0f, 1.0f);
}

/// A 2 m plane lit by a point light, and a 0.6 m blocker above it turned 20 degrees about the
/// vertical and 10 about x, so its silhouette is neither along the plane's edges nor the
/// image's rows.
struct EdgeScene {
    test::RenderWorld world;

    EdgeScene() {
        world.add_mesh(test::single_mesh_scene(test::horizontal_square(glm::vec3(0.0f), 1.0f),
                                               glm::vec3(0.6f, 0.5f, 0.4f)));
        const ecs::Entity blocker =
            world.add_mesh(test::single_mesh_scene(test::horizontal_square(glm::vec3(0.0f), 0.3f),
                                                   glm::vec3(0.15f, 0.2f, 0.7f)),
                           glm::vec3(0.2f, 0.6f, 0.1f));
        world.registry.patch<ecs::Transform>(blocker, [](ecs::Transform& t) {
            t.rotation = glm::angleAxis(glm::radians(20.0f), glm::vec3(0.0f, 1.0f, 0.0f)) *
                         glm::angleAxis(glm::radians(10.0f), glm::vec3(1.0f, 0.0f, 0.0f));
        });
        world.add_point_light({-0.4f, 1.8f, 0.5f}, glm::vec3(40.0f));
        world.start();
        world.update();
    }
};

renderer::FrameSettings settings(int size, bool anti_aliasing) {
    renderer::FrameSettings s;
    s.width = size;
    s.height = size;
    s.anti_aliasing = anti_aliasing;
    s.wait_for_timings = true;
    return s;
}

float luminance(const glm::vec4& c) {
    return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}

/// The supersampled frame averaged over each block of kSupersample^2 samples.
Image box_filtered(const Image& fine) {
    Image out(kSize, kSize, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
            glm::dvec3 sum(0.0);
            for (int j = 0; j < kSupersample; ++j) {
                for (int i = 0; i < kSupersample; ++i) {
                    sum += glm::dvec3(
                        glm::vec3(fine.pixel(x * kSupersample + i, y * kSupersample + j)));
                }
            }
            out.set_pixel(x, y, glm::vec4(glm::vec3(sum / double(kSupersample * kSupersample)), 1));
        }
    }
    return out;
}

/// Pixels of the box-filtered frame that straddle an edge: their block is not uniform
/// (some samples differ by more than a tenth from the block's mean, in luminance).
std::vector<bool> edge_pixels(const Image& fine, const Image& reference) {
    std::vector<bool> edge(static_cast<std::size_t>(kSize * kSize), false);
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
            const float mean = luminance(reference.pixel(x, y));
            bool mixed = false;
            for (int j = 0; j < kSupersample && !mixed; ++j) {
                for (int i = 0; i < kSupersample && !mixed; ++i) {
                    const float s =
                        luminance(fine.pixel(x * kSupersample + i, y * kSupersample + j));
                    mixed = std::abs(s - mean) > 0.1f * std::max(mean, 1e-3f);
                }
            }
            edge[static_cast<std::size_t>(y * kSize + x)] = mixed;
        }
    }
    return edge;
}

/// sqrt(sum (a - r)^2 / sum r^2) over the pixels `use` selects, in luminance.
double rel_rmse(const Image& a, const Image& r, const std::vector<bool>& use) {
    double error = 0.0;
    double norm = 0.0;
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
            if (!use[static_cast<std::size_t>(y * kSize + x)]) {
                continue;
            }
            const double d = luminance(a.pixel(x, y)) - luminance(r.pixel(x, y));
            error += d * d;
            norm += double(luminance(r.pixel(x, y))) * luminance(r.pixel(x, y));
        }
    }
    return norm > 0.0 ? std::sqrt(error / norm) : 0.0;
}

class AntiAliasing : public ::testing::Test {
  protected:
    void SetUp() override { context_ = test::make_render_context(); }
    void TearDown() override { context_.reset(); }
    std::unique_ptr<GlContext> context_;
};

TEST_F(AntiAliasing, EdgesComeCloserToTheBoxFilteredFrameAndNothingElseChanges) {
    EdgeScene scene;
    const auto render = [&](int size, bool anti_aliasing) {
        renderer::FrameRenderer renderer(scene.world.registry, *scene.world.lighting,
                                         settings(size, anti_aliasing));
        renderer.render(test_camera(), scene.world.time);
        return renderer.read(renderer::FrameImage::Frame);
    };
    const Image fine = render(kSize * kSupersample, false);
    const Image reference = box_filtered(fine);
    const Image off = render(kSize, false);
    const Image on = render(kSize, true);

    const std::vector<bool> edges = edge_pixels(fine, reference);
    const std::vector<bool> everywhere(edges.size(), true);
    std::size_t edge_count = 0;
    for (bool e : edges) {
        edge_count += e ? 1 : 0;
    }
    ASSERT_GT(edge_count, 150u) << "the scene must put edges in view";

    const double whole_off = rel_rmse(off, reference, everywhere);
    const double whole_on = rel_rmse(on, reference, everywhere);
    const double edges_off = rel_rmse(off, reference, edges);
    const double edges_on = rel_rmse(on, reference, edges);
    std::printf(
        "relRMSE against the box-filtered frame (%zu edge pixels): whole frame %.2f%% "
        "without, %.2f%% with anti-aliasing; edge pixels %.2f%% / %.2f%%\n",
        edge_count, 100.0 * whole_off, 100.0 * whole_on, 100.0 * edges_off, 100.0 * edges_on);
    EXPECT_LT(edges_on, 0.75 * edges_off);
    // Not only on average: pixels the pass made clearly worse (by a fifth of the box-filtered
    // value more than without it) stay a small minority of the edge pixels.
    std::size_t worse = 0;
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
            if (!edges[static_cast<std::size_t>(y * kSize + x)]) {
                continue;
            }
            const float r = luminance(reference.pixel(x, y));
            const float e_on = std::abs(luminance(on.pixel(x, y)) - r);
            const float e_off = std::abs(luminance(off.pixel(x, y)) - r);
            worse += e_on > e_off + 0.2f * std::max(r, 1e-3f) ? 1 : 0;
        }
    }
    std::printf("edge pixels made worse by over a fifth: %zu of %zu\n", worse, edge_count);
    EXPECT_LT(worse, edge_count / 10);
    EXPECT_LT(whole_on, 0.75 * whole_off);

    // Away from edges the frame is the composite's, bit for bit: a pixel whose 5 x 5
    // neighbourhood in the box-filtered frame has no edge pixel.
    int compared = 0;
    for (int y = 2; y < kSize - 2; ++y) {
        for (int x = 2; x < kSize - 2; ++x) {
            bool near_edge = false;
            for (int j = -2; j <= 2; ++j) {
                for (int i = -2; i <= 2; ++i) {
                    near_edge =
                        near_edge || edges[static_cast<std::size_t>((y + j) * kSize + x + i)];
                }
            }
            if (near_edge) {
                continue;
            }
            ++compared;
            ASSERT_EQ(on.pixel(x, y), off.pixel(x, y)) << "pixel " << x << ", " << y;
        }
    }
    EXPECT_GT(compared, kSize * kSize / 2);
    for (float v : on.rgba) {
        ASSERT_TRUE(std::isfinite(v));
    }
}

TEST_F(AntiAliasing, IsAPassOfItsOwnAndOffLeavesItOut) {
    EdgeScene scene;
    renderer::FrameRenderer with(scene.world.registry, *scene.world.lighting,
                                 settings(kSize, true));
    EXPECT_GT(with.render(test_camera(), scene.world.time)[renderer::RenderPass::AntiAliasing],
              0.0);
    EXPECT_EQ(renderer::name(renderer::RenderPass::AntiAliasing), "anti_aliasing");
    renderer::FrameRenderer without(scene.world.registry, *scene.world.lighting,
                                    settings(kSize, false));
    EXPECT_EQ(without.render(test_camera(), scene.world.time)[renderer::RenderPass::AntiAliasing],
              0.0);
}

}  // namespace
