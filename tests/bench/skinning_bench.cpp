// What a skinned figure costs per frame it moves (issue 29), on a 10,000-vertex skinned mesh: a
// 100 x 100 vertex sheet bent by four joints, every vertex blending two of them.
//   SkinOnCpu            scene::posed_mesh alone: linear blend skinning of positions and normals.
//   NewPoseIntoRayScene  a joint moves: TransformSystem, world::update_skins (skin + a new
//                        MeshInstance) and PhotonWorld::sync (the object's vertices moved in
//                        place and its BVH refitted, RayScene::deform). The goal: 1 ms.
//   RigidMoveBaseline    the same mesh unskinned, moved as a rigid dynamic object: the
//                        TransformSystem and PhotonWorld::sync updating one instance transform.
//   RaySceneRefit        the ray scene alone: new vertices by RayScene::deform, committed.
//   RaySceneRebuild      the same by removing and re-adding the object (what a new mesh costs).
// Ratios against the baselines measured in the same run are in docs/PERFORMANCE.md.

#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "luxel/ecs/transform_system.hpp"
#include "luxel/lighting/core/photon_world.hpp"
#include "luxel/lighting/core/ray_scene.hpp"
#include "luxel/scene/components.hpp"
#include "luxel/scene/skin.hpp"
#include "luxel/world/scene_instance.hpp"
#include "luxel/world/skinning.hpp"
#include "sheet_mesh.hpp"

namespace {

using namespace luxel;

constexpr int kSide = 100;  // vertices along each side of the sheet: 10,000 in all

/// The sheet in the xz plane, 2 m across, and four joints along x, each weighting the vertices
/// around it; node 0 holds the mesh (skinned unless `rigid`), nodes 1-4 are the joints.
std::shared_ptr<const scene::Scene> sheet(bool rigid) {
    auto s = std::make_shared<scene::Scene>();
    scene::Primitive primitive = luxel::testing::sheet_primitive(kSide, glm::vec3(0.0f), 2.0f);
    for (const glm::vec3& p : primitive.positions) {
        const float along = p.x / 2.0f * 3.0f;  // between joints floor(along) and the next
        const auto first = static_cast<std::uint16_t>(std::min(2.0f, along));
        const float w = along - static_cast<float>(first);
        primitive.joints.emplace_back(first, first + 1, 0, 0);
        primitive.weights.emplace_back(1.0f - w, w, 0.0f, 0.0f);
    }
    if (rigid) {
        primitive.joints.clear();
        primitive.weights.clear();
    }
    s->meshes.push_back({"sheet", {primitive}});
    s->nodes.resize(5);
    s->nodes[0].mesh = 0;
    s->nodes[0].flags.dynamic = true;
    scene::Skin skin;
    for (int j = 0; j < 4; ++j) {
        s->nodes[static_cast<std::size_t>(j + 1)].translation = glm::vec3(2.0f * j / 3.0f, 0, 0);
        skin.joints.push_back(j + 1);
        skin.inverse_bind_matrices.push_back(
            glm::translate(glm::mat4(1.0f), glm::vec3(-2.0f * j / 3.0f, 0, 0)));
    }
    if (!rigid) {
        s->nodes[0].skin = 0;
        s->skins.push_back(skin);
    }
    s->roots = {0, 1, 2, 3, 4};
    s->validate();
    return s;
}

void SkinOnCpu(benchmark::State& state) {
    const auto scene = sheet(false);
    std::vector<glm::mat4> world = scene->world_matrices();
    float angle = 0.0f;
    for (auto _ : state) {
        angle += 0.01f;
        world[4] = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(2, 0, 0)), angle,
                               glm::vec3(0, 0, 1));
        benchmark::DoNotOptimize(
            scene::posed_mesh(scene->meshes[0], scene::joint_matrices(scene->skins[0], world)));
    }
    state.counters["vertices"] = kSide * kSide;
}
BENCHMARK(SkinOnCpu)->Unit(benchmark::kMillisecond);

/// One frame's move of joint (or node) `mover` into the ray scene, per iteration.
void move_and_sync(benchmark::State& state, bool rigid) {
    const auto scene = sheet(rigid);
    ecs::Registry registry;
    const world::SceneInstance instance = world::instantiate(registry, scene);
    ecs::TransformSystem transforms(registry);
    transforms.update();
    world::update_skins(registry);
    lighting::PhotonWorld photons(registry);
    photons.sync();
    const ecs::Entity mover = instance.nodes[rigid ? 0 : 4];
    float angle = 0.0f;
    for (auto _ : state) {
        angle += 0.01f;
        registry.patch<ecs::Transform>(mover, [&](ecs::Transform& t) {
            t.rotation = glm::angleAxis(angle, glm::vec3(0, 0, 1));
        });
        transforms.update();
        world::update_skins(registry);
        photons.sync();
    }
    state.counters["vertices"] = kSide * kSide;
}

void NewPoseIntoRayScene(benchmark::State& state) {
    move_and_sync(state, false);
}
BENCHMARK(NewPoseIntoRayScene)->Unit(benchmark::kMillisecond);

void RigidMoveBaseline(benchmark::State& state) {
    move_and_sync(state, true);
}
BENCHMARK(RigidMoveBaseline)->Unit(benchmark::kMillisecond);

/// The ray scene alone: the sheet's triangles as one dynamic object, given new vertices each
/// iteration, by RayScene::deform (refit) or by removing and adding the object (rebuild).
void ray_scene_update(benchmark::State& state, bool refit) {
    const auto scene = sheet(true);
    const scene::Primitive& primitive = scene->meshes[0].primitives[0];
    lighting::TriangleMesh mesh;
    mesh.positions = primitive.positions;
    mesh.normals = primitive.normals;
    mesh.indices = primitive.indices;
    mesh.surface_ids.assign(primitive.triangle_count(), -1);
    mesh.material_ids.assign(primitive.triangle_count(), 0);
    lighting::RayScene rays;
    lighting::ObjectId object = rays.add_object(mesh, glm::mat4(1.0f), true);
    rays.commit();
    std::vector<glm::vec3> positions = mesh.positions;
    float lift = 0.0f;
    for (auto _ : state) {
        lift += 0.001f;
        for (glm::vec3& p : positions) {
            p.y = lift * p.x * p.x;  // the sheet bends a little more each frame
        }
        if (refit) {
            rays.deform(object, positions, mesh.normals);
        } else {
            rays.remove_object(object);
            mesh.positions = positions;
            object = rays.add_object(mesh, glm::mat4(1.0f), true);
        }
        rays.commit();
    }
    state.counters["triangles"] = static_cast<double>(primitive.triangle_count());
}

void RaySceneRefit(benchmark::State& state) {
    ray_scene_update(state, true);
}
BENCHMARK(RaySceneRefit)->Unit(benchmark::kMillisecond);

void RaySceneRebuild(benchmark::State& state) {
    ray_scene_update(state, false);
}
BENCHMARK(RaySceneRebuild)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
