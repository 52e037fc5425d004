// Skinning in the vertex stage (FrameSettings::gpu_skinning, render/skinning.glsl): the frame
// a renderer draws from the bind mesh and the pose's joint matrices is the one it draws from
// the CPU's posed vertices (which the ray scene traces), a walk uploads the figure's vertices
// once, and the shadow maps follow the pose (the frame's direct term is compared, shadows
// included). The figure is Blender's (tests/levels/blender/skinned-figure.py): seven bones,
// weights that blend two bones at the joints, its rig moved and turned.

#include <cmath>
#include <cstdio>
#include <memory>

#include <gtest/gtest.h>

#include "luxel/renderer/frame_renderer.hpp"
#include "luxel/scene/gltf.hpp"
#include "luxel/world/animation_system.hpp"
#include "luxel/world/scene_instance.hpp"
#include "luxel/world/skinning.hpp"
#include "render_scenes.hpp"

namespace {

using namespace luxel;

constexpr int kWidth = 320;
constexpr int kHeight = 180;
// The level's own camera ("Camera" node), as in skinned_shadow_test.cpp.
const glm::vec3 kEye(0.2f, 1.9f, 4.6f);
const glm::vec3 kTarget = kEye + glm::vec3(0.0f, -0.2675f, -0.9636f);
constexpr float kFov = 0.7984f;

renderer::FrameCamera level_camera() {
    return renderer::FrameCamera::look_at(kEye, kTarget, {0.0f, 1.0f, 0.0f}, kFov,
                                          static_cast<float>(kWidth) / kHeight);
}

struct Figure {
    test::RenderWorld world;

    Figure() {
        const auto level = std::make_shared<scene::Scene>(
            scene::load_gltf(test::prepared_level("skinned-figure")));
        world::InstantiateOptions options;
        options.play_animations = true;
        world::instantiate(world.registry, level, options);
        pose(0.7);  // mid-stride: legs and arms far from the rest pose
        world.start();
        world.update(1.0, 0.0);
    }

    /// Poses the figure at `seconds` of its walk; the ray scene follows at the next update.
    void pose(double seconds) {
        world.registry.view<world::AnimationPlayer>().each(
            [&](world::AnimationPlayer& player) { player.time = seconds; });
        world::update_animations(world.registry, 0.0);
        world.transforms.update();
        ASSERT_EQ(world::update_skins(world.registry), 1u);
    }
};

renderer::FrameSettings settings_with(bool gpu_skinning) {
    renderer::FrameSettings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    settings.gpu_skinning = gpu_skinning;
    return settings;
}

/// One renderer skinning in the vertex stage and one uploading the CPU's pose, over one world.
struct BothRenderers {
    renderer::FrameRenderer gpu;
    renderer::FrameRenderer cpu;

    explicit BothRenderers(test::RenderWorld& world)
        : gpu(world.registry, *world.lighting, settings_with(true)),
          cpu(world.registry, *world.lighting, settings_with(false)) {}

    void render(const renderer::FrameCamera& camera, double time) {
        gpu.render(camera, time);
        cpu.render(camera, time);
    }
};

double relrmse(const Image& frame, const Image& reference) {
    double diff = 0.0;
    double norm = 0.0;
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            const glm::dvec3 a(glm::vec3(frame.pixel(x, y)));
            const glm::dvec3 b(glm::vec3(reference.pixel(x, y)));
            diff += glm::dot(a - b, a - b);
            norm += glm::dot(b, b);
        }
    }
    return norm > 0.0 ? std::sqrt(diff / norm) : 1e30;
}

/// Pixels whose G-buffer position differs by more than `tolerance` metres (or that one of the
/// two covers and the other does not).
int moved_pixels(const std::vector<glm::vec4>& a, const std::vector<glm::vec4>& b,
                 float tolerance) {
    int moved = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        if ((a[i].w == 0.0f) != (b[i].w == 0.0f) ||
            glm::length(glm::vec3(a[i]) - glm::vec3(b[i])) > tolerance) {
            ++moved;
        }
    }
    return moved;
}

