// Caustic filter benchmark (issue 9; the paper's figures, docs/METHOD.md §7.5: 37.6 ms untiled
// full screen, 0.38 ms for 1% of 512 x 512). A 512 x 512 frame of a plane facing the camera;
// 20,000 caustic photons at random pixel centres of a centred square covering `coverage`
// percent of the frame. One iteration is one CausticPass::render() and glFinish.
//   CausticFilter/<coverage %>/<mode>   mode 0 = Full (untiled), 1 = EarlyOut, 2 = Indirect
// The reported time is the filter's GPU time (GL_TIME_ELAPSED: tile compaction + filter);
// counters: splat_ms (clears + splat), wall_ms (render + glFinish), tiles filtered.

#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "caustic_test_support.hpp"
#include "luxel/lighting/gpu/caustic_kernel.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;

constexpr glm::ivec2 kSize(512, 512);

struct Frame {
    std::unique_ptr<GlContext> context = test::make_caustic_gl_context();
    test::RectScene scene{test::look_at({0, 0, 3}, {0, 0, 0}, kSize),
                          {{{0, 0, 0}, {5, 0, 0}, {0, 5, 0}}}};
};

Frame& frame() {
    static Frame f;
    return f;
}

std::vector<CausticPhoton> photons_covering(const test::RectScene& scene, double percent) {
    const int side =
        std::min(kSize.x, static_cast<int>(std::lround(kSize.x * std::sqrt(percent / 100.0))));
    const int lo = (kSize.x - side) / 2;
    std::mt19937 random(7);
    std::uniform_int_distribution<int> pick(lo, lo + side - 1);
    // Each photon's footprint (the ray-differential kernel's disc) as the photon differential
    // would give it: its share of the square's area on the plane.
    constexpr int kPhotons = 20'000;
    const double pixel_area = caustic_pixel_area(scene.camera(), 3.0);
    const double share = static_cast<double>(side) * side * pixel_area / kPhotons;
    const std::uint32_t footprint =
        encode_footprint_radius(static_cast<float>(std::sqrt(share / 3.14159265358979)));
    std::vector<CausticPhoton> photons;
    for (int i = 0; i < kPhotons; ++i) {
        if (const auto p = scene.hit(pick(random), pick(random))) {
            CausticPhoton photon;
            photon.position = *p;
            photon.power = glm::vec3(1e-4f);
            photon.footprint = footprint;
            photons.push_back(photon);
        }
    }
    return photons;
}

void CausticFilter(benchmark::State& state) {
    Frame& f = frame();
    CausticPassSettings settings;
    settings.tile_mode = static_cast<CausticTileMode>(state.range(1));
    CausticPass pass(settings, kSize);
    pass.upload(photons_covering(f.scene, static_cast<double>(state.range(0))));
    double splat_ms = 0.0;
    double wall_ms = 0.0;
    std::uint32_t filtered = 0;
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        pass.render(f.scene.camera(), f.scene.depth_texture().id());
        glFinish();
        const auto end = std::chrono::steady_clock::now();
        const CausticPassStats& stats = pass.stats();
        state.SetIterationTime(stats.filter_ms * 1e-3);
        splat_ms += stats.splat_ms;
        wall_ms += std::chrono::duration<double, std::milli>(end - start).count();
        filtered = stats.tiles_filtered;
    }
    const auto n = static_cast<double>(state.iterations());
    state.counters["splat_ms"] = splat_ms / n;
    state.counters["wall_ms"] = wall_ms / n;
    state.counters["tiles_filtered"] = filtered;
    state.SetLabel(reinterpret_cast<const char*>(glGetString(GL_RENDERER)));
}

BENCHMARK(CausticFilter)
    ->ArgsProduct({{1, 5, 100}, {0, 1, 2}})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);

// CausticKernelCost/<coverage %>/<kernel>: the same frame through Larsen's kernel (0, the
// baseline, in its default Indirect tile mode), the level-adjusted mip-maps (1, every tile,
// the mip chain's generation included) and the ray-differential footprints (2: a quad per
// photon, the work in the splat); the time is the whole pass's, splat and filter, and each
// kernel / Larsen is docs/PERFORMANCE.md's figure. One render before timing: the first pays
// the driver's shader compilation (luxel-bench's caustic_gpu_ms with one checkpoint measured
// that, not the pass).
void CausticKernelCost(benchmark::State& state) {
    Frame& f = frame();
    CausticPassSettings settings;
    constexpr CausticKernel kKernels[] = {CausticKernel::Larsen, CausticKernel::MipLevels,
                                          CausticKernel::PhotonFootprints};
    settings.kernel = kKernels[state.range(1)];
    CausticPass pass(settings, kSize);
    pass.upload(photons_covering(f.scene, static_cast<double>(state.range(0))));
    pass.render(f.scene.camera(), f.scene.depth_texture().id());
    glFinish();
    double splat_ms = 0.0;
    for (auto _ : state) {
        pass.render(f.scene.camera(), f.scene.depth_texture().id());
        glFinish();
        const CausticPassStats& stats = pass.stats();
        state.SetIterationTime((stats.splat_ms + stats.filter_ms) * 1e-3);
        splat_ms += stats.splat_ms;
    }
    state.counters["splat_ms"] = splat_ms / static_cast<double>(state.iterations());
    state.SetLabel(kernel_name(settings.kernel));
}

BENCHMARK(CausticKernelCost)
    ->ArgsProduct({{5, 100}, {0, 1, 2}})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);

}  // namespace

BENCHMARK_MAIN();
