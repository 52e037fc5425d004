// Photon engine benchmarks on the paper's 13,000-triangle Cornell box (assets/levels/
// cornell-13k.glb); figures and the commands that produced them are in docs/PERFORMANCE.md.
//   SegmentsVsRawRays/threads  photon path segments per second (the 77 x 40 photons of the
//        level's light, traced group by group through RayScene as a retrace does, without the
//        PhotonMap update) against rtcIntersect1 rays per second replaying the same rays in a
//        flat Embree scene of the same triangles built here; both on the same JobSystem, timed
//        alternately within each iteration. Counter `ratio` = segments/s over rays/s (goal 0.8),
//        `cpu_ratio` the same per CPU-second; `scene_ratio` is RayScene::intersect alone on the
//        same rays over raw Embree.
//   FullTrace          PhotonWorld sync + update of the whole level (every group traced and
//        stored); counter `bytes_per_hit` = PhotonMap::bytes_used() / stored_hit_count()
//        (goal 32), and the same for the caustic photons once all 8 slices are traced.
//   RetraceStore/per_group  two groups retraced on one thread and stored with replace_groups in
//        a map of the whole light (77 groups of 40 or 400 photons); counter `store_share` =
//        store / (trace + store), median.
//   PaperFrame/threads the paper's configuration with the level's animations playing (cube
//        sliding, glass sphere orbiting): 77 groups x 40 photons, 10,000 caustic photons over 8
//        frames. Each iteration is one 1/30 s frame; the time is PhotonWorld's work only (sync,
//        probes, group retraces, one caustic slice), with median and 95th percentile counters of
//        wall time and of process CPU time (summed over the job threads).
//   RadicalInverse     the photon samples' radical inverses as computed now against the sum of
//        digit weights they replaced; counter `ratio` = the old way's time over the new's.
//   CausticPathCells   every slice of the glass sphere's caustic list (40,000 photons) traced
//        with its paths recorded in PathCells over the scene's box against without (no region:
//        one flag), alternately; counter `ratio` = with / without (median), `cells` marked.
//   CausticDifferentials  the glass sphere's 40,000 caustic photons traced one by one on one
//        thread with their photon differentials (the footprint the default caustic kernel
//        draws) against the same photons with the differential switched off (invalid from the
//        start, so no step runs), alternately; counter `ratio` = with / without (median).
//   ExactInvalidation  the whole level traced and stored with exact invalidation's path index
//        against without, alternately; counters `ratio` (on / off, median), `index_bytes_per_hit`,
//        `segments_per_hit`, `query_us` (one query for a 0.5 m box) and `groups_found`.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <limits>
#include <memory>
#include <span>
#include <vector>

#include <embree3/rtcore.h>

#include "luxel/ecs/transform.hpp"
#include "luxel/ecs/transform_system.hpp"
#include "luxel/lighting/core/halton.hpp"
#include "luxel/lighting/core/photon_world.hpp"
#include "luxel/runtime/clock.hpp"
#include "luxel/scene/gltf.hpp"
#include "luxel/world/animation_system.hpp"
#include "luxel/world/scene_instance.hpp"
#include "test_paths.hpp"

namespace {

using namespace luxel;

std::shared_ptr<const scene::Scene> cornell_13k() {
    static const auto loaded = std::make_shared<scene::Scene>(
        scene::load_gltf(luxel::testing::source_dir() / "assets" / "levels" / "cornell-13k.glb"));
    return loaded;
}

/// The level as a game holds it: registry, transforms and the photon world.
struct Level {
    ecs::Registry registry;
    world::SceneInstance instance;
    ecs::TransformSystem transforms{registry};
    std::unique_ptr<lighting::PhotonWorld> photons;

