// The sky in the reflections (issue 20): a specular cube map's faces show the sky behind the
// level, as the frame's background does. A white mirror (F0 = 1, so Fresnel is 1 at every
// angle) reflects exactly the radiance along the reflected ray: facing up under a uniform sky
// of radiance L it shows L; facing down it shows the sky's ground below the horizon, rho L;
// without a sky it shows nothing.

#include <algorithm>
#include <cstdio>
#include <memory>
#include <optional>

#include <gtest/gtest.h>

#include "luxel/renderer/frame_renderer.hpp"
#include "luxel/world/sky.hpp"
#include "render_scenes.hpp"

namespace {

using namespace luxel;

constexpr int kSize = 48;

struct Reflection {
    int pixels = 0;  ///< the mirror's pixels
    glm::dvec3 mean{0.0};
    double worst = 0.0;      ///< largest |shown - expected| / |expected| over the mirror's pixels
    double brightest = 0.0;  ///< the specular term's largest value over the whole frame
};

/// Renders a 2 x 2 m white mirror at height `height` facing up (or down) from an eye 1.5 m
/// off its plane, and compares its specular term with `expected`.
Reflection reflect(const std::optional<scene::SkySpec>& sky, bool facing_up,
                   const glm::vec3& expected) {
    auto context = test::make_render_context();
    test::RenderWorld world;
    const float height = facing_up ? 0.0f : 3.0f;
    auto mirror = test::single_mesh_scene(
        test::horizontal_square(glm::vec3(0.0f, height, 0.0f), 1.0f, facing_up), glm::vec3(1.0f));
    mirror->materials[0].metallic = 1.0f;
    mirror->materials[0].roughness = 0.0f;
    world.add_mesh(mirror);
    if (sky) {
        world::add_sky(world.registry, *mirror, *sky);
    }
    world.start();
    world.update(1e9);
    renderer::FrameSettings settings;
    settings.width = kSize;
    settings.height = kSize;
    settings.specular_cube_size = 32;
    renderer::FrameRenderer renderer(world.registry, *world.lighting, settings);
    const glm::vec3 eye(0.0f, 1.5f, 2.5f);
    const renderer::FrameCamera camera = renderer::FrameCamera::look_at(
        eye, glm::vec3(0.0f, height, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f), 0.9f, 1.0f);
    renderer.render(camera, world.time);
    const Image specular = renderer.read(renderer::FrameImage::Specular);
    // Alpha 1 where a specular material is: the mirror's pixels.
    const Image albedo = renderer.read(renderer::FrameImage::Albedo);
    Reflection out;
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
            const glm::vec4 term = specular.pixel(x, y);
            out.brightest =
                std::max(out.brightest, static_cast<double>(std::max({term.r, term.g, term.b})));
            if (albedo.pixel(x, y).w < 0.5f) {
                continue;  // not the mirror
            }
            const glm::vec3 shown(specular.pixel(x, y));
            ++out.pixels;
            out.mean += glm::dvec3(shown);
            const double scale = std::max(static_cast<double>(glm::length(expected)), 1e-6);
            out.worst =
                std::max(out.worst, static_cast<double>(glm::length(shown - expected)) / scale);
        }
    }
    if (out.pixels > 0) {
        out.mean /= static_cast<double>(out.pixels);
    }
    return out;
}

TEST(SkyReflection, AMirrorFacingUpShowsTheSky) {
    const glm::vec3 radiance(0.25f, 0.5f, 1.0f);
    const Reflection up =
        reflect(scene::parse_sky("uniform:0.25,0.5,1,ground=0.5"), true, radiance);
    std::printf("[ figures  ] mirror facing up: %d pixels, mean %.4f %.4f %.4f, worst %.2e\n",
                up.pixels, up.mean.r, up.mean.g, up.mean.b, up.worst);
    EXPECT_GT(up.pixels, 200);
    EXPECT_LT(up.worst, 1e-3);
}

TEST(SkyReflection, AMirrorFacingDownShowsTheGround) {
    const glm::vec3 ground = 0.5f * glm::vec3(0.25f, 0.5f, 1.0f);  // rho L
    const Reflection down =
        reflect(scene::parse_sky("uniform:0.25,0.5,1,ground=0.5"), false, ground);
    std::printf("[ figures  ] mirror facing down: %d pixels, mean %.4f %.4f %.4f, worst %.2e\n",
                down.pixels, down.mean.r, down.mean.g, down.mean.b, down.worst);
    EXPECT_GT(down.pixels, 200);
    EXPECT_LT(down.worst, 1e-3);
}

TEST(SkyReflection, WithoutASkyTheMirrorShowsNothing) {
    // Nothing lights the level, so the specular pass is left out (FeaturePlan) and the term
    // is black everywhere.
    const Reflection none = reflect(std::nullopt, true, glm::vec3(0.0f));
    EXPECT_EQ(none.brightest, 0.0);
}

}  // namespace
