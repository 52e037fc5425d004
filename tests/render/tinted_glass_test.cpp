// Tinted and absorbing glass (issue 21) in the real-time frame and in the reference frame, both
// against the closed form. A backdrop emitting L (nothing else lights the scene, there is no
// sky) seen through two pieces of one glass material (ior 1.5, base colour T, attenuation
// colour c over distance d, KHR_materials_volume thickness t = d):
//   - a closed slab t thick: a view ray crosses two surfaces and t of the inside,
//       L_seen = (1 - F)^2 T^2 c^(t / d) L     (F = 0.04 near normal incidence);
//   - an open sheet (a single quad): one surface and no inside,
//       L_seen = (1 - F) T L.
// Before, the real-time frame passed (1 - F) L through both, untinted.

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "cube_scene.hpp"
#include "luxel/lighting/reference/reference_frame.hpp"
#include "luxel/lighting/reference/reference_scene.hpp"
#include "luxel/renderer/frame_renderer.hpp"
#include "luxel/scene/gltf.hpp"
#include "luxel/scene/volume.hpp"
#include "render_scenes.hpp"

namespace {

using namespace luxel;

constexpr float kRadiance = 2.0f;  // the backdrop's, W/(m^2 sr)
const glm::vec3 kTint(0.9f, 0.7f, 0.5f);
const glm::vec3 kAttenuation(0.8f, 0.9f, 0.6f);
constexpr float kThickness = 0.2f;  // metres, also the attenuation distance: c^1 through it
constexpr float kHalf = 0.6f;       // the glass pieces' half width
constexpr float kSlabX = -0.7f;     // their centres on x
constexpr float kSheetX = 0.7f;
constexpr double kF = 0.04;  // ((1.5 - 1) / (1.5 + 1))^2

/// A square in the plane z = `z` facing +z.
scene::Primitive square(const glm::vec3& centre, float half) {
    scene::Primitive p;
    p.positions = {centre + glm::vec3(-half, -half, 0), centre + glm::vec3(half, -half, 0),
                   centre + glm::vec3(half, half, 0), centre + glm::vec3(-half, half, 0)};
    p.normals.assign(4, glm::vec3(0, 0, 1));
    p.indices = {0, 1, 2, 0, 2, 3};
    return p;
}

std::shared_ptr<scene::Scene> glass_scene() {
    auto s = std::make_shared<scene::Scene>();
    scene::Material backdrop;
    backdrop.name = "backdrop";
    backdrop.base_color = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    backdrop.metallic = 0.0f;
    backdrop.emissive = glm::vec3(1.0f);
    backdrop.emissive_strength = kRadiance;
    s->materials.push_back(backdrop);
    scene::Material glass;
    glass.name = "smoked glass";
    glass.base_color = glm::vec4(kTint, 1.0f);
    glass.metallic = 0.0f;
    glass.roughness = 0.0f;
    glass.transmission = 1.0f;
    glass.ior = 1.5f;
    glass.thickness = kThickness;
    glass.attenuation_distance = kThickness;
    glass.attenuation_color = kAttenuation;
    glass.double_sided = true;
    s->materials.push_back(glass);

    scene::Primitive wall = square(glm::vec3(0.0f, 0.0f, -1.5f), 4.0f);
    wall.material = 0;
    s->meshes.push_back({"backdrop", {std::move(wall)}});
    // Four corners per face, as exporters write a box: closed only by its welded positions.
    scene::Primitive slab;
    const glm::vec3 slab_half(kHalf, kHalf, 0.5f * kThickness);
    luxel::testing::append_box(glm::vec3(kSlabX, 0.0f, 0.0f) - slab_half,
                               glm::vec3(kSlabX, 0.0f, 0.0f) + slab_half, slab.positions,
                               slab.indices);
    slab.material = 1;
    s->meshes.push_back({"slab", {std::move(slab)}});
    scene::Primitive sheet = square(glm::vec3(kSheetX, 0.0f, 0.0f), kHalf);
    sheet.material = 1;
    s->meshes.push_back({"sheet", {std::move(sheet)}});
    for (int mesh = 0; mesh < 3; ++mesh) {
        scene::Node node;
        node.name = s->meshes[static_cast<std::size_t>(mesh)].name;
        node.mesh = mesh;
        s->nodes.push_back(node);
        s->roots.push_back(mesh);
    }
    return s;
}

constexpr int kWidth = 128;
constexpr int kHeight = 64;
const glm::vec3 kEye(0.0f, 0.0f, 4.0f);
const float kFov = glm::radians(30.0f);

/// The mean of `image` over the pixels whose centre ray meets z = 0 within 0.35 m of
/// (x, 0): well inside a glass piece, away from its edges.
glm::dvec3 mean_around(const Image& image, const lighting::reference::ReferenceCamera& camera,
                       float x, int& count) {
    glm::dvec3 sum(0.0);
    count = 0;
    for (int py = 0; py < kHeight; ++py) {
        for (int px = 0; px < kWidth; ++px) {
            glm::vec3 origin;
            glm::vec3 direction;
            camera.ray(px + 0.5, py + 0.5, origin, direction);
            const glm::vec3 p = origin - direction * (origin.z / direction.z);
            if (std::abs(p.x - x) < 0.35f && std::abs(p.y) < 0.35f) {
                sum += glm::dvec3(glm::vec3(image.pixel(px, py)));
                ++count;
            }
        }
    }
    return count > 0 ? sum / static_cast<double>(count) : sum;
}

void expect_within(const glm::dvec3& got, const glm::dvec3& want, double tolerance,
                   const std::string& what) {
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(got[c], want[c], tolerance * want[c]) << what << ", channel " << c;
    }
}

