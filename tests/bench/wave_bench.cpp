// What moving water costs per frame (issue 23): a 64 x 64 vertex surface over 2 x 2 m with a
// vertex wave from extras.luxel.wave, as in the source's wave-plane scene.
//   WaveShapeOnCpu     world::waved_mesh alone: every vertex and normal of one new shape.
//   WaveIntoRayScene   a frame of the wave: world::update_waves (a new shape, set_mesh_shape)
//                      and PhotonWorld::sync (the object's vertices moved in place and its BVH
//                      refitted, RayScene::deform). The goal: 1 ms.
//   RigidMoveBaseline  the same surface without a wave, moved as a rigid dynamic object: the
//                      TransformSystem and PhotonWorld::sync updating one instance transform.
// Ratios against the baseline measured in the same run are in docs/PERFORMANCE.md.

#include <benchmark/benchmark.h>

#include <memory>

#include <glm/gtc/quaternion.hpp>

#include "luxel/ecs/transform_system.hpp"
#include "luxel/lighting/core/photon_world.hpp"
#include "luxel/scene/components.hpp"
#include "luxel/world/scene_instance.hpp"
#include "luxel/world/vertex_wave.hpp"
#include "sheet_mesh.hpp"

namespace {

using namespace luxel;

constexpr int kSide = 64;  // vertices along each side: 4,096 in all, 7,938 triangles

/// The water: one node holding the surface, with the caustics level's wave unless `rigid`
/// (then flagged dynamic, to be moved by its transform).
std::shared_ptr<const scene::Scene> water(bool rigid) {
    auto s = std::make_shared<scene::Scene>();
    const scene::Primitive primitive =
        luxel::testing::sheet_primitive(kSide, glm::vec3(-1.0f, 0.0f, -1.0f), 2.0f);
    s->meshes.push_back({"water", {primitive}});
    s->nodes.resize(1);
    s->nodes[0].mesh = 0;
    if (rigid) {
        s->nodes[0].flags.dynamic = true;
    } else {
        s->nodes[0].flags.raw["wave"] = {
            {"amplitude", 0.02}, {"wavelength", 0.5}, {"speed", 0.4}, {"direction", {1.0, 0.3}}};
    }
    s->roots = {0};
    s->validate();
    return s;
}

void WaveShapeOnCpu(benchmark::State& state) {
    const auto scene = water(false);
    const world::WaveParameters wave = *world::read_wave(scene->nodes[0].flags.raw);
    double time = 0.0;
    for (auto _ : state) {
        time += 1.0 / 60.0;
        benchmark::DoNotOptimize(world::waved_mesh(scene->meshes[0], wave, time));
    }
    state.counters["vertices"] = kSide * kSide;
}
BENCHMARK(WaveShapeOnCpu)->Unit(benchmark::kMillisecond);

/// One frame of the water into the ray scene, per iteration: the wave steps a 60th of a
/// second, or (rigid) the node turns a little.
void frame_into_ray_scene(benchmark::State& state, bool rigid) {
    const auto scene = water(rigid);
    ecs::Registry registry;
    const world::SceneInstance instance = world::instantiate(registry, scene);
    ecs::TransformSystem transforms(registry);
    transforms.update();
    lighting::PhotonWorld photons(registry);
    photons.sync();
    float angle = 0.0f;
    for (auto _ : state) {
        if (rigid) {
            angle += 0.01f;
            registry.patch<ecs::Transform>(instance.nodes[0], [&](ecs::Transform& t) {
                t.rotation = glm::angleAxis(angle, glm::vec3(0, 1, 0));
            });
        } else {
            world::update_waves(registry, 1.0 / 60.0);
        }
        transforms.update();
        photons.sync();
    }
    state.counters["vertices"] = kSide * kSide;
}

void WaveIntoRayScene(benchmark::State& state) {
    frame_into_ray_scene(state, false);
}
BENCHMARK(WaveIntoRayScene)->Unit(benchmark::kMillisecond);

void RigidMoveBaseline(benchmark::State& state) {
    frame_into_ray_scene(state, true);
}
BENCHMARK(RigidMoveBaseline)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
