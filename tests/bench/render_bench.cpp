// Frame renderer benchmarks: GPU time per pass (timer queries) for the prepared Cornell box at
// 512 x 512, on whatever GL the EGL context gets (llvmpipe without a GPU; the renderer string
// is the benchmark's label). Figures and the command are in the report of issue 9.
//   Frame/static      nothing moves: shadow maps and probes are not redrawn
//   Frame/moving      the light moves every frame: its cube shadow map is redrawn each frame
//   Frame/bicubic     static, light maps read through the cubic B-spline (16 texels a pixel
//                     against bilinear's 4): its indirect_ms over Frame/static's is the cost
//   Frame/sky         static under a uniform sky (the closed box hides it): the sky-edge mask
//   Frame/sky-plain   the same without the mask (FrameSettings::sky_edge_coverage false)
//   Frame/skinned-gpu Blender's skinned figure level (tests/levels/blender/skinned-figure.py),
//                     the figure posed anew before every frame (outside the timing), skinned
//                     in the vertex stage: the G-buffer, shadow maps and probes skin it
//   Frame/skinned-cpu the same, each pose's vertices skinned on the CPU and uploaded
//                     (FrameSettings::gpu_skinning false): the baseline of the row above
//   Frame/caustics    the caustics level (water, glass, brass) lit a frame before every frame
//                     (outside the timing), so its caustic photons change and the caustic
//                     layer of the light maps is redrawn; the specular pass includes that
//   Frame/caustics-no-layer the same without the renderer's caustic pass (no layer, no
//                     splat): the baseline of the row above
//   Frame/soft        static, cornell's light a sphere of 5 cm (PointLight::radius): its
//                     soft_shadows_ms is the soft shadows' cost; Frame/static the baseline
// Counters: milliseconds per frame of each pass (GPU), averaged over the iterations; for the
// skinned rows also the bytes a frame sends for the figure (vertices or joint matrices).

#include <benchmark/benchmark.h>

#include <array>
#include <memory>
#include <optional>
#include <string>

#include "luxel/ecs/transform.hpp"
#include "luxel/renderer/frame_renderer.hpp"
#include "luxel/scene/gltf.hpp"
#include "luxel/scene/sky.hpp"
#include "luxel/world/animation_system.hpp"
#include "luxel/world/skinning.hpp"
#include "render_scenes.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;

constexpr int kSize = 512;

struct Variant {
    bool moving = false;
    bool bicubic = false;
    bool sky = false;
    bool sky_edges = true;
    bool skinned = false;  ///< the skinned figure level, posed every frame
    bool gpu_skinning = true;
    bool caustics_level = false;  ///< the caustics level, lit before every frame
    bool caustic_pass = true;     ///< FrameSettings::caustics set
    float light_radius = 0.0f;    ///< the point light's sphere, m (> 0: soft shadows)
};

/// Vertices of every skinned mesh's bind pose in the registry.
std::size_t figure_vertices(ecs::Registry& registry) {
    std::size_t vertices = 0;
    registry.view<world::SkinnedMesh>().each([&](const world::SkinnedMesh& skinned) {
        for (const scene::Primitive& primitive :
             skinned.source->meshes.at(static_cast<std::size_t>(skinned.mesh)).primitives) {
            vertices += primitive.positions.size();
        }
    });
    return vertices;
}

