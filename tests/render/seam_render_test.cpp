// Light-map seams in the rendered frame (issue 22, docs/METHOD.md §6.13): cornell as luxel-prep
// prepared it has its walls, floor and ceiling cut into two surfaces each, and each surface's
// IIM gathers its own noise. The test finds every seam in the indirect term of the frame by
// projecting the seam samples, and compares the pixels a few pixels either side of the seam
// with the step between two pixels as far apart on one side of it.

#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include <gtest/gtest.h>

#include "luxel/ecs/transform.hpp"
#include "luxel/renderer/frame_renderer.hpp"
#include "luxel/scene/gltf.hpp"
#include "render_scenes.hpp"

namespace {

using namespace luxel;

constexpr int kSize = 320;
/// Pixels from the seam to each pixel compared: past the anti-aliasing and the lookups'
/// bilinear reach at cornell's texels (about 2.6 pixels each at this size), within one texel
/// row either side of the charts' edge.
constexpr float kOffset = 3.0f;

struct SeamSteps {
    double across = 0.0;  ///< RMS of (one side - the other) over RMS of their mean
    double beside = 0.0;  ///< the same for two pixels as far apart on one side
    std::size_t pixels = 0;
};

glm::vec3 rgb(const Image& image, glm::vec2 pixel) {
    const glm::vec4 v = image.pixel(static_cast<int>(pixel.x), static_cast<int>(pixel.y));
    return {v.x, v.y, v.z};
}

SeamSteps render_cornell(bool stitch) {
    auto context = test::make_render_context();
    test::RenderWorld world;
    world::InstantiateOptions options;
    options.play_animations = false;
    world::instantiate(
        world.registry,
        std::make_shared<scene::Scene>(scene::load_gltf(test::prepared_level("cornell"))), options);
    lighting::LightingConfig config = test::small_lighting_config();
    config.maps.stitch_seams = stitch;
    world.start(config);
    for (int frame = 0; frame < 3; ++frame) {
        world.update(1e9);
    }
    renderer::FrameSettings settings;
    settings.width = kSize;
    settings.height = kSize;
    settings.caustics.reset();
    renderer::FrameRenderer renderer(world.registry, *world.lighting, settings);
    renderer::FrameCamera camera;
    for (auto [entity, component] : world.registry.view<scene::CameraComponent>()) {
        const auto* placed = world.registry.try_get<ecs::WorldTransform>(entity);
        camera = renderer::FrameCamera::from_scene(
            component.camera, placed != nullptr ? placed->matrix : glm::mat4(1.0f), 1.0f);
    }
    // Seconds after the last commit, so every texel has faded in (IimPage).
    renderer.render(camera, world.time + 10.0);
    const Image indirect = renderer.read(renderer::FrameImage::Indirect);
    if (const char* out = std::getenv("LUXEL_RENDER_OUT")) {
        std::filesystem::create_directories(out);
        write_png(std::filesystem::path(out) /
                      (std::string("cornell-seams-") + (stitch ? "on" : "off") + ".png"),
                  indirect);
    }

    const glm::mat4 clip = camera.projection * camera.view;
    const glm::mat4 unclip = glm::inverse(clip);
    const auto to_pixel = [&](const glm::vec3& p, glm::vec2& pixel) {
        const glm::vec4 c = clip * glm::vec4(p, 1.0f);
        if (!(c.w > 0.0f)) {
            return false;
        }
        const glm::vec2 ndc = glm::vec2(c) / c.w;
        pixel = {(ndc.x * 0.5f + 0.5f) * kSize, (0.5f - ndc.y * 0.5f) * kSize};
        return pixel.x >= 0.0f && pixel.y >= 0.0f && pixel.x < kSize && pixel.y < kSize;
    };
    // The surface a pixel's centre sees, by a ray from the eye (-1: none).
    const lighting::RayScene& rays = world.lighting->photons().ray_scene();
    const auto seen = [&](glm::vec2 pixel) {
        pixel = glm::floor(pixel) + 0.5f;
        const glm::vec2 ndc(pixel.x / kSize * 2.0f - 1.0f, 1.0f - pixel.y / kSize * 2.0f);
        const glm::vec4 far = unclip * glm::vec4(ndc, 1.0f, 1.0f);
        const auto hit = rays.intersect(camera.position, glm::vec3(far) / far.w - camera.position);
        return hit ? hit->surface : -1;
    };

    const auto& surfaces = world.lighting->maps().surfaces();
    SeamSteps steps;
    double across = 0.0;
    double beside = 0.0;
    double level = 0.0;
    for (const lighting::SeamSample& s : world.lighting->maps().seam_samples()) {
        const glm::mat4& to_world = surfaces[s.surface_a].to_world;
        const glm::vec3 p = glm::vec3(to_world * glm::vec4(s.position, 1.0f));
        const glm::vec3 q = glm::vec3(to_world * glm::vec4(s.position + 0.01f * s.along, 1.0f));
        glm::vec2 at;
        glm::vec2 next;
        if (!to_pixel(p, at) || !to_pixel(q, next) || glm::length(next - at) < 1e-3f) {
            continue;
        }
        const glm::vec2 along = glm::normalize(next - at);
        const glm::vec2 normal(-along.y, along.x);
        const std::array<glm::vec2, 4> pixels{at - 3.0f * kOffset * normal, at - kOffset * normal,
                                              at + kOffset * normal, at + 3.0f * kOffset * normal};
        bool on_seam = true;
        for (const glm::vec2& pixel : pixels) {
            const bool inside =
                pixel.x >= 0.0f && pixel.y >= 0.0f && pixel.x < kSize && pixel.y < kSize;
            const std::int32_t surface = inside ? seen(pixel) : -1;
            on_seam = on_seam && (surface == static_cast<std::int32_t>(s.surface_a) ||
                                  surface == static_cast<std::int32_t>(s.surface_b));
        }
        if (!on_seam) {
            continue;  // hidden behind the cube or the sphere, or off the frame
        }
        const glm::dvec3 outer_a(rgb(indirect, pixels[0]));
        const glm::dvec3 a(rgb(indirect, pixels[1]));
        const glm::dvec3 b(rgb(indirect, pixels[2]));
        const glm::dvec3 outer_b(rgb(indirect, pixels[3]));
        const glm::dvec3 d = a - b;
        across += glm::dot(d, d);
        // Pixels 2 kOffset apart on one side, the same distance as a and b.
        const glm::dvec3 da = outer_a - a;
        const glm::dvec3 db = outer_b - b;
        beside += 0.5 * (glm::dot(da, da) + glm::dot(db, db));
        const glm::dvec3 m = 0.5 * (a + b);
        level += glm::dot(m, m);
        ++steps.pixels;
    }
    if (level > 0.0) {
        steps.across = std::sqrt(across / level);
        steps.beside = std::sqrt(beside / level);
    }
    return steps;
}

TEST(SeamRender, NoStepAcrossCornellsSeams) {
    const SeamSteps apart = render_cornell(false);
    const SeamSteps stitched = render_cornell(true);
    std::printf(
        "[ figures  ] cornell seams in the indirect term, %zu pixel pairs: step across "
        "%.4f without stitching, %.4f with; between pixels beside the seam %.4f / %.4f\n",
        stitched.pixels, apart.across, stitched.across, apart.beside, stitched.beside);
    ASSERT_GT(stitched.pixels, 100u) << "the seams of the back wall, floor and ceiling are in view";
    EXPECT_EQ(stitched.pixels, apart.pixels);
    // Without stitching the step across a seam stands out from the light's own gradient; with
    // it, it is no larger than the step between two pixels as far apart beside the seam.
    EXPECT_GT(apart.across, 1.5 * apart.beside);
    EXPECT_LT(stitched.across, 1.25 * stitched.beside + 0.002);
    EXPECT_LT(stitched.across, 0.6 * apart.across);
}

}  // namespace
