// Silhouettes against the sky (FrameSettings::sky_edge_coverage, docs/METHOD.md §8.6): the
// furnace sphere seen from outside under a uniform sky. A pixel on its outline shows the sky
// over the share of its area the sphere leaves, which the test computes exactly (a ray-sphere
// test at 16 x 16 points a pixel) and compares with what the frame shows, against the sphere's
// light one pixel inside and the sky's along the pixel's ray.

#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include <gtest/gtest.h>

#include "luxel/renderer/frame_renderer.hpp"
#include "luxel/scene/sky.hpp"
#include "luxel/world/scene_instance.hpp"
#include "render_scenes.hpp"

namespace {

using namespace luxel;

constexpr int kWidth = 128;
constexpr int kHeight = 96;
const glm::vec3 kEye(0.0f, 0.0f, 6.0f);

/// The ray through (px, py) of the frame (pixel units, rows from the top).
glm::vec3 ray_at(const glm::mat4& inverse, float px, float py) {
    const glm::vec2 ndc(2.0f * px / kWidth - 1.0f, 1.0f - 2.0f * py / kHeight);
    const glm::vec4 far = inverse * glm::vec4(ndc, 0.5f, 1.0f);
    return glm::normalize(glm::vec3(far) / far.w - kEye);
}

bool hits_unit_sphere(const glm::vec3& ray) {
    const glm::vec3 closest = kEye - glm::dot(kEye, ray) * ray;
    return glm::length(closest) < 1.0f;
}

struct EdgeError {
    double rms = 0.0;  ///< of (shown - expected) / (sky - surface), over outline pixels
    int pixels = 0;
};

/// The furnace sphere lit under `sky` (or none), and the view of it from kEye.
struct FurnaceView {
    std::unique_ptr<GlContext> context = test::make_render_context();
    test::RenderWorld world;
    renderer::FrameCamera camera =
        renderer::FrameCamera::look_at(kEye, glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f), 1.2f,
                                       static_cast<float>(kWidth) / kHeight);

    explicit FurnaceView(const std::optional<scene::SkySpec>& sky) {
        world.load_level("furnace", sky);
        world.start();
        world.update(1e9);
    }

    [[nodiscard]] static renderer::FrameSettings settings() {
        renderer::FrameSettings settings;
        settings.width = kWidth;
        settings.height = kHeight;
        return settings;
    }
};

EdgeError outline_error(bool coverage, bool anti_aliasing) {
    FurnaceView view(scene::parse_sky("uniform:2,2,2"));
    renderer::FrameSettings settings = FurnaceView::settings();
    settings.sky_edge_coverage = coverage;
    settings.anti_aliasing = anti_aliasing;
    renderer::FrameRenderer renderer(view.world.registry, *view.world.lighting, settings);
    const renderer::FrameCamera& camera = view.camera;
    renderer.render(camera, view.world.time);
    const Image frame = renderer.read(renderer::FrameImage::Frame);
    const glm::mat4 inverse = glm::inverse(camera.projection * camera.view);
    const glm::vec2 centre(kWidth / 2.0f, kHeight / 2.0f);
    double sum = 0.0;
    EdgeError error;
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            constexpr int kPoints = 16;
            int missed = 0;
            for (int j = 0; j < kPoints; ++j) {
                for (int i = 0; i < kPoints; ++i) {
                    const glm::vec3 ray = ray_at(
                        inverse, static_cast<float>(x) + (static_cast<float>(i) + 0.5f) / kPoints,
                        static_cast<float>(y) + (static_cast<float>(j) + 0.5f) / kPoints);
                    missed += hits_unit_sphere(ray) ? 0 : 1;
                }
            }
            const double sky_share = static_cast<double>(missed) / (kPoints * kPoints);
            const glm::vec3 centre_ray =
                ray_at(inverse, static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
            // Outline pixels only, above the horizon (the ground below it is black), and
            // with a pixel two steps inward that the sphere covers whole.
            if (sky_share < 0.05 || sky_share > 0.95 || centre_ray.y < 0.05f) {
                continue;
            }
            const glm::vec2 inward = glm::normalize(centre - glm::vec2(x + 0.5f, y + 0.5f));
            const int ix = static_cast<int>(std::lround(x + 2.0f * inward.x));
            const int iy = static_cast<int>(std::lround(y + 2.0f * inward.y));
            const double surface = frame.pixel(ix, iy).g;
            const double sky = 2.0;
            const double expected = surface + (sky - surface) * sky_share;
            const double shown = frame.pixel(x, y).g;
            const double e = (shown - expected) / (sky - surface);
            sum += e * e;
            ++error.pixels;
        }
    }
    error.rms = error.pixels > 0 ? std::sqrt(sum / error.pixels) : -1.0;
    return error;
}

TEST(SkyEdges, AnOutlinePixelShowsTheSkyOverTheShareOfItTheSurfaceLeaves) {
    const EdgeError with = outline_error(true, true);
    const EdgeError centre_only = outline_error(false, false);
    const EdgeError edge_filter = outline_error(false, true);
    std::printf(
        "[ figures  ] %d outline pixels, rms error in units of (sky - surface): coverage %.3f, "
        "pixel centres %.3f, edge filter %.3f\n",
        with.pixels, with.rms, centre_only.rms, edge_filter.rms);
    EXPECT_GT(with.pixels, 20);
    // 16 sub-samples quantise the share to 1/16 in area (more along an edge in one direction).
    EXPECT_LT(with.rms, 0.12);
    EXPECT_GT(centre_only.rms, 0.25);
    EXPECT_LT(with.rms, 0.5 * edge_filter.rms);
}

TEST(SkyEdges, NoSkyNoMaskPass) {
    FurnaceView view(std::nullopt);
    renderer::FrameSettings settings = FurnaceView::settings();
    settings.wait_for_timings = true;
    renderer::FrameRenderer renderer(view.world.registry, *view.world.lighting, settings);
    const renderer::FrameTimings& timings = renderer.render(view.camera, view.world.time);
    EXPECT_EQ(timings.milliseconds[static_cast<std::size_t>(renderer::RenderPass::SkyEdges)], 0.0);
}

}  // namespace