TEST(GpuSkinning, DrawsTheFrameTheCpusPoseDraws) {
    const auto context = test::make_render_context();
    Figure figure;
    BothRenderers both(figure.world);
    renderer::FrameRenderer& gpu = both.gpu;
    renderer::FrameRenderer& cpu = both.cpu;
    both.render(level_camera(), figure.world.time);
    std::size_t joints = 0;
    figure.world.registry.view<world::SkinnedMesh>().each(
        [&](const world::SkinnedMesh& skinned) { joints += skinned.joints.size(); });
    EXPECT_EQ(joints, 7u);
    EXPECT_EQ(gpu.counters().joint_matrices, joints);
    EXPECT_EQ(cpu.counters().joint_matrices, 0u);

    const auto gpu_positions = test::read_texture(gpu.position_texture(), kWidth, kHeight);
    const auto cpu_positions = test::read_texture(cpu.position_texture(), kWidth, kHeight);
    const Image gpu_direct = gpu.read(renderer::FrameImage::Direct);
    const Image cpu_direct = cpu.read(renderer::FrameImage::Direct);
    const Image gpu_frame = gpu.read(renderer::FrameImage::Frame);
    const Image cpu_frame = cpu.read(renderer::FrameImage::Frame);

    // What the comparison can tell: the same renderer one pose earlier (the figure standing).
    figure.pose(0.0);
    figure.world.update(1.0, 0.0);
    gpu.render(level_camera(), figure.world.time);
    const auto standing = test::read_texture(gpu.position_texture(), kWidth, kHeight);

    const int differ = moved_pixels(gpu_positions, cpu_positions, 1e-3f);
    const int posed = moved_pixels(gpu_positions, standing, 1e-2f);
    const double direct_error = relrmse(gpu_direct, cpu_direct);
    const double frame_error = relrmse(gpu_frame, cpu_frame);
    std::printf(
        "[ figures  ] GPU against CPU skinning: %d of %d pixels' positions differ by > 1 mm "
        "(%d change between the two poses); direct relRMSE %.4f%%, frame %.4f%%\n",
        differ, kWidth * kHeight, posed, 100.0 * direct_error, 100.0 * frame_error);
    ASSERT_GT(posed, 500) << "the figure moves in view between the two poses";
    // Float sums in another order: a silhouette pixel may flip, nothing more.
    EXPECT_LT(differ, posed / 50);
    EXPECT_LT(direct_error, 0.01) << "the shadow maps draw the same pose";
    EXPECT_LT(frame_error, 0.01);
}

TEST(GpuSkinning, AWalkUploadsTheFiguresVerticesOnce) {
    const auto context = test::make_render_context();
    Figure figure;
    BothRenderers both(figure.world);
    renderer::FrameRenderer& gpu = both.gpu;
    renderer::FrameRenderer& cpu = both.cpu;
    both.render(level_camera(), figure.world.time);
    const std::uint64_t gpu_first = gpu.counters().mesh_uploads;
    const std::uint64_t cpu_first = cpu.counters().mesh_uploads;
    constexpr int kSteps = 6;
    for (int step = 1; step <= kSteps; ++step) {
        figure.pose(0.7 + 0.1 * step);
        figure.world.update(1.0, 0.0);
        both.render(level_camera(), figure.world.time);
    }
    EXPECT_EQ(gpu.counters().mesh_uploads, gpu_first) << "each pose: joint matrices only";
    EXPECT_EQ(cpu.counters().mesh_uploads, cpu_first + kSteps) << "each pose: its vertices";
    // The poses the CPU path uploaded are freed as the next replaces them.
    EXPECT_EQ(cpu.counters().meshes_cached, gpu.counters().meshes_cached);
}

