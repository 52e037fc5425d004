// Final-gather benchmarks: the GPU hemi-plane (HemiPlaneGatherer) against the CPU backend
// (CpuGatherer) in the same run, on the same texels, for scenes of 34, 8,800, 13,000 and
// 133,000 triangles. Figures and the command that produced them are in docs/PERFORMANCE.md.
//   HemiPlane/scene/batch   one gather() of 256 texels (a = 2, 64 x 64 pixels, its 16 horizon
//        rays per texel on the calling thread; no material table, so no specular rays) with
//        `batch` texels per submission; counters: texels/s and ms per texel. The GL renderer
//        (llvmpipe without a GPU) is the benchmark's label.
//   Cpu/scene               CpuGatherer with 1024 rays per texel on 2 job threads.
// scene: 0 = a 34-triangle box (five walls and two blocks), 1 = prepared/cornell,
// 2 = prepared/cornell-13k, 3 = prepared/cornell-133k.

#include <benchmark/benchmark.h>

#include <array>
#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "gather_scenes.hpp"
#include "luxel/lighting/core/cpu_gather.hpp"
#include "luxel/lighting/gpu/hemi_plane_gatherer.hpp"
#include "luxel/runtime/jobs.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;

constexpr std::size_t kTexels = 256;

/// What a benchmark gathers over: a scene, its atlas and texel centres.
struct Workload {
    std::unique_ptr<test::GatherLevel> level;  // null for the box
    RayScene box;
    RadianceAtlas box_atlas;
    std::vector<GatherTexel> texels;

    [[nodiscard]] const RayScene& scene() const { return level ? level->scene() : box; }
    [[nodiscard]] const RadianceAtlas& atlas() const { return level ? level->atlas : box_atlas; }
};

/// The classic 34-triangle Cornell box: five walls (the box minus its +z face) and two blocks.
std::unique_ptr<Workload> box_workload() {
    auto w = std::make_unique<Workload>();
    TriangleMesh walls = test::box_mesh(glm::vec3(-1.0f), glm::vec3(1.0f), true, 0);
    walls.positions.resize(20);
    walls.lightmap_uvs.resize(20);
    walls.indices.resize(30);
    walls.surface_ids.resize(10);
    walls.material_ids.resize(10);
    w->box.add_object(std::move(walls), glm::mat4(1.0f), false);
    w->box.add_object(test::box_mesh({-0.7f, -1.0f, -0.6f}, {-0.1f, 0.2f, 0.0f}, false, 6),
                      glm::mat4(1.0f), false);
    w->box.add_object(test::box_mesh({0.1f, -1.0f, 0.1f}, {0.7f, -0.4f, 0.7f}, false, 12),
                      glm::mat4(1.0f), false);
    w->box.commit();
    w->box_atlas = test::constant_atlas(18, glm::vec3(0.5f, 0.4f, 0.3f));
    // Texels on the floor, on a grid.
    for (std::size_t i = 0; i < kTexels; ++i) {
        const float x = -0.95f + 1.9f * static_cast<float>(i % 16) / 15.0f;
        const float z = -0.95f + 1.9f * static_cast<float>(i / 16) / 15.0f;
        w->texels.push_back({{x, -0.998f, z}, {0.0f, 1.0f, 0.0f}});
    }
    return w;
}

const Workload& workload(std::int64_t scene) {
    static std::array<std::unique_ptr<Workload>, 4> loaded;
    auto& slot = loaded.at(static_cast<std::size_t>(scene));
    if (!slot) {
        if (scene == 0) {
            slot = box_workload();
        } else {
            static const char* const names[] = {"", "prepared/cornell", "prepared/cornell-13k",
                                                "prepared/cornell-133k"};
            slot = std::make_unique<Workload>();
            slot->level = std::make_unique<test::GatherLevel>(names[scene]);
            slot->texels = slot->level->texels(kTexels);
        }
    }
    return *slot;
}

/// texels/s and ms/texel from the wall time of the whole loop (gather() returns only once the
/// sums are read back, so wall time includes all the GPU's work).
void report(benchmark::State& state, const Workload& w, std::chrono::duration<double> elapsed) {
    const double texels =
        static_cast<double>(w.texels.size()) * static_cast<double>(state.iterations());
    state.counters["texels/s"] = texels / elapsed.count();
    state.counters["ms/texel"] = 1e3 * elapsed.count() / texels;
    state.counters["triangles"] = static_cast<double>(w.scene().triangle_count());
}

GlContext& context() {
    static const std::unique_ptr<GlContext> made = test::make_gl_context();
    return *made;
}

void HemiPlane(benchmark::State& state) {
    const Workload& w = workload(state.range(0));
    GlContext& gl = context();
    HemiPlaneSettings settings;
    settings.texels_per_batch = static_cast<int>(state.range(1));
    HemiPlaneGatherer gatherer(w.scene(), w.atlas(), settings);
    std::vector<glm::vec3> e(w.texels.size());
    gatherer.gather(w.texels, e);  // uploads geometry and pages outside the timed loop
    const auto start = std::chrono::steady_clock::now();
    for (auto _ : state) {
        gatherer.gather(w.texels, e);
        benchmark::DoNotOptimize(e.data());
    }
    report(state, w, std::chrono::steady_clock::now() - start);
    state.SetLabel(gl.info().renderer);
}
BENCHMARK(HemiPlane)
    ->ArgsProduct({{0, 1, 2, 3}, {16, 64, 256, 1024}})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(0.5)
    ->UseRealTime();

void Cpu(benchmark::State& state) {
    const Workload& w = workload(state.range(0));
    JobSystem jobs(2);
    CpuGatherer gatherer(w.scene(), w.atlas(), {1024}, &jobs);
    std::vector<glm::vec3> e(w.texels.size());
    const auto start = std::chrono::steady_clock::now();
    for (auto _ : state) {
        gatherer.gather(w.texels, e);
        benchmark::DoNotOptimize(e.data());
    }
    report(state, w, std::chrono::steady_clock::now() - start);
}
BENCHMARK(Cpu)->DenseRange(0, 3)->Unit(benchmark::kMillisecond)->MinTime(0.5)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
