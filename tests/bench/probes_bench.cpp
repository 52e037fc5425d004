// Irradiance probes (issue 26); figures and the command that produced them are in
// docs/PERFORMANCE.md ("Irradiance probes").
//   ProbePass        IrradianceProbes::gather of 16 probes (one pass each, 256 rays, one
//        thread) on prepared/cornell, lit and its AIM built by a warm-up, against the baseline
//        CpuGatherer::gather of 16 floor texels at 256 rays each: the same number of rays
//        through the same scene and atlas. Counters: ms_per_probe, ms_per_texel,
//        ratio = probe / texel (what a probe costs beyond its rays: the irradiance map's
//        16x16 texels or the SH projection, and the 8x8 distance texels). Argument: the
//        basis, 0 octahedral (the default), 1 band-2 SH.
//   ProbeLookup      IrradianceProbes::irradiance at 4096 points of the room (the CPU twin
//        of the shader's per-pixel work), against one probe's own irradiance at the same
//        normals (the least a lookup can do). Counters: ns_per_lookup, ratio. The same
//        argument.

#include <benchmark/benchmark.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <random>
#include <vector>

#include "luxel/ecs/transform_system.hpp"
#include "luxel/lighting/core/cpu_gather.hpp"
#include "luxel/lighting/core/irradiance_probes.hpp"
#include "luxel/lighting/core/lighting_system.hpp"
#include "luxel/runtime/jobs.hpp"
#include "luxel/scene/gltf.hpp"
#include "luxel/world/scene_instance.hpp"
#include "test_paths.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

/// prepared/cornell with its lighting warmed up: the AIM the probes and the texels gather.
struct LitCornell {
    ecs::Registry registry;
    JobSystem jobs{2};
    std::unique_ptr<LightingSystem> lighting;
    LitCornell() {
        auto level = std::make_shared<scene::Scene>(
            scene::load_gltf(luxel::testing::source_dir() / "assets/levels/prepared/cornell.glb"));
        world::instantiate(registry, level);
        ecs::TransformSystem(registry).update();
        lighting = std::make_unique<LightingSystem>(registry, jobs);
        lighting->warm_up(0.0, 120000.0);
    }
};

LitCornell& cornell() {
    static LitCornell lit;
    return lit;
}

ProbeGrid room_grid(const LitCornell& lit) {
    AxisBox box;
    box.add(lit.lighting->photons().ray_scene().bounds_min());
    box.add(lit.lighting->photons().ray_scene().bounds_max());
    return fit_probe_grid(box, 0.5f, 4096);
}

IrradianceProbeSettings settings_for(const benchmark::State& state) {
    IrradianceProbeSettings settings;
    settings.basis = state.range(0) == 0 ? ProbeBasis::Octahedral : ProbeBasis::Sh2;
    return settings;
}

ProbeRayTracer tracer_of(const CpuGatherer& gatherer) {
    return [&gatherer](const glm::vec3& origin, std::span<const glm::vec3> directions,
                       std::span<ProbeRay> rays, std::uint32_t seed) {
        gatherer.trace_probe_rays(origin, directions, rays, seed);
    };
}

void ProbePass(benchmark::State& state) {
    LitCornell& lit = cornell();
    const CpuGatherer gatherer(lit.lighting->photons().ray_scene(), lit.lighting->maps().aim(),
                               {256, 1e6f});
    const ProbeRayTracer tracer = tracer_of(gatherer);
    IrradianceProbes probes(room_grid(lit), settings_for(state));
    CpuGatherer texel_gatherer(lit.lighting->photons().ray_scene(), lit.lighting->maps().aim(),
                               {256, 1e6f});
    std::vector<GatherTexel> texels;
    for (int i = 0; i < 16; ++i) {
        texels.push_back({{-0.8f + 0.1f * static_cast<float>(i), 0.01f, 0.1f}, {0, 1, 0}});
    }
    std::vector<glm::vec3> irradiance(texels.size());
    double probe_s = 0.0;
    double texel_s = 0.0;
    for (auto _ : state) {
        probes.lighting_changed();
        Clock::time_point start = Clock::now();
        benchmark::DoNotOptimize(probes.gather(16, tracer, nullptr));
        probe_s += seconds_since(start);
        start = Clock::now();
        texel_gatherer.gather(texels, irradiance);
        texel_s += seconds_since(start);
        benchmark::DoNotOptimize(irradiance.data());
    }
    const double n = static_cast<double>(state.iterations()) * 16.0;
    state.counters["ms_per_probe"] = 1e3 * probe_s / n;
    state.counters["ms_per_texel"] = 1e3 * texel_s / n;
    state.counters["ratio"] = texel_s > 0.0 ? probe_s / texel_s : 0.0;
    state.counters["probes"] = static_cast<double>(probes.probes().size());
}
BENCHMARK(ProbePass)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void ProbeLookup(benchmark::State& state) {
    LitCornell& lit = cornell();
    const CpuGatherer gatherer(lit.lighting->photons().ray_scene(), lit.lighting->maps().aim(),
                               {256, 1e6f});
    const ProbeRayTracer tracer = tracer_of(gatherer);
    IrradianceProbes probes(room_grid(lit), settings_for(state));
    while (probes.pending() > 0) {
        probes.gather(256, tracer, &lit.jobs);
    }
    const glm::vec3 lo = lit.lighting->photons().ray_scene().bounds_min();
    const glm::vec3 hi = lit.lighting->photons().ray_scene().bounds_max();
    std::mt19937 random(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<glm::vec3> points;
    std::vector<glm::vec3> normals;
    for (int i = 0; i < 4096; ++i) {
        points.push_back(glm::mix(lo, hi, glm::vec3(unit(random), unit(random), unit(random))));
        normals.push_back(glm::normalize(
            glm::vec3(unit(random), unit(random), unit(random)) * 2.0f - 1.0f + 1e-3f));
    }
    const std::size_t one = probes.probes().size() / 2;
    double lookup_s = 0.0;
    double own_s = 0.0;
    for (auto _ : state) {
        Clock::time_point start = Clock::now();
        glm::vec3 sum(0.0f);
        for (std::size_t i = 0; i < points.size(); ++i) {
            sum += probes.irradiance(points[i], normals[i]);
        }
        benchmark::DoNotOptimize(sum);
        lookup_s += seconds_since(start);
        start = Clock::now();
        glm::vec3 own_sum(0.0f);
        for (const glm::vec3& n : normals) {
            own_sum += probes.probe_irradiance(one, n);
        }
        benchmark::DoNotOptimize(own_sum);
        own_s += seconds_since(start);
    }
    const double n = static_cast<double>(state.iterations()) * static_cast<double>(points.size());
    state.counters["ns_per_lookup"] = 1e9 * lookup_s / n;
    state.counters["ns_per_probe"] = 1e9 * own_s / n;
    state.counters["ratio"] = own_s > 0.0 ? lookup_s / own_s : 0.0;
}
BENCHMARK(ProbeLookup)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