    explicit Level(bool play_animations, lighting::PhotonWorldSettings settings = {}) {
        world::InstantiateOptions options;
        options.play_animations = play_animations;
        instance = world::instantiate(registry, cornell_13k(), options);
        transforms.update();
        photons = std::make_unique<lighting::PhotonWorld>(registry, settings);
        photons->sync();
    }
};

// --- Raw Embree: the same triangles, world space, one flat BVH --------------------------------

struct EmbreeDeleter {
    void operator()(RTCDevice device) const { rtcReleaseDevice(device); }
    void operator()(RTCScene scene) const { rtcReleaseScene(scene); }
};

class RawEmbreeScene {
  public:
    explicit RawEmbreeScene(const scene::Scene& source)
        : device_(rtcNewDevice(nullptr)), scene_(rtcNewScene(device_.get())) {
        rtcSetSceneBuildQuality(scene_.get(), RTC_BUILD_QUALITY_HIGH);
        const std::vector<glm::mat4> world = source.world_matrices();
        for (std::size_t n = 0; n < source.nodes.size(); ++n) {
            if (source.nodes[n].mesh < 0) {
                continue;
            }
            const auto& mesh = source.meshes.at(static_cast<std::size_t>(source.nodes[n].mesh));
            for (const scene::Primitive& primitive : mesh.primitives) {
                RTCGeometry geometry = rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
                auto* vertices = static_cast<glm::vec3*>(
                    rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                            sizeof(glm::vec3), primitive.positions.size()));
                auto* indices = static_cast<std::uint32_t*>(
                    rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                            3 * sizeof(std::uint32_t), primitive.triangle_count()));
                for (std::size_t v = 0; v < primitive.positions.size(); ++v) {
                    vertices[v] = glm::vec3(world[n] * glm::vec4(primitive.positions[v], 1.0f));
                }
                std::copy(primitive.indices.begin(), primitive.indices.end(), indices);
                rtcCommitGeometry(geometry);
                rtcAttachGeometry(scene_.get(), geometry);
                rtcReleaseGeometry(geometry);
            }
        }
        rtcCommitScene(scene_.get());
    }

    /// Closest-hit query; returns the geometry id hit (or RTC_INVALID_GEOMETRY_ID).
    unsigned intersect(const glm::vec3& origin, const glm::vec3& direction) const {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRayHit query{};
        query.ray.org_x = origin.x;
        query.ray.org_y = origin.y;
        query.ray.org_z = origin.z;
        query.ray.dir_x = direction.x;
        query.ray.dir_y = direction.y;
        query.ray.dir_z = direction.z;
        query.ray.tnear = 0.0f;
        query.ray.tfar = std::numeric_limits<float>::infinity();
        query.ray.mask = 0xFFFFFFFFu;
        query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        query.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene_.get(), &context, &query);
        return query.hit.geomID;
    }

  private:
    std::unique_ptr<RTCDeviceTy, EmbreeDeleter> device_;
    std::unique_ptr<RTCSceneTy, EmbreeDeleter> scene_;
};

struct Ray {
    glm::vec3 origin;
    glm::vec3 direction;
};

/// The rays the photon tracer shoots for `light`, rebuilt from the traced paths: the emission
/// ray and every hop-to-hop segment (its origin moved 0.1 mm along the ray, off the surface). A
/// segment that left the scene after a bounce has no end point and cannot be rebuilt (the
/// counters report how many rays were rebuilt against how many segments were traced).
std::vector<Ray> photon_rays(const lighting::LightPhotons& light, const lighting::RayScene& scene,
                             std::span<const lighting::TraceMaterial> materials) {
    const auto groups =
        lighting::partition_into_groups(light.group_count(), light.photons_per_group());
    const std::uint64_t total =
        static_cast<std::uint64_t>(light.group_count()) * light.photons_per_group();
    std::vector<Ray> rays;
    for (std::uint32_t g = 0; g < light.group_count(); ++g) {
        for (std::uint32_t p = 0; p < light.photons_per_group(); ++p) {
            // Emission uses sample dimensions 0-3, which no seed rotates.
            const std::uint64_t index = groups[g][p];
            const lighting::EmittedPhoton emitted = light.emitter().emit(
                {lighting::photon_sample(index, 0, 0), lighting::photon_sample(index, 1, 0)},
                {lighting::photon_sample(index, 2, 0), lighting::photon_sample(index, 3, 0)},
                total);
            std::vector<lighting::TracedHop> hops;
            lighting::TraceCounters counters;
            light.trace(scene, materials, g, p, hops, counters);
            rays.push_back({emitted.origin, emitted.direction});
            for (std::size_t h = 0; h + 1 < hops.size(); ++h) {
                const glm::vec3 direction = glm::normalize(hops[h + 1].position - hops[h].position);
                rays.push_back({hops[h].position + 1e-4f * direction, direction});
            }
        }
    }
    return rays;
}