void frame(benchmark::State& state, const Variant& variant) {
    const bool moving = variant.moving;
    const std::unique_ptr<GlContext> context = test::make_render_context();
    test::RenderWorld world;
    world::instantiate(
        world.registry,
        std::make_shared<scene::Scene>(
            scene::load_gltf(test::prepared_level(variant.skinned          ? "skinned-figure"
                                                  : variant.caustics_level ? "caustics"
                                                                           : "cornell"))),
        world::InstantiateOptions{
            .play_animations = variant.skinned,
            .sky = variant.sky ? std::optional<scene::SkySpec>(scene::parse_sky("uniform:1,1,1"))
                               : std::nullopt});
    world.start();
    // Lit and gathered, so every pass has its real input.
    for (int i = 0; i < 20; ++i) {
        world.update();
    }
    ecs::Entity light;
    renderer::FrameCamera camera;
    for (auto [entity, component] : world.registry.view<scene::CameraComponent>()) {
        camera = renderer::FrameCamera::from_scene(
            component.camera, world.registry.get<ecs::WorldTransform>(entity).matrix, 1.0f);
    }
    for (auto [entity, point] : world.registry.view<PointLight>()) {
        light = entity;
    }
    if (variant.light_radius > 0.0f) {
        world.registry.patch<PointLight>(
            light, [&](PointLight& point) { point.radius = variant.light_radius; });
    }
    renderer::FrameSettings settings;
    settings.width = kSize;
    settings.height = kSize;
    settings.wait_for_timings = true;
    settings.bicubic_light_maps = variant.bicubic;
    settings.sky_edge_coverage = variant.sky_edges;
    settings.gpu_skinning = variant.gpu_skinning;
    if (!variant.caustic_pass) {
        settings.caustics.reset();
    }
    renderer::FrameRenderer renderer(world.registry, *world.lighting, settings);
    renderer.render(camera, world.time);  // allocations and first shadow maps out of the loop

    std::array<double, renderer::kRenderPassCount> sums{};
    double total = 0.0;
    float offset = 0.01f;
    std::uint64_t first_uploads = renderer.counters().mesh_uploads;
    for (auto _ : state) {
        if (variant.skinned) {
            state.PauseTiming();
            world::update_animations(world.registry, 1.0 / 60.0);
            world.transforms.update();
            world::update_skins(world.registry);
            state.ResumeTiming();
        }
        if (variant.caustics_level) {
            state.PauseTiming();
            world.update(4.0);  // a 4 ms frame of lighting: caustic slices land
            state.ResumeTiming();
        }
        if (moving) {
            world.registry.patch<ecs::Transform>(
                light, [&](ecs::Transform& t) { t.translation.x += offset; });
            offset = -offset;
            world.transforms.update();
        }
        const renderer::FrameTimings& timings = renderer.render(camera, world.time);
        for (std::size_t pass = 0; pass < renderer::kRenderPassCount; ++pass) {
            sums[pass] += timings.milliseconds[pass];
        }
        total += timings.total();
    }
    for (std::size_t pass = 0; pass < renderer::kRenderPassCount; ++pass) {
        state.counters[std::string(name(static_cast<renderer::RenderPass>(pass))) + "_ms"] =
            benchmark::Counter(sums[pass], benchmark::Counter::kAvgIterations);
    }
    state.counters["gpu_total_ms"] = benchmark::Counter(total, benchmark::Counter::kAvgIterations);
    state.counters["shadow_maps_drawn"] =
        static_cast<double>(renderer.counters().shadow_maps_drawn);
    if (variant.skinned) {
        // What the bus carries for the figure each frame: its pose's vertices (40 bytes each,
        // counted from the uploads) or its joint matrices (64 bytes each).
        const double vertex_bytes = 40.0 * static_cast<double>(figure_vertices(world.registry));
        const double uploads =
            static_cast<double>(renderer.counters().mesh_uploads - first_uploads);
        const double joint_bytes = 64.0 * static_cast<double>(renderer.counters().joint_matrices);
        state.counters["figure_bytes_per_frame"] = benchmark::Counter(
            variant.gpu_skinning ? joint_bytes * static_cast<double>(state.iterations())
                                 : vertex_bytes * uploads,
            benchmark::Counter::kAvgIterations);
    }
    state.SetLabel(context->info().renderer);
}

void BM_FrameSkinnedGpu(benchmark::State& state) {
    frame(state, {.skinned = true});
}
void BM_FrameSkinnedCpu(benchmark::State& state) {
    frame(state, {.skinned = true, .gpu_skinning = false});
}

void BM_FrameCaustics(benchmark::State& state) {
    frame(state, {.caustics_level = true});
}
void BM_FrameCausticsNoLayer(benchmark::State& state) {
    frame(state, {.caustics_level = true, .caustic_pass = false});
}

void BM_FrameStatic(benchmark::State& state) {
    frame(state, {});
}
void BM_FrameSoft(benchmark::State& state) {
    frame(state, {.light_radius = 0.05f});
}
void BM_FrameMovingLight(benchmark::State& state) {
    frame(state, {.moving = true});
}

void BM_FrameBicubic(benchmark::State& state) {
    frame(state, {.bicubic = true});
}
void BM_FrameSky(benchmark::State& state) {
    frame(state, {.sky = true});
}
void BM_FrameSkyPlain(benchmark::State& state) {
    frame(state, {.sky = true, .sky_edges = false});
}

BENCHMARK(BM_FrameStatic)
    ->Name("Frame/static")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);
BENCHMARK(BM_FrameSoft)
    ->Name("Frame/soft")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);
BENCHMARK(BM_FrameMovingLight)
    ->Name("Frame/moving")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);
BENCHMARK(BM_FrameBicubic)
    ->Name("Frame/bicubic")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);
BENCHMARK(BM_FrameSky)
    ->Name("Frame/sky")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);
BENCHMARK(BM_FrameSkyPlain)
    ->Name("Frame/sky-plain")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);
BENCHMARK(BM_FrameSkinnedGpu)
    ->Name("Frame/skinned-gpu")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);
BENCHMARK(BM_FrameSkinnedCpu)
    ->Name("Frame/skinned-cpu")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);
BENCHMARK(BM_FrameCaustics)
    ->Name("Frame/caustics")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);
BENCHMARK(BM_FrameCausticsNoLayer)
    ->Name("Frame/caustics-no-layer")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);

}  // namespace

BENCHMARK_MAIN();