/// A vertical 1 x 1 m square facing +z, its lower edge centred at `base`.
scene::Primitive upright_square(const glm::vec3& base) {
    scene::Primitive p;
    p.positions = {base + glm::vec3(-0.5f, 0.0f, 0.0f), base + glm::vec3(0.5f, 0.0f, 0.0f),
                   base + glm::vec3(0.5f, 1.0f, 0.0f), base + glm::vec3(-0.5f, 1.0f, 0.0f)};
    p.normals.assign(4, glm::vec3(0.0f, 0.0f, 1.0f));
    p.indices = {0, 1, 2, 0, 2, 3};
    return p;
}

// glTF lets a node without a skin draw a mesh that has joints (it draws the bind pose where
// the node stands): the renderer may then meet that mesh first, without a pose, and must still
// skin it for the node that has the skin.
TEST(GpuSkinning, AMeshAnUnskinnedNodeDrewFirstIsStillSkinned) {
    const auto context = test::make_render_context();
    auto level = std::make_shared<scene::Scene>();
    scene::Primitive square = upright_square(glm::vec3(0.0f));
    square.joints.assign(4, glm::u16vec4(0));
    square.weights.assign(4, glm::vec4(1.0f, 0.0f, 0.0f, 0.0f));
    level->meshes.push_back({"square", {square}});
    level->nodes.resize(3);
    level->nodes[0].mesh = 0;
    level->nodes[0].skin = 0;
    level->nodes[1].translation = glm::vec3(1.2f, 0.0f, 0.0f);  // the joint: 1.2 m to the right
    level->nodes[2].mesh = 0;                                   // no skin, 1 m behind
    level->nodes[2].translation = glm::vec3(0.0f, 0.0f, -1.0f);
    scene::Skin skin;
    skin.joints = {1};
    skin.inverse_bind_matrices = {glm::mat4(1.0f)};
    level->skins.push_back(skin);
    level->roots = {0, 1, 2};
    level->validate();

    test::RenderWorld world;
    world::instantiate(world.registry, level, world::InstantiateOptions{});
    ecs::Entity figure = ecs::null_entity;
    world.registry.view<world::SkinnedMesh>().each(
        [&](ecs::Entity entity, const world::SkinnedMesh&) { figure = entity; });
    ASSERT_NE(figure, ecs::null_entity);
    world.start();
    world.update(1.0, 0.0);

    const auto camera =
        renderer::FrameCamera::look_at({0.6f, 1.1f, 4.0f}, {0.6f, 1.1f, 0.0f}, {0.0f, 1.0f, 0.0f},
                                       0.9f, static_cast<float>(kWidth) / kHeight);
    BothRenderers both(world);
    renderer::FrameRenderer& gpu = both.gpu;
    renderer::FrameRenderer& cpu = both.cpu;
    // The unskinned node's entity alone first: the mesh reaches the GPU without its skin.
    const scene::MeshInstance pose = world.registry.get<scene::MeshInstance>(figure);
    world.registry.remove<scene::MeshInstance>(figure);
    gpu.render(camera, world.time);
    world.registry.emplace<scene::MeshInstance>(figure, pose);
    gpu.render(camera, world.time);
    cpu.render(camera, world.time);
    const auto a = test::read_texture(gpu.position_texture(), kWidth, kHeight);
    const auto b = test::read_texture(cpu.position_texture(), kWidth, kHeight);

    int skinned_square = 0;  // where the joint puts the skinned node's square
    int bind_square = 0;     // the unskinned node's, in its bind pose behind
    for (const glm::vec4& p : b) {
        if (p.w != 0.0f) {
            skinned_square += std::abs(p.z) < 1e-3f && p.x > 0.8f ? 1 : 0;
            bind_square += std::abs(p.z + 1.0f) < 1e-3f && p.x < 0.4f ? 1 : 0;
        }
    }
    EXPECT_GT(skinned_square, 500);
    EXPECT_GT(bind_square, 500);
    EXPECT_EQ(moved_pixels(a, b, 1e-4f), 0) << "the GPU's pose is the CPU's, pixel for pixel";
}

}  // namespace