/// What tracing the level's one light takes; `light` is null when the level has another number
/// of lights (the benchmark is then skipped).
struct LightToTrace {
    const lighting::LightPhotons* light = nullptr;
    const lighting::RayScene* scene = nullptr;
    std::span<const lighting::TraceMaterial> materials;
};

LightToTrace the_light(const Level& level, benchmark::State& state) {
    const auto lights = level.photons->active_lights();
    if (lights.size() != 1) {
        state.SkipWithError("expected the level's one light");
        return {};
    }
    return {lights.front(), &level.photons->ray_scene(), level.photons->materials()};
}

void SegmentsVsRawRays(benchmark::State& state) {
    Level level(false);
    JobSystem jobs(static_cast<int>(state.range(0)));
    const LightToTrace found = the_light(level, state);
    if (found.light == nullptr) {
        return;
    }
    const lighting::LightPhotons& light = *found.light;
    const lighting::RayScene& scene = *found.scene;
    const auto materials = found.materials;
    const RawEmbreeScene raw(*cornell_13k());
    const std::vector<Ray> rays = photon_rays(light, scene, materials);

    // Wall time, and process CPU time: on a shared machine a phase that is preempted shows the
    // wait in its wall time but not in its CPU time, so the CPU ratio is the steadier one.
    double photon_seconds = 0.0;
    double raw_seconds = 0.0;
    double scene_seconds = 0.0;
    double photon_cpu = 0.0;
    double raw_cpu = 0.0;
    double scene_cpu = 0.0;
    auto cpu_seconds_since = [](std::clock_t start) {
        return static_cast<double>(std::clock() - start) / static_cast<double>(CLOCKS_PER_SEC);
    };
    std::uint64_t segments = 0;
    std::uint64_t raw_rays = 0;
    constexpr std::size_t kRaysPerChunk = 64;
    const std::size_t chunks = (rays.size() + kRaysPerChunk - 1) / kRaysPerChunk;
    for (auto _ : state) {
        std::vector<lighting::TraceCounters> counters(light.group_count());
        const std::clock_t photon_cpu_start = std::clock();
        Stopwatch photon_clock;
        jobs.parallel_for(0, light.group_count(), [&](std::size_t g) {
            const lighting::TracedGroup traced =
                light.trace_group(scene, materials, static_cast<std::uint32_t>(g), counters[g]);
            benchmark::DoNotOptimize(traced.hops.data());
        });
        photon_seconds += to_seconds(photon_clock.elapsed());
        photon_cpu += cpu_seconds_since(photon_cpu_start);
        for (const auto& c : counters) {
            segments += c.segments;
        }

        std::atomic<std::uint64_t> hits{0};
        const std::clock_t raw_cpu_start = std::clock();
        Stopwatch raw_clock;
        jobs.parallel_for(0, chunks, [&](std::size_t chunk) {
            std::uint64_t local = 0;
            const std::size_t end = std::min(rays.size(), (chunk + 1) * kRaysPerChunk);
            for (std::size_t r = chunk * kRaysPerChunk; r < end; ++r) {
                local += raw.intersect(rays[r].origin, rays[r].direction) != RTC_INVALID_GEOMETRY_ID
                             ? 1
                             : 0;
            }
            hits.fetch_add(local, std::memory_order_relaxed);
        });
        raw_seconds += to_seconds(raw_clock.elapsed());
        raw_cpu += cpu_seconds_since(raw_cpu_start);
        raw_rays += rays.size();

        // The same rays through RayScene::intersect alone: what the two-level BVH and the hit
        // record (object, material, normals, UVs) cost without the tracer around them.
        const std::clock_t scene_cpu_start = std::clock();
        Stopwatch scene_clock;
        jobs.parallel_for(0, chunks, [&](std::size_t chunk) {
            std::uint64_t local = 0;
            const std::size_t end = std::min(rays.size(), (chunk + 1) * kRaysPerChunk);
            for (std::size_t r = chunk * kRaysPerChunk; r < end; ++r) {
                local += scene.intersect(rays[r].origin, rays[r].direction).has_value() ? 1 : 0;
            }
            hits.fetch_add(local, std::memory_order_relaxed);
        });
        scene_seconds += to_seconds(scene_clock.elapsed());
        scene_cpu += cpu_seconds_since(scene_cpu_start);
        benchmark::DoNotOptimize(hits.load());
    }
    const double segments_per_second = static_cast<double>(segments) / photon_seconds;
    const double rays_per_second = static_cast<double>(raw_rays) / raw_seconds;
    state.counters["segments_per_s"] = segments_per_second;
    state.counters["raw_rays_per_s"] = rays_per_second;
    state.counters["ratio"] = segments_per_second / rays_per_second;
    const double scene_rays_per_second = static_cast<double>(raw_rays) / scene_seconds;
    state.counters["scene_rays_per_s"] = scene_rays_per_second;
    state.counters["scene_ratio"] = scene_rays_per_second / rays_per_second;
    // Per CPU-second: (segments / photon_cpu) / (rays / raw_cpu).
    const auto replayed = static_cast<double>(raw_rays);
    state.counters["cpu_ratio"] =
        (static_cast<double>(segments) / photon_cpu) / (replayed / raw_cpu);
    state.counters["scene_cpu_ratio"] = (replayed / scene_cpu) / (replayed / raw_cpu);
    state.counters["segments_per_pass"] =
        static_cast<double>(segments) / static_cast<double>(state.iterations());
    state.counters["replayed_rays_per_pass"] = static_cast<double>(rays.size());
}
BENCHMARK(SegmentsVsRawRays)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void FullTrace(benchmark::State& state) {
    Level level(false);
    JobSystem jobs(2);
    std::size_t bytes = 0;
    std::size_t hits = 0;
    std::size_t paths = 0;
    for (auto _ : state) {
        state.PauseTiming();
        level.photons.reset();
        level.photons = std::make_unique<lighting::PhotonWorld>(level.registry);
        state.ResumeTiming();
        level.photons->sync();
        level.photons->probe(0, jobs);
        level.photons->retrace_pending(jobs);
        bytes = level.photons->photon_map().bytes_used();
        hits = level.photons->photon_map().stored_hit_count();
        paths = level.photons->photon_map().path_count();
    }
    state.counters["stored_hits"] = static_cast<double>(hits);
    state.counters["paths"] = static_cast<double>(paths);
    state.counters["bytes_per_hit"] = static_cast<double>(bytes) / static_cast<double>(hits);
    // Where the bytes go: the per-surface hit arrays (22 bytes a hit, with their growth slack)
    // against everything else (per-photon path fingerprints, each group's surfaces, the vectors).
    const lighting::PhotonMap& map = level.photons->photon_map();
    std::size_t hit_array_bytes = 0;
    for (std::uint32_t s = 0; s < map.surface_count(); ++s) {
        const lighting::SurfacePhotons& photons = map.surface(s);
        hit_array_bytes += photons.positions.capacity() * sizeof(glm::vec3) +
                           photons.powers.capacity() * sizeof(lighting::HalfPower) +
                           photons.owners.capacity() * sizeof(std::uint32_t);
    }
    state.counters["hit_array_bytes_per_hit"] =
        static_cast<double>(hit_array_bytes) / static_cast<double>(hits);
    state.counters["path_bytes_per_hit"] =
        static_cast<double>(bytes - hit_array_bytes) / static_cast<double>(hits);
    for (std::uint64_t frame = 0; frame < 8; ++frame) {
        level.photons->update_caustics(frame, jobs);
    }
    const lighting::CausticTotals caustics = level.photons->caustic_totals();
    state.counters["caustic_photons"] = static_cast<double>(caustics.stored);
    state.counters["caustic_bytes_per_photon"] =
        static_cast<double>(caustics.bytes) / static_cast<double>(caustics.stored);
}
BENCHMARK(FullTrace)->Unit(benchmark::kMillisecond)->UseRealTime();

