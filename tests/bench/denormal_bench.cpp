// Denormal floats, measured (issue 12). The prepared Cornell box (assets/levels/prepared/
// cornell.glb, 77 x 40 photons) twice in one process: its light at 1 W (the baseline) and at
// 1e-40 W per photon (3.1e-37 W for the 3,080 photons), so that every photon power is a
// subnormal float (below FLT_MIN = 1.2e-38). Nothing in luxel flushes subnormals: no
// FTZ/DAZ mode is set and nothing is built with -ffast-math (counter `ftz_daz` reads the
// benchmark thread's MXCSR: 0 when neither is set, 1 DAZ, 2 FTZ, 3 both). Each benchmark times
// the same work on both levels alternately within each iteration and reports
// ratio = subnormal time / baseline time; figures are in docs/PERFORMANCE.md, the command in
// docs/STABILITY.md. Not a test: nothing here asserts a speed.
//   Trace       every group of the light traced through RayScene (LightPhotons::trace_group,
//        one thread, no PhotonMap update); counter `subnormal_hops` = fraction of the traced
//        hops whose power is subnormal in the scaled level.
//   AimRebuild  IlluminationMaps::rebuild_aim of every light-mapped surface (the kd-tree and
//        the density estimate over each texel); `subnormal_texels` = fraction of the scaled
//        level's non-zero AIM values that are subnormal.
//   Gather      CpuGatherer::gather of 256 texels spread over every surface at 64 rays, one
//        thread, reading each level's own AIM; `subnormal_texels` the same for its results.

#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <vector>

#if defined(__SSE__) || defined(__x86_64__)
#include <xmmintrin.h>
#define LUXEL_HAS_MXCSR 1
#endif

#include "luxel/ecs/transform_system.hpp"
#include "luxel/lighting/components.hpp"
#include "luxel/lighting/core/cpu_gather.hpp"
#include "luxel/lighting/core/illumination_maps.hpp"
#include "luxel/lighting/core/photon_world.hpp"
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

bool subnormal(float v) {
    return std::fpclassify(v) == FP_SUBNORMAL;
}

/// FTZ (bit 15) and DAZ (bit 6) of this thread's MXCSR as 2 * FTZ + DAZ; -1 where there is none.
double flush_modes() {
#ifdef LUXEL_HAS_MXCSR
    const unsigned csr = _mm_getcsr();
    return 2.0 * static_cast<double>((csr >> 15) & 1u) + static_cast<double>((csr >> 6) & 1u);
#else
    return -1.0;
#endif
}

/// prepared/cornell with every point light's power set so that each photon carries
/// `photon_power` watts per channel, photons traced once and every AIM built.
struct PoweredLevel {
    ecs::Registry registry;
    world::SceneInstance instance;
    ecs::TransformSystem transforms{registry};
    std::unique_ptr<PhotonWorld> photons;
    std::unique_ptr<IlluminationMaps> maps;

    explicit PoweredLevel(float light_power) {
        world::InstantiateOptions options;
        options.play_animations = false;
        instance = world::instantiate(
            registry,
            std::make_shared<scene::Scene>(scene::load_gltf(
                luxel::testing::source_dir() / "assets" / "levels" / "prepared" / "cornell.glb")),
            options);
        for (auto [entity, light] : registry.view<PointLight>()) {
            light.power = glm::vec3(light_power);
        }
        transforms.update();
        JobSystem jobs(2);
        photons = std::make_unique<PhotonWorld>(registry);
        photons->sync();
        photons->probe(0, jobs);
        photons->retrace_pending(jobs);
        maps = std::make_unique<IlluminationMaps>(registry, *photons);
        maps->sync();
        for (const MapRequest& request : maps->aim_requests()) {
            maps->rebuild_aim(request.surface);
        }
    }

    [[nodiscard]] std::vector<std::uint32_t> mapped_surfaces() const {
        std::vector<std::uint32_t> out;
        for (std::uint32_t s = 0; s < maps->surfaces().size(); ++s) {
            if (!maps->surfaces()[s].texels.texels.empty()) {
                out.push_back(s);
            }
        }
        return out;
    }
};

/// The two levels, built once: light power 1 W, and 1e-40 W per photon.
struct Levels {
    std::unique_ptr<PoweredLevel> baseline;
    std::unique_ptr<PoweredLevel> scaled;
};

const Levels& levels() {
    static const Levels built = [] {
        const PhotonWorldSettings settings;
        const double photons = static_cast<double>(settings.selective.groups) *
                               static_cast<double>(settings.selective.per_group);
        Levels l;
        l.baseline = std::make_unique<PoweredLevel>(1.0f);
        l.scaled = std::make_unique<PoweredLevel>(static_cast<float>(1e-40 * photons));
        return l;
    }();
    return built;
}