TEST(TintedGlass, TheFrameAndTheReferenceTintAndAbsorbAsTheClosedFormSays) {
    auto context = test::make_render_context();
    test::RenderWorld world;
    // As a level loads: the backdrop becomes an area light, the glass caustic generators.
    world::instantiate(world.registry, glass_scene());
    world.start();
    world.update(1e9);

    const glm::dvec3 tint(kTint);
    const glm::dvec3 slab_want = (1.0 - kF) * (1.0 - kF) * tint * tint * glm::dvec3(kAttenuation) *
                                 static_cast<double>(kRadiance);
    const glm::dvec3 sheet_want = (1.0 - kF) * tint * static_cast<double>(kRadiance);

    const auto camera =
        lighting::reference::ReferenceCamera::look_at(kEye, glm::vec3(0.0f), kFov, kWidth, kHeight);
    renderer::FrameSettings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    renderer::FrameRenderer renderer(world.registry, *world.lighting, settings);
    renderer.render(renderer::FrameCamera::look_at(kEye, glm::vec3(0.0f), {0.0f, 1.0f, 0.0f}, kFov,
                                                   static_cast<float>(kWidth) / kHeight),
                    world.time);
    const Image frame = renderer.read(renderer::FrameImage::Frame);

    const lighting::reference::ReferenceScene reference_scene =
        lighting::reference::ReferenceScene::from_world(world.lighting->photons(),
                                                        world.lighting->maps());
    lighting::reference::ReferenceFrameSettings reference_settings;
    reference_settings.samples_per_pass = 16;
    lighting::reference::ReferenceFrame reference(reference_scene, camera, reference_settings);
    reference.run_pass(world.jobs);
    const Image reference_image = reference.image();

    // To look at them: LUXEL_RENDER_OUT=DIR (as the level renders of levels_test.cpp).
    if (const char* dump = std::getenv("LUXEL_RENDER_OUT")) {
        write_exr(std::string(dump) + "/tinted-glass-frame.exr", frame);
        write_exr(std::string(dump) + "/tinted-glass-reference.exr", reference_image);
    }
    int n = 0;
    const glm::dvec3 slab_frame = mean_around(frame, camera, kSlabX, n);
    ASSERT_GT(n, 200);
    const glm::dvec3 slab_reference = mean_around(reference_image, camera, kSlabX, n);
    const glm::dvec3 sheet_frame = mean_around(frame, camera, kSheetX, n);
    ASSERT_GT(n, 200);
    const glm::dvec3 sheet_reference = mean_around(reference_image, camera, kSheetX, n);
    std::printf(
        "[ figures  ] through the slab:  frame %.4f %.4f %.4f, reference %.4f %.4f %.4f, "
        "closed form %.4f %.4f %.4f\n"
        "[ figures  ] through the sheet: frame %.4f %.4f %.4f, reference %.4f %.4f %.4f, "
        "closed form %.4f %.4f %.4f\n",
        slab_frame.r, slab_frame.g, slab_frame.b, slab_reference.r, slab_reference.g,
        slab_reference.b, slab_want.r, slab_want.g, slab_want.b, sheet_frame.r, sheet_frame.g,
        sheet_frame.b, sheet_reference.r, sheet_reference.g, sheet_reference.b, sheet_want.r,
        sheet_want.g, sheet_want.b);

    // Both against the closed form: the frame's Schlick Fresnel and one thickness for every
    // pixel, the reference's paths up to 10 degrees off the normal and their internal
    // reflections, each well within 3%.
    expect_within(slab_frame, slab_want, 0.03, "the frame through the slab");
    expect_within(sheet_frame, sheet_want, 0.03, "the frame through the sheet");
    expect_within(slab_reference, slab_want, 0.03, "the reference through the slab");
    expect_within(sheet_reference, sheet_want, 0.03, "the reference through the sheet");
    // Issue 21's goal: the colour through the glass within 5% per channel of the reference.
    expect_within(slab_frame, slab_reference, 0.05, "the frame against the reference (slab)");
    expect_within(sheet_frame, sheet_reference, 0.05, "the frame against the reference (sheet)");
}

