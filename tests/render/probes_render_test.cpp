// Irradiance probes in the frame: a crate without a light map in a prepared level is lit in
// the indirect term by shaders/render/irradiance_probes.glsl exactly as
// IrradianceProbes::irradiance says on the CPU, pixel for pixel, while the light-mapped
// surfaces around it keep their IIM; with either basis a probe can store its irradiance in.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "cube_scene.hpp"
#include "luxel/renderer/frame_renderer.hpp"
#include "luxel/scene/gltf.hpp"
#include "render_scenes.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;

constexpr int kSize = 96;
constexpr float kAlbedo = 0.5f;
const glm::vec3 kCrate(-2.0f, 0.25f, 0.0f);  // on the west room's floor
constexpr float kHalf = 0.25f;

class ProbesRender : public ::testing::TestWithParam<ProbeBasis> {};

TEST_P(ProbesRender, ACrateWithoutALightMapShowsTheProbesIrradiance) {
    const auto context = test::make_render_context();
    test::RenderWorld world;
    world::instantiate(
        world.registry,
        std::make_shared<scene::Scene>(scene::load_gltf(test::prepared_level("two-rooms"))), {});
    world.add_mesh(luxel::testing::cube_scene(kHalf, luxel::testing::diffuse_material(kAlbedo)),
                   kCrate);
    lighting::LightingConfig config = test::small_lighting_config();
    config.probes.basis = GetParam();
    world.start(config);
    world.lighting->warm_up(world.time, 1e9);
    world.update();
    ASSERT_TRUE(world.lighting->plan().irradiance_probes());
    const IrradianceProbes* probes = world.lighting->irradiance_probes();
    ASSERT_NE(probes, nullptr);

    renderer::FrameSettings settings;
    settings.width = kSize;
    settings.height = kSize;
    settings.anti_aliasing = false;
    renderer::FrameRenderer renderer(world.registry, *world.lighting, settings);
    const glm::vec3 eye = kCrate + glm::vec3(0.9f, 0.9f, 1.1f);
    const renderer::FrameCamera camera =
        renderer::FrameCamera::look_at(eye, kCrate, {0.0f, 1.0f, 0.0f}, 0.9f, 1.0f);
    renderer.render(camera, world.time);
    EXPECT_GT(renderer.counters().probe_uploads, 0u);
    const Image indirect = renderer.read(renderer::FrameImage::Indirect);
    const auto positions = test::read_texture(renderer.position_texture(), kSize, kSize);
    const auto normals = test::read_texture(renderer.normal_texture(), kSize, kSize);
    std::vector<float> errors;
    int lit = 0;
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
            const std::size_t i = static_cast<std::size_t>((kSize - 1 - y) * kSize + x);
            const glm::vec3 p(positions[i]);
            if (positions[i].w == 0.0f ||
                glm::any(glm::greaterThan(glm::abs(p - kCrate), glm::vec3(kHalf + 1e-3f)))) {
                continue;  // not the crate
            }
            const glm::vec3 expected =
                kAlbedo * probes->irradiance(p, glm::vec3(normals[i]), eye) / glm::pi<float>();
            const glm::vec3 got(indirect.pixel(x, y));
            ASSERT_TRUE(std::isfinite(got.x) && std::isfinite(got.y) && std::isfinite(got.z));
            lit += got.y > 0.0f ? 1 : 0;
            errors.push_back(glm::length(got - expected) / std::max(glm::length(expected), 1e-6f));
        }
    }
    ASSERT_GT(errors.size(), 500u) << "the crate should fill a good part of the frame";
    EXPECT_EQ(lit, static_cast<int>(errors.size())) << "every crate pixel gets indirect light";
    std::sort(errors.begin(), errors.end());
    std::printf("%zu crate pixels: median error %.4f%%, 95th percentile %.4f%%\n", errors.size(),
                100.0 * static_cast<double>(errors[errors.size() / 2]),
                100.0 * static_cast<double>(errors[errors.size() * 95 / 100]));
    // The GPU filters the tiles with its own sub-texel precision, and holds the octahedral
    // irradiance in half floats: per pixel the two agree to a fraction of a per cent, at the
    // visibility test's steep edges to a few.
    EXPECT_LT(errors[errors.size() / 2], 0.002f);  // llvmpipe: 0.03% octahedral, 0.0000% SH
    EXPECT_LT(errors[errors.size() * 95 / 100], 0.02f);
}

INSTANTIATE_TEST_SUITE_P(Bases, ProbesRender,
                         ::testing::Values(ProbeBasis::Octahedral, ProbeBasis::Sh2),
                         [](const ::testing::TestParamInfo<ProbeBasis>& basis) {
                             return basis.param == ProbeBasis::Octahedral
                                        ? std::string("Octahedral")
                                        : std::string("Sh2");
                         });

}  // namespace