/// Times `work(level)` on the baseline and the scaled level alternately; reports both.
template <typename Work>
void alternate(benchmark::State& state, Work&& work) {
    const Levels& l = levels();
    double baseline_seconds = 0.0;
    double scaled_seconds = 0.0;
    for (auto _ : state) {
        const Clock::time_point baseline_start = Clock::now();
        work(*l.baseline);
        baseline_seconds += seconds_since(baseline_start);
        const Clock::time_point scaled_start = Clock::now();
        work(*l.scaled);
        const double scaled = seconds_since(scaled_start);
        scaled_seconds += scaled;
        state.SetIterationTime(scaled);
    }
    const auto iterations = static_cast<double>(state.iterations());
    state.counters["baseline_ms"] = 1e3 * baseline_seconds / iterations;
    state.counters["subnormal_ms"] = 1e3 * scaled_seconds / iterations;
    state.counters["ratio"] = baseline_seconds > 0.0 ? scaled_seconds / baseline_seconds : 0.0;
    state.counters["ftz_daz"] = flush_modes();
}

void Trace(benchmark::State& state) {
    std::size_t hops = 0;
    std::size_t subnormal_hops = 0;
    alternate(state, [&](const PoweredLevel& level) {
        const bool scaled = &level == levels().scaled.get();
        for (const LightPhotons* light : level.photons->active_lights()) {
            for (std::uint32_t g = 0; g < light->group_count(); ++g) {
                TraceCounters counters;
                const TracedGroup traced = light->trace_group(
                    level.photons->ray_scene(), level.photons->materials(), g, counters);
                benchmark::DoNotOptimize(traced.hops.data());
                if (scaled) {
                    for (const TracedHop& hop : traced.hops) {
                        ++hops;
                        subnormal_hops += subnormal(hop.power.g) ? 1 : 0;
                    }
                }
            }
        }
    });
    state.counters["subnormal_hops"] =
        hops > 0 ? static_cast<double>(subnormal_hops) / static_cast<double>(hops) : 0.0;
}
BENCHMARK(Trace)->UseManualTime()->Unit(benchmark::kMillisecond);

/// The fraction of a level's non-zero AIM values (all channels) that are subnormal.
double subnormal_aim_fraction(const PoweredLevel& level) {
    std::size_t nonzero = 0;
    std::size_t tiny = 0;
    for (const RadiancePage& page : level.maps->aim().pages) {
        for (int y = 0; y < page.size; ++y) {
            for (int x = 0; x < page.size; ++x) {
                const glm::vec3 v = page.at(x, y);
                for (int c = 0; c < 3; ++c) {
                    nonzero += v[c] != 0.0f ? 1 : 0;
                    tiny += subnormal(v[c]) ? 1 : 0;
                }
            }
        }
    }
    return nonzero > 0 ? static_cast<double>(tiny) / static_cast<double>(nonzero) : 0.0;
}

void AimRebuild(benchmark::State& state) {
    alternate(state, [](const PoweredLevel& level) {
        for (const std::uint32_t s : level.mapped_surfaces()) {
            benchmark::DoNotOptimize(level.maps->rebuild_aim(s));
        }
    });
    state.counters["subnormal_texels"] = subnormal_aim_fraction(*levels().scaled);
}
BENCHMARK(AimRebuild)->UseManualTime()->Unit(benchmark::kMillisecond);

void Gather(benchmark::State& state) {
    constexpr std::size_t kTexels = 256;
    constexpr std::uint32_t kRays = 64;
    const auto texels_of = [&](const PoweredLevel& level) {
        std::vector<GatherTexel> all;
        for (const std::uint32_t s : level.mapped_surfaces()) {
            const std::vector<GatherTexel> texels = level.maps->world_texels(s);
            all.insert(all.end(), texels.begin(), texels.end());
        }
        std::vector<GatherTexel> picked;
        for (std::size_t i = 0; i < kTexels && !all.empty(); ++i) {
            picked.push_back(all[i * all.size() / kTexels]);
        }
        return picked;
    };
    const Levels& l = levels();
    const std::vector<GatherTexel> texels = texels_of(*l.baseline);
    CpuGatherer baseline(l.baseline->photons->ray_scene(), l.baseline->maps->aim(), {kRays, 1e6f});
    CpuGatherer scaled(l.scaled->photons->ray_scene(), l.scaled->maps->aim(), {kRays, 1e6f});
    std::vector<glm::vec3> irradiance(texels.size());
    alternate(state, [&](const PoweredLevel& level) {
        (&level == l.baseline.get() ? baseline : scaled).gather(texels, irradiance);
        benchmark::DoNotOptimize(irradiance.data());
    });
    // The last call was the scaled level's.
    std::size_t nonzero = 0;
    std::size_t tiny = 0;
    for (const glm::vec3& e : irradiance) {
        for (int c = 0; c < 3; ++c) {
            nonzero += e[c] != 0.0f ? 1 : 0;
            tiny += subnormal(e[c]) ? 1 : 0;
        }
    }
    state.counters["subnormal_texels"] =
        nonzero > 0 ? static_cast<double>(tiny) / static_cast<double>(nonzero) : 0.0;
}
BENCHMARK(Gather)->UseManualTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