// The same material as a level designer makes it: tests/levels/blender/tinted-glass.py builds
// an amber glass cube with Blender's glTF Material Output group and a Volume Absorption, and a
// blue single-quad pane; Blender's exporter writes KHR_materials_volume for the cube only.
TEST(TintedGlass, BlendersVolumeReachesTheMaterialAndTheCubeIsClosed) {
    const scene::Scene level = scene::load_gltf(test::prepared_level("tinted-glass"));
    const scene::Material* amber = nullptr;
    const scene::Material* blue = nullptr;
    for (const scene::Material& m : level.materials) {
        amber = m.name == "amber glass" ? &m : amber;
        blue = m.name == "blue glass" ? &m : blue;
    }
    ASSERT_NE(amber, nullptr);
    ASSERT_NE(blue, nullptr);
    EXPECT_FLOAT_EQ(amber->transmission, 1.0f);
    EXPECT_NEAR(amber->thickness, 0.6f, 1e-6f);
    EXPECT_NEAR(amber->attenuation_distance, 0.6f, 1e-6f);
    EXPECT_NEAR(amber->attenuation_color.r, 0.9f, 1e-6f);
    EXPECT_NEAR(amber->attenuation_color.g, 0.75f, 1e-6f);
    EXPECT_NEAR(amber->attenuation_color.b, 0.5f, 1e-6f);
    EXPECT_TRUE(scene::absorbs_inside(*amber));
    EXPECT_FLOAT_EQ(blue->transmission, 1.0f);
    EXPECT_EQ(blue->thickness, 0.0f) << "no volume: a thin wall";
    EXPECT_FALSE(scene::absorbs_inside(*blue));

    // Which glass primitives a view ray crosses twice: the cube's, not the pane's.
    int closed = 0;
    int open = 0;
    for (const scene::Mesh& mesh : level.meshes) {
        for (const scene::Primitive& primitive : mesh.primitives) {
            if (primitive.material < 0 ||
                level.materials[static_cast<std::size_t>(primitive.material)].transmission <=
                    0.0f) {
                continue;
            }
            const bool is_closed = scene::is_closed_surface(primitive);
            EXPECT_EQ(is_closed, mesh.name == "Amber block") << mesh.name;
            (is_closed ? closed : open) += 1;
        }
    }
    EXPECT_EQ(closed, 1);
    EXPECT_EQ(open, 1);
}

}  // namespace