/// What storing costs beside tracing: the level's light with `per_group` photons in each of its
/// 77 groups, all stored in a PhotonMap; each iteration retraces two groups on one thread (a
/// retrace unit) and stores them with replace_groups, which passes once over every surface the
/// groups' old hits lay on. Counters: `store_share` (store / (trace + store), median), the
/// median `store_us` and `trace_us`, and the map's `stored_hits`.
void RetraceStore(benchmark::State& state) {
    lighting::PhotonWorldSettings settings;
    settings.selective.per_group = static_cast<std::uint32_t>(state.range(0));
    Level level(false, settings);
    const LightToTrace found = the_light(level, state);
    if (found.light == nullptr) {
        return;
    }
    const lighting::LightPhotons& light = *found.light;
    lighting::PhotonMap map(level.photons->photon_map().surface_count(),
                            light.first_group() + light.group_count(),
                            settings.selective.tolerance);
    lighting::TraceCounters counters;
    for (std::uint32_t g = 0; g < light.group_count(); ++g) {
        map.replace_group(light.first_group() + g,
                          light.trace_group(*found.scene, found.materials, g, counters));
    }
    std::vector<double> store_us;
    std::vector<double> trace_us;
    std::vector<double> shares;
    std::uint32_t next = 0;
    for (auto _ : state) {
        const std::uint32_t groups[] = {light.first_group() + next,
                                        light.first_group() + (next + 1) % light.group_count()};
        next = (next + 2) % light.group_count();
        Stopwatch trace_clock;
        const lighting::TracedGroup traced[] = {
            light.trace_group(*found.scene, found.materials, groups[0] - light.first_group(),
                              counters),
            light.trace_group(*found.scene, found.materials, groups[1] - light.first_group(),
                              counters)};
        const double trace = to_seconds(trace_clock.elapsed());
        Stopwatch store_clock;
        map.replace_groups(groups, traced);
        const double store = to_seconds(store_clock.elapsed());
        trace_us.push_back(1e6 * trace);
        store_us.push_back(1e6 * store);
        shares.push_back(store / std::max(trace + store, 1e-12));
    }
    std::sort(shares.begin(), shares.end());
    std::sort(store_us.begin(), store_us.end());
    std::sort(trace_us.begin(), trace_us.end());
    state.counters["store_share"] = shares[shares.size() / 2];
    state.counters["store_us"] = store_us[store_us.size() / 2];
    state.counters["trace_us"] = trace_us[trace_us.size() / 2];
    state.counters["stored_hits"] = static_cast<double>(map.stored_hit_count());
}
BENCHMARK(RetraceStore)->Arg(40)->Arg(400)->Unit(benchmark::kMicrosecond)->UseRealTime();

