// Every built-in prepared level, rendered from its own camera after a few lighting updates
// while its animations play: no NaN, Inf or negative value in any term of any frame, and the
// frame is not black.

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include <gtest/gtest.h>

#include "luxel/ecs/transform.hpp"
#include "luxel/renderer/frame_renderer.hpp"
#include "luxel/scene/gltf.hpp"
#include "luxel/world/animation_system.hpp"
#include "render_scenes.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;

// LUXEL_RENDER_OUT=<dir> writes each level's last frame and its terms as PNG (larger, for a
// person to look at); the check is the same.
const char* output_dir() {
    return std::getenv("LUXEL_RENDER_OUT");
}
const int kWidth = output_dir() != nullptr ? 480 : 96;
const int kHeight = output_dir() != nullptr ? 360 : 72;

renderer::FrameCamera level_camera(ecs::Registry& registry) {
    return test::level_camera(registry, static_cast<float>(kWidth) / static_cast<float>(kHeight));
}

/// Checks every value; returns the sum of the rgb values.
double check_image(const Image& image, const std::string& what) {
    double sum = 0.0;
    int bad = 0;
    for (std::size_t i = 0; i < image.rgba.size(); ++i) {
        const float v = image.rgba[i];
        if (!std::isfinite(v) || v < 0.0f) {
            if (++bad <= 5) {
                ADD_FAILURE() << what << ": value " << v << " at pixel " << i / 4 << " channel "
                              << i % 4;
            }
        } else if (i % 4 != 3) {
            sum += v;
        }
    }
    EXPECT_EQ(bad, 0) << what;
    return sum;
}

class BuiltInLevels : public ::testing::TestWithParam<std::string> {
  protected:
    void SetUp() override { context_ = test::make_render_context(); }
    void TearDown() override { context_.reset(); }
    std::unique_ptr<GlContext> context_;
};

TEST_P(BuiltInLevels, FramesHoldNoNanInfOrNegative) {
    test::RenderWorld world;
    world::InstantiateOptions options;
    options.play_animations = true;
    world::instantiate(
        world.registry,
        std::make_shared<scene::Scene>(scene::load_gltf(test::prepared_level(GetParam()))),
        options);
    world.start();
    renderer::FrameSettings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    settings.cube_shadow_size = 128;
    settings.map_shadow_size = 256;
    settings.specular_cube_size = 32;
    settings.specular_faces_per_frame = 2;
    renderer::FrameRenderer renderer(world.registry, *world.lighting, settings);
    for (int frame = 0; frame < 4; ++frame) {
        const double dt = 1.0 / 30.0;
        world::update_animations(world.registry, dt);
        world.update(frame == 0 ? 1e9 : 50.0, dt);
        renderer.render(level_camera(world.registry), world.time);
        const std::string what = GetParam() + " frame " + std::to_string(frame);
        const double total =
            check_image(renderer.read(renderer::FrameImage::Frame), what + " frame");
        check_image(renderer.read(renderer::FrameImage::Direct), what + " direct");
        check_image(renderer.read(renderer::FrameImage::Indirect), what + " indirect");
        check_image(renderer.read(renderer::FrameImage::Specular), what + " specular");
        EXPECT_GT(total, 0.0) << what << ": a lit level renders black";
    }
    if (output_dir() != nullptr) {
        const std::filesystem::path dir(output_dir());
        std::filesystem::create_directories(dir);
        write_png(dir / (GetParam() + ".png"), renderer.read(renderer::FrameImage::Frame));
        write_png(dir / (GetParam() + "-direct.png"), renderer.read(renderer::FrameImage::Direct));
        write_png(dir / (GetParam() + "-indirect.png"),
                  renderer.read(renderer::FrameImage::Indirect));
        write_png(dir / (GetParam() + "-specular.png"),
                  renderer.read(renderer::FrameImage::Specular));
    }
    // The renderer makes its caustic pass exactly while the plan has caustic data, and none
    // when the settings ask for none.
    EXPECT_EQ(renderer.caustic_pass() != nullptr, world.lighting->plan().caustic_data())
        << GetParam();
    renderer::FrameSettings no_caustics = settings;
    no_caustics.caustics.reset();
    renderer::FrameRenderer bare(world.registry, *world.lighting, no_caustics);
    bare.render(level_camera(world.registry), world.time);
    EXPECT_EQ(bare.caustic_pass(), nullptr);

    const renderer::FrameCounters& counters = renderer.counters();
    EXPECT_EQ(counters.shadow_maps, counters.lights) << "one shadow map per enabled light";
    EXPECT_EQ(counters.draws_over_fill_budget, 0u)
        << "a real level covers each view a few times over, far within the fill budget";
    if (world.lighting->plan().specular()) {
        EXPECT_GT(counters.specular_cube_maps, 0u) << "specular materials get cube maps";
    }
    std::printf("[ figures  ] %s: %zu lights, %zu shadow maps, %zu probes, %zu draws\n",
                GetParam().c_str(), counters.lights, counters.shadow_maps,
                counters.specular_cube_maps, counters.draws);
}

TEST(RenderStability, ACameraInsideAWallRendersFiniteFrames) {
    // Issue 12: the camera inside the Cornell box's back wall (z = -1), and exactly on it,
    // looking along it and through it: what it sees is the backs of faces and the room beyond;
    // nothing may be NaN, infinite or negative.
    auto context = test::make_render_context();
    test::RenderWorld world;
    world::instantiate(world.registry, std::make_shared<scene::Scene>(
                                           scene::load_gltf(test::prepared_level("cornell"))));
    world.start();
    world.update(1e9);
    renderer::FrameSettings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    settings.cube_shadow_size = 128;
    settings.map_shadow_size = 256;
    settings.specular_cube_size = 32;
    renderer::FrameRenderer renderer(world.registry, *world.lighting, settings);
    const float aspect = static_cast<float>(kWidth) / static_cast<float>(kHeight);
    const struct {
        glm::vec3 eye;
        glm::vec3 target;
    } views[] = {{{0.0f, 1.0f, -1.02f}, {0.0f, 1.0f, 0.0f}},     // behind the wall, looking in
                 {{0.0f, 1.0f, -1.0f}, {0.0f, 1.0f, 1.0f}},      // exactly in its plane
                 {{0.3f, 1.0f, -1.0f}, {1.0f, 1.0f, -1.0f}},     // along it
                 {{0.0f, 1.0f, -1.001f}, {0.0f, 1.0f, -3.0f}}};  // out of the box
    for (const auto& view : views) {
        renderer.render(renderer::FrameCamera::look_at(view.eye, view.target, {0.0f, 1.0f, 0.0f},
                                                       1.0f, aspect, 0.001f, 100.0f),
                        world.time);
        check_image(renderer.read(renderer::FrameImage::Frame), "camera in the wall");
    }
}

INSTANTIATE_TEST_SUITE_P(Prepared, BuiltInLevels, ::testing::ValuesIn(test::prepared_levels()),
                         [](const ::testing::TestParamInfo<std::string>& level) {
                             std::string name = level.param;
                             for (char& c : name) {
                                 c = std::isalnum(static_cast<unsigned char>(c)) != 0 ? c : '_';
                             }
                             return name;
                         });

}  // namespace
