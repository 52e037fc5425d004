// The reference frame reads base-colour textures per hit (lighting/reference HitTextures), as
// the renderer draws them: a floor with a 2 x 2 checker of 4 x 4-texel blocks (white and
// black, base-colour factor 0.8) under a point light. Inside each block's pure part (between
// its outer texels' centres, where bilinear filtering reads the block's own colour) a white
// pixel reads 0.8 E / pi and a black one nothing; before, every pixel read the texture's mean
// (0.4 E / pi).

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "luxel/ecs/registry.hpp"
#include "luxel/ecs/transform.hpp"
#include "luxel/ecs/transform_system.hpp"
#include "luxel/lighting/components.hpp"
#include "luxel/lighting/core/illumination_maps.hpp"
#include "luxel/lighting/core/photon_world.hpp"
#include "luxel/lighting/reference/hit_textures.hpp"
#include "luxel/lighting/reference/reference_frame.hpp"
#include "luxel/lighting/reference/reference_scene.hpp"
#include "luxel/runtime/jobs.hpp"
#include "luxel/scene/components.hpp"
#include "luxel/scene/texture_mean.hpp"

#include <stb_image_write.h>

namespace {

using namespace luxel;
using namespace luxel::lighting;
using namespace luxel::lighting::reference;

constexpr float kHalf = 1.0f;  // the floor spans 2 x 2 m; UV [0, 1] over it: 1 m blocks
constexpr float kFactor = 0.8f;
const glm::vec3 kLight(0.0f, 1.5f, 0.0f);
constexpr float kPower = 60.0f;

/// Whether block (bx, by) of the checker is white.
bool white_block(int bx, int by) {
    return (bx + by) % 2 == 0;
}

std::vector<std::uint8_t> checker_png() {
    constexpr int kEdge = 8;
    std::vector<std::uint8_t> rgba(kEdge * kEdge * 4, 255);
    for (int y = 0; y < kEdge; ++y) {
        for (int x = 0; x < kEdge; ++x) {
            const std::uint8_t value = white_block(x / 4, y / 4) ? 255 : 0;
            for (int c = 0; c < 3; ++c) {
                rgba[static_cast<std::size_t>((y * kEdge + x) * 4 + c)] = value;
            }
        }
    }
    std::vector<std::uint8_t> bytes;
    const auto append = [](void* context, void* data, int size) {
        auto* out = static_cast<std::vector<std::uint8_t>*>(context);
        const auto* first = static_cast<const std::uint8_t*>(data);
        out->insert(out->end(), first, first + size);
    };
    EXPECT_NE(stbi_write_png_to_func(append, &bytes, kEdge, kEdge, 4, rgba.data(), kEdge * 4), 0);
    return bytes;
}

std::shared_ptr<scene::Scene> textured_floor() {
    auto result = std::make_shared<scene::Scene>();
    result->images.push_back({"checker", "image/png", checker_png()});
    scene::Material material;
    material.base_color = glm::vec4(kFactor, kFactor, kFactor, 1.0f);
    material.metallic = 0.0f;
    material.base_color_image = 0;
    result->materials.push_back(material);
    scene::Primitive p;
    p.positions = {
        {-kHalf, 0.0f, -kHalf}, {kHalf, 0.0f, -kHalf}, {kHalf, 0.0f, kHalf}, {-kHalf, 0.0f, kHalf}};
    p.normals.assign(4, glm::vec3(0.0f, 1.0f, 0.0f));
    p.texcoords0 = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    p.indices = {0, 2, 1, 0, 3, 2};
    p.material = 0;
    result->meshes.push_back({"floor", {std::move(p)}});
    return result;
}

TEST(HitTextures, TheReferenceFrameShowsTheBaseColourTexturePerPixel) {
    ecs::Registry registry;
    const ecs::Entity floor = registry.create();
    registry.emplace<scene::MeshInstance>(floor, textured_floor(), 0);
    registry.emplace<ecs::Transform>(floor, glm::vec3(0.0f));
    const ecs::Entity light = registry.create();
    registry.emplace<PointLight>(light, glm::vec3(kPower), 0.0f, true);
    registry.emplace<ecs::Transform>(light, kLight);
    ecs::TransformSystem(registry).update();
    PhotonWorldSettings settings;
    settings.caustics.photons_per_pair = 0;
    PhotonWorld world(registry, settings);
    world.sync();
    IlluminationMaps maps(registry, world);
    maps.sync();
    const ReferenceScene scene = ReferenceScene::from_world(world, maps);
    ASSERT_TRUE(scene.textured());

    constexpr int kPixels = 48;
    ReferenceFrameSettings frame_settings;
    frame_settings.samples_per_pass = 4;
    frame_settings.paths.max_vertices = 1;  // direct light only: E is closed-form
    const glm::vec3 eye(0.0f, 3.0f, 0.001f);
    ReferenceFrame frame(
        scene,
        ReferenceCamera::look_at(eye, glm::vec3(0.0f), glm::radians(40.0f), kPixels, kPixels),
        frame_settings);
    JobSystem jobs(2);
    frame.run_pass(jobs);
    const Image image = frame.image();

    int white = 0;
    int black = 0;
    float worst_white = 0.0f;
    float brightest_black = 0.0f;
    const float intensity = kPower / (4.0f * glm::pi<float>());
    for (int y = 0; y < kPixels; ++y) {
        for (int x = 0; x < kPixels; ++x) {
            // The floor point under the pixel's centre.
            glm::vec3 origin;
            glm::vec3 direction;
            frame.camera().ray(x + 0.5, y + 0.5, origin, direction);
            if (!(direction.y < 0.0f)) {
                continue;
            }
            const glm::vec3 p = origin - direction * (origin.y / direction.y);
            const glm::vec2 uv((p.x + kHalf) / (2.0f * kHalf), (p.z + kHalf) / (2.0f * kHalf));
            // A block's pure part, with a margin for the pixel's footprint (~4 cm).
            const glm::vec2 in_block = uv * 2.0f - glm::floor(uv * 2.0f);
            if (uv.x <= 0.0f || uv.y <= 0.0f || uv.x >= 1.0f || uv.y >= 1.0f ||
                glm::any(glm::lessThan(in_block, glm::vec2(0.19f))) ||
                glm::any(glm::greaterThan(in_block, glm::vec2(0.81f)))) {
                continue;
            }
            const glm::vec3 to_light = kLight - p;
            const float d2 = glm::dot(to_light, to_light);
            const float e = intensity * (to_light.y / std::sqrt(d2)) / d2;
            const float lit = kFactor * e / glm::pi<float>();
            const float got = image.pixel(x, y).g;
            if (white_block(static_cast<int>(uv.x * 2.0f), static_cast<int>(uv.y * 2.0f))) {
                ++white;
                worst_white = std::max(worst_white, std::abs(got - lit) / lit);
            } else {
                ++black;
                brightest_black = std::max(brightest_black, got / lit);
            }
        }
    }
    EXPECT_GT(white, 100);
    EXPECT_GT(black, 100);
    EXPECT_LT(worst_white, 0.05f) << "white blocks read factor x E / pi";
    EXPECT_LT(brightest_black, 0.01f) << "black blocks read nothing, not the texture's mean";
    std::printf(
        "[ figures  ] textured floor: %d white pixels within %.2f%%, %d black pixels at "
        "most %.3f of white\n",
        white, 100.0f * worst_white, black, brightest_black);
}

// LinearImage::bilinear as a GL sampler reads with LINEAR and REPEAT: texel centres exactly,
// halfway between two texels their mean, across the wrap the first and last texels' mean.
TEST(HitTextures, BilinearReadsAsAGlSamplerWithRepeat) {
    const scene::LinearImage image(2, 1, {glm::vec3(0.0f), glm::vec3(1.0f)});
    EXPECT_FLOAT_EQ(image.bilinear({0.25f, 0.5f}).x, 0.0f);
    EXPECT_FLOAT_EQ(image.bilinear({0.75f, 0.5f}).x, 1.0f);
    EXPECT_FLOAT_EQ(image.bilinear({0.5f, 0.5f}).x, 0.5f);
    EXPECT_FLOAT_EQ(image.bilinear({0.0f, 0.5f}).x, 0.5f);  // the wrap: texel 1 and texel 0
    EXPECT_FLOAT_EQ(image.bilinear({1.75f, 0.5f}).x, 1.0f);
    EXPECT_FLOAT_EQ(image.bilinear({-0.25f, 0.5f}).x, 1.0f);
    EXPECT_FLOAT_EQ(image.bilinear({1e30f, 0.5f}).x, 0.5f);  // finite and defined
    EXPECT_FLOAT_EQ(image.bilinear({std::nanf(""), 0.5f}).x, 0.5f);
}

}  // namespace