double percentile(std::vector<double> values, double fraction) {
    std::sort(values.begin(), values.end());
    const auto rank = static_cast<std::size_t>(fraction * static_cast<double>(values.size() - 1));
    return values[rank];
}

/// Exact invalidation's price: the whole level traced and stored with the path index kept
/// (exact_invalidation on) against without it, alternately in each iteration; counters: the
/// median time ratio (`ratio`, on / off), the index's bytes per stored hit, and the time of
/// one query for the moving cube's box (what a move costs on top of the retraces it causes).
void ExactInvalidation(benchmark::State& state) {
    JobSystem jobs(2);
    lighting::PhotonWorldSettings off;
    off.selective.exact_invalidation = false;
    lighting::PhotonWorldSettings on;
    on.selective.exact_invalidation = true;
    Level without(false, off);
    Level with(false, on);
    const auto trace = [&](Level& level, const lighting::PhotonWorldSettings& settings) {
        level.photons = std::make_unique<lighting::PhotonWorld>(level.registry, settings);
        const auto start = std::chrono::steady_clock::now();
        level.photons->sync();
        level.photons->probe(0, jobs);
        level.photons->retrace_pending(jobs);
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    std::vector<double> ratios;
    for (auto _ : state) {
        const double base = trace(without, off);
        const double exact = trace(with, on);
        ratios.push_back(base > 0.0 ? exact / base : 0.0);
    }
    const lighting::PathSegmentIndex& paths = with.photons->paths();
    const std::size_t hits = with.photons->photon_map().stored_hit_count();
    // A 0.5 m box where the level's moving cube stands.
    const glm::mat4 cube =
        with.registry.get<ecs::WorldTransform>(with.instance.find("moving cube")).matrix;
    const glm::vec3 centre(cube[3]);
    lighting::AxisBox box;
    box.add(centre - glm::vec3(0.25f));
    box.add(centre + glm::vec3(0.25f));
    constexpr int kQueries = 1000;
    std::size_t found = 0;
    const auto start = std::chrono::steady_clock::now();
    for (int q = 0; q < kQueries; ++q) {
        found += paths.groups_meeting(box).size();
    }
    const double query_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    state.counters["ratio"] = percentile(ratios, 0.5);
    state.counters["index_bytes_per_hit"] = static_cast<double>(paths.bytes_used()) /
                                            static_cast<double>(std::max<std::size_t>(hits, 1));
    state.counters["segments_per_hit"] = static_cast<double>(paths.segment_count()) /
                                         static_cast<double>(std::max<std::size_t>(hits, 1));
    state.counters["query_us"] = query_s / kQueries * 1e6;
    state.counters["groups_found"] = static_cast<double>(found) / kQueries;
}
BENCHMARK(ExactInvalidation)->Unit(benchmark::kMillisecond)->UseRealTime();

/// What recording a caustic list's paths costs (METHOD 7.2): the list traced whole with its
/// PathCells over the scene's box, against the same list recording nothing but a flag.
/// The emitter of the level's first caustic list (the glass sphere and the light), or null
/// with the benchmark skipped when the level has none.
const lighting::CausticEmitter* sphere_emitter(const Level& level, benchmark::State& state) {
    if (level.photons->caustics().empty()) {
        state.SkipWithError("cornell-13k has no caustic generator");
        return nullptr;
    }
    return &level.photons->caustics().front().photons.emitter();
}

void CausticPathCells(benchmark::State& state) {
    JobSystem jobs(2);
    Level level(false);
    const lighting::CausticEmitter* const found = sphere_emitter(level, state);
    if (found == nullptr) {
        return;
    }
    const lighting::CausticEmitter& emitter = *found;
    const lighting::RayScene& rays = level.photons->ray_scene();
    lighting::AxisBox region;
    region.add(rays.bounds_min());
    region.add(rays.bounds_max());
    lighting::CausticPhotonList with(40'000, 8, 1);
    lighting::CausticPhotonList without(40'000, 8, 1);
    const auto trace = [&](lighting::CausticPhotonList& list, const lighting::AxisBox& box) {
        list.set_emitter(emitter, box);
        const auto start = std::chrono::steady_clock::now();
        for (std::uint32_t k = 0; k < 8; ++k) {
            list.retrace_slice(rays, level.photons->materials(), k, 16, jobs);
        }
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    std::vector<double> ratios;
    for (auto _ : state) {
        const double base = trace(without, {});
        const double recorded = trace(with, region);
        ratios.push_back(base > 0.0 ? recorded / base : 0.0);
    }
    int cells = 0;
    const lighting::PathCells& recorded = with.path_cells();
    constexpr int kCells = lighting::PathCells::kCells;
    const glm::vec3 size = (region.max - region.min) / static_cast<float>(kCells);
    for (int z = 0; z < kCells; ++z) {
        for (int y = 0; y < kCells; ++y) {
            for (int x = 0; x < kCells; ++x) {
                const glm::vec3 lo = region.min + size * glm::vec3(x, y, z) + 0.1f * size;
                lighting::AxisBox cell;
                cell.add(lo);
                cell.add(lo + 0.8f * size);
                cells += recorded.meets(cell) ? 1 : 0;
            }
        }
    }
    state.counters["ratio"] = percentile(ratios, 0.5);
    state.counters["cells"] = cells;
}
BENCHMARK(CausticPathCells)->Unit(benchmark::kMillisecond)->UseRealTime();

void CausticDifferentials(benchmark::State& state) {
    Level level(false);
    const lighting::CausticEmitter* const found = sphere_emitter(level, state);
    if (found == nullptr) {
        return;
    }
    const lighting::CausticEmitter& emitter = *found;
    const lighting::RayScene& rays = level.photons->ray_scene();
    constexpr std::uint64_t kPhotons = 40'000;
    std::vector<lighting::EmittedPhoton> emitted;
    for (std::uint64_t j = 1; j <= kPhotons; ++j) {
        emitted.push_back(emitter.emit(
            {lighting::photon_sample(j, 0, 1), lighting::photon_sample(j, 1, 1)},
            {lighting::photon_sample(j, 2, 1), lighting::photon_sample(j, 3, 1)}, kPhotons));
    }
    lighting::PhotonDifferential off;
    off.valid = false;
    const auto trace = [&](bool differentials) {
        lighting::CausticTraceCounters counters;
        std::uint64_t stored = 0;
        const auto start = std::chrono::steady_clock::now();
        for (std::uint64_t j = 0; j < kPhotons; ++j) {
            const lighting::PhotonDifferential start_differential =
                differentials ? emitter.differential(emitted[j], kPhotons) : off;
            stored += lighting::trace_caustic_photon(rays, level.photons->materials(), emitted[j],
                                                     start_differential, j + 1, 1, 16, counters)
                          ? 1
                          : 0;
        }
        benchmark::DoNotOptimize(stored);
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    std::vector<double> ratios;
    for (auto _ : state) {
        const double without = trace(false);
        const double with = trace(true);
        ratios.push_back(without > 0.0 ? with / without : 0.0);
    }
    state.counters["ratio"] = percentile(ratios, 0.5);
}
BENCHMARK(CausticDifferentials)->Unit(benchmark::kMillisecond)->UseRealTime();

void PaperFrame(benchmark::State& state) {
    lighting::PhotonWorldSettings settings;  // 77 x 40; 10,000 caustic photons, K = 8
    Level level(true, settings);
    JobSystem jobs(static_cast<int>(state.range(0)));
    // Warm up: every group traced, every caustic slice filled, before anything moves.
    level.photons->probe(0, jobs);
    level.photons->retrace_pending(jobs);
    for (std::uint64_t frame = 0; frame < 8; ++frame) {
        level.photons->update_caustics(frame, jobs);
    }
    std::vector<double> total_ms;
    std::vector<double> cpu_ms;
    std::vector<double> sync_ms;
    std::vector<double> global_ms;
    std::vector<double> caustic_ms;
    std::uint64_t retraced_groups = 0;
    std::uint32_t most_groups_in_a_frame = 0;
    std::uint64_t caustic_photons = 0;
    std::uint64_t segments = 0;
    std::uint64_t frame = 8;
    for (auto _ : state) {
        // The game's part of the frame: not counted.
        world::update_animations(level.registry, 1.0 / 30.0);
        level.transforms.update();

        // Process CPU time as well: on a shared machine a frame that is preempted shows the
        // time slice it waited in its wall time but not in its CPU time.
        const std::clock_t cpu_start = std::clock();
        Stopwatch clock;
        level.photons->sync();
        const double after_sync = clock.elapsed_ms();
        const lighting::EmissionStats probes = level.photons->probe(frame, jobs);
        const lighting::EmissionStats retraces = level.photons->retrace_pending(jobs);
        const double after_global = clock.elapsed_ms();
        const lighting::CausticFrameStats caustics = level.photons->update_caustics(frame, jobs);
        const double after_caustics = clock.elapsed_ms();
        const std::clock_t cpu_end = std::clock();
        state.SetIterationTime(after_caustics / 1000.0);
        cpu_ms.push_back(1000.0 * static_cast<double>(cpu_end - cpu_start) /
                         static_cast<double>(CLOCKS_PER_SEC));

        total_ms.push_back(after_caustics);
        sync_ms.push_back(after_sync);
        global_ms.push_back(after_global - after_sync);
        caustic_ms.push_back(after_caustics - after_global);
        retraced_groups += retraces.groups_retraced;
        most_groups_in_a_frame = std::max(most_groups_in_a_frame, retraces.groups_retraced);
        caustic_photons += caustics.trace.photons;
        segments += probes.trace.segments + retraces.trace.segments + caustics.trace.segments;
        ++frame;
    }
    const auto frames = static_cast<double>(total_ms.size());
    state.counters["median_ms"] = percentile(total_ms, 0.5);
    state.counters["p95_ms"] = percentile(total_ms, 0.95);
    state.counters["cpu_median_ms"] = percentile(cpu_ms, 0.5);
    state.counters["cpu_p95_ms"] = percentile(cpu_ms, 0.95);
    state.counters["sync_median_ms"] = percentile(sync_ms, 0.5);
    state.counters["global_median_ms"] = percentile(global_ms, 0.5);
    state.counters["caustic_median_ms"] = percentile(caustic_ms, 0.5);
    state.counters["global_p95_ms"] = percentile(global_ms, 0.95);
    state.counters["caustic_p95_ms"] = percentile(caustic_ms, 0.95);
    state.counters["most_groups_retraced"] = most_groups_in_a_frame;
    state.counters["groups_retraced_per_frame"] = static_cast<double>(retraced_groups) / frames;
    state.counters["caustic_photons_per_frame"] = static_cast<double>(caustic_photons) / frames;
    state.counters["segments_per_frame"] = static_cast<double>(segments) / frames;
}
BENCHMARK(PaperFrame)
    ->Arg(1)
    ->Arg(2)
    ->Iterations(200)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

/// photon_sample's Halton dimensions: the per-prime quotient of the reversed digits
/// (radical_inverse_in_dimension) against the sum of the digits' weights with a division per
/// digit (radical_inverse_sum, what photon_sample used before issue 24), over the same 32
/// dimensions and the indices of a million photons, timed alternately in each iteration.
/// Counters: `ratio` (sum's time over the quotient's: the speed-up), ns per sample of each.
void RadicalInverse(benchmark::State& state) {
    constexpr std::uint64_t kIndices = 1u << 20;
    constexpr std::uint64_t kStride = 97;  // 10,811 indices spread over the million
    double quotient_seconds = 0.0;
    double sum_seconds = 0.0;
    std::uint64_t samples = 0;
    for (auto _ : state) {
        double total = 0.0;
        Stopwatch quotient_clock;
        for (std::uint64_t index = 0; index < kIndices; index += kStride) {
            for (std::uint32_t dim = 0; dim < lighting::kHaltonPrimes.size(); ++dim) {
                total += lighting::radical_inverse_in_dimension(dim, index);
            }
        }
        quotient_seconds += to_seconds(quotient_clock.elapsed());
        Stopwatch sum_clock;
        for (std::uint64_t index = 0; index < kIndices; index += kStride) {
            for (std::uint32_t dim = 0; dim < lighting::kHaltonPrimes.size(); ++dim) {
                total -= lighting::radical_inverse_sum(lighting::kHaltonPrimes[dim], index);
            }
        }
        sum_seconds += to_seconds(sum_clock.elapsed());
        benchmark::DoNotOptimize(total);
        samples += ((kIndices + kStride - 1) / kStride) * lighting::kHaltonPrimes.size();
    }
    state.counters["ratio"] = quotient_seconds > 0.0 ? sum_seconds / quotient_seconds : 0.0;
    state.counters["quotient_ns"] = 1e9 * quotient_seconds / static_cast<double>(samples);
    state.counters["sum_ns"] = 1e9 * sum_seconds / static_cast<double>(samples);
}
BENCHMARK(RadicalInverse)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
