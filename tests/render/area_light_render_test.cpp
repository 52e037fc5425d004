// An area light's direct light on screen: inside the `furnace` (a closed sphere of albedo rho
// emitting Le inwards) every pixel sees a wall whose radiance is Le / (1 - rho). The frame
// composes it from the emitter's own radiance (Le, the G-buffer's emission) and the light map
// (rho E / pi with E = pi Le / (1 - rho), which the gather collects from the emission and the
// AIM); without the area light's direct light in the IIM the frame would show
// Le (1 + rho^2 / (1 - rho)) = 1.5 Le instead of 2 Le at rho = 0.5.

#include <cmath>
#include <cstdio>
#include <memory>

#include <gtest/gtest.h>

#include "luxel/renderer/frame_renderer.hpp"
#include "luxel/scene/gltf.hpp"
#include "render_scenes.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;

TEST(AreaLightFrame, TheFurnaceShowsEmissionOverOneMinusAlbedoEverywhere) {
    auto context = test::make_render_context();
    constexpr float kAlbedo = 0.5f;
    constexpr double kEmitted = 1.0;  // the furnace's Le (docs/LEVELS.md)
    scene::Scene scene = scene::load_gltf(test::prepared_level("furnace"));
    scene.materials.at(0).base_color = glm::vec4(glm::vec3(kAlbedo), 1.0f);
    test::RenderWorld world;
    world::instantiate(world.registry, std::make_shared<scene::Scene>(std::move(scene)));
    LightingConfig config = test::small_lighting_config();
    config.photons.selective.groups = 77;  // the paper's 77 x 40 photons
    config.photons.selective.per_group = 40;
    config.gather.rays_per_texel = 64;
    world.start(config);
    for (int frame = 0; frame < 100 && !world.lighting->plan().census().converged; ++frame) {
        world.update(1e9);
    }
    ASSERT_TRUE(world.lighting->plan().census().converged);

    renderer::FrameSettings settings;
    settings.width = 64;
    settings.height = 48;
    renderer::FrameRenderer renderer(world.registry, *world.lighting, settings);
    // From the centre, looking along -z and then +x: each pixel sees the wall 1 m away.
    const double expected = kEmitted / (1.0 - kAlbedo);
    for (const glm::vec3 forward : {glm::vec3(0.0f, 0.0f, -1.0f), glm::vec3(1.0f, 0.0f, 0.0f)}) {
        const renderer::FrameCamera camera = renderer::FrameCamera::look_at(
            glm::vec3(0.0f), forward, glm::vec3(0.0f, 1.0f, 0.0f), 1.2f, 64.0f / 48.0f);
        // The IIM fades in over blend_seconds: render long after the last commit.
        renderer.render(camera, world.time + 1e3);
        const Image frame = renderer.read(renderer::FrameImage::Frame);
        double sum = 0.0;
        double lowest = 1e30;
        double highest = 0.0;
        std::size_t pixels = 0;
        for (std::size_t i = 0; i + 3 < frame.rgba.size(); i += 4) {
            const double g = frame.rgba[i + 1];
            ASSERT_TRUE(std::isfinite(g));
            sum += g;
            lowest = std::min(lowest, g);
            highest = std::max(highest, g);
            ++pixels;
        }
        const double mean = sum / static_cast<double>(pixels);
        std::printf(
            "[ figures  ] furnace rho %.2f looking (%g, %g, %g): mean L %.4f, expected "
            "%.4f (%+.2f%%), range %.4f .. %.4f\n",
            kAlbedo, forward.x, forward.y, forward.z, mean, expected,
            100.0 * (mean / expected - 1.0), lowest, highest);
        // Half of L is the exact emission; the other half is the light map, whose mean carries
        // the AIM's photon noise (1 / sqrt(3080) = 1.8%) seen through a 64-ray gather and the
        // 2-texel filter. 3% on the mean is over 3 sigma of the light-map half's noise, and
        // single pixels get the same (measured: every pixel within 0.5%).
        EXPECT_NEAR(mean / expected, 1.0, 0.03);
        EXPECT_GT(lowest, 0.97 * expected);
        EXPECT_LT(highest, 1.03 * expected);
    }
}

}  // namespace
