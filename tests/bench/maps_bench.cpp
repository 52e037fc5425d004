// Illumination-map benchmarks, CPU side (issue 7); figures and the command that produced them
// are in docs/PERFORMANCE.md ("Illumination maps").
//   KdBuild/photons   PhotonDensity construction (nanoflann kd-tree, leaves of 16) over one
//        surface's photons, against a plain loop copying the same photons out of the PhotonMap
//        (what the construction does before building the tree), timed alternately within each
//        iteration. Counters: build_ms, copy_ms, ratio = build / copy.
//   KdQuery/photons   PhotonDensity::irradiance with DensitySettings::nearest = 100 at 64 points
//        on the surface, against a brute-force search (squared distances to every photon, then
//        std::nth_element for the 100 nearest, summing their power). Counters per query:
//        query_ms, brute_ms, ratio = query / brute.
//   Gather/scene/rays CpuGatherer::gather of 64 floor texels at `rays` rays per texel, one
//        thread (no JobSystem), against the same rays (same origins, same cosine-weighted
//        Halton directions with the same per-texel rotation) traced by RayScene::intersect
//        alone, and by rtcIntersect1 in a flat Embree scene of the same triangles. Counters:
//        ms_per_texel, gather_rays_per_s, scene_rays_per_s, ratio = gather / scene rays per
//        second (goal 0.7), cpu_ratio the same per process CPU second, flat_rays_per_s and
//        flat_ratio = gather / flat.
//        scene: 0 = a 34-triangle box (five walls, two blocks) with a synthetic atlas,
//        1 = prepared/cornell-13k, 2 = prepared/cornell-133k, both with their photons traced and
//        every surface's AIM built before timing.
//   AimRebuild        IlluminationMaps::rebuild_aim of every light-mapped surface of
//        prepared/cornell, each timed; counters: ms_per_surface (mean), max_surface_ms,
//        ms_per_texel, texels and photons per pass.
//   GatherUnit        IlluminationMaps::gather of one unit of 20 texels (the paper's unit) on
//        prepared/two-rooms' largest surface, 50 units per iteration, against
//        CpuGatherer::gather of the same 20 texels placed in the world beforehand (one thread,
//        64 rays). Counters: unit_ms, gather_ms, ratio = unit / gather (what a unit costs
//        beyond its rays), surface_texels.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <span>
#include <string>
#include <vector>

#include <embree3/rtcore.h>

#include "luxel/ecs/transform_system.hpp"
#include "luxel/lighting/core/cpu_gather.hpp"
#include "luxel/lighting/core/halton.hpp"
#include "luxel/lighting/core/illumination_maps.hpp"
#include "luxel/lighting/core/light_source.hpp"
#include "luxel/lighting/core/photon_density.hpp"
#include "luxel/lighting/core/photon_world.hpp"
#include "luxel/lighting/core/seam_stitcher.hpp"
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
double cpu_seconds_since(std::clock_t start) {
    return static_cast<double>(std::clock() - start) / static_cast<double>(CLOCKS_PER_SEC);
}

// --- kd-tree -----------------------------------------------------------------------------------

/// `count` photons scattered uniformly over a 1 m x 1 m square at y = 0, stored as surface 0 of
/// a PhotonMap (one hop each, direct hits), and 64 query points on the square.
struct SurfacePhotons1 {
    PhotonMap map{1, 1};
    std::vector<glm::vec3> queries;

    explicit SurfacePhotons1(std::size_t count) {
        std::mt19937 random(7);
        std::uniform_real_distribution<float> unit(0.0f, 1.0f);
        TracedGroup traced;
        traced.starts.push_back(0);
        for (std::size_t i = 0; i < count; ++i) {
            const glm::vec3 position(unit(random), 0.0f, unit(random));
            const glm::vec3 power(1e-3f * (0.5f + unit(random)));
            traced.hops.push_back({position, power, 0, kNoObject, 0});
            traced.starts.push_back(static_cast<std::uint32_t>(traced.hops.size()));
        }
        map.replace_group(0, traced);
        for (int q = 0; q < 64; ++q) {
            queries.emplace_back(unit(random), 0.0f, unit(random));
        }
    }
};

struct PlainPhoton {
    glm::vec3 position;
    glm::vec3 power;
};

/// The baseline build: what PhotonDensity does before the tree, copying the hits out.
std::vector<PlainPhoton> copy_photons(const PhotonMap& map) {
    std::vector<PlainPhoton> photons;
    for (std::size_t i = 0; i < map.surface(0).hit_count(); ++i) {
        const StoredHit hit = map.hit(0, i);
        photons.push_back({hit.position, hit.power});
    }
    return photons;
}

void KdBuild(benchmark::State& state) {
    const SurfacePhotons1 surface(static_cast<std::size_t>(state.range(0)));
    const std::array<std::uint32_t, 1> surfaces{0};
    double build_seconds = 0.0;
    double copy_seconds = 0.0;
    for (auto _ : state) {
        const Clock::time_point build_start = Clock::now();
        {
            const PhotonDensity density(surface.map, surfaces, PhotonSelection::Full);
            benchmark::DoNotOptimize(density.photon_count());
        }
        const double build = seconds_since(build_start);
        const Clock::time_point copy_start = Clock::now();
        {
            const std::vector<PlainPhoton> copied = copy_photons(surface.map);
            benchmark::DoNotOptimize(copied.data());
        }
        copy_seconds += seconds_since(copy_start);
        build_seconds += build;
        state.SetIterationTime(build);
    }
    const auto iterations = static_cast<double>(state.iterations());
    state.counters["build_ms"] = 1e3 * build_seconds / iterations;
    state.counters["copy_ms"] = 1e3 * copy_seconds / iterations;
    state.counters["ratio"] = build_seconds / copy_seconds;
}
BENCHMARK(KdBuild)->Arg(300)->Arg(500)->Arg(1000)->Arg(2000)->UseManualTime()->Unit(
    benchmark::kMillisecond);

/// The baseline query: every squared distance, then nth_element for the `nearest` smallest;
/// the power of those nearer than the last is summed over the disc through it.
glm::vec3 brute_force_irradiance(const std::vector<PlainPhoton>& photons, const glm::vec3& query,
                                 std::size_t nearest,
                                 std::vector<std::pair<float, std::uint32_t>>& d) {
    d.resize(photons.size());
    for (std::size_t i = 0; i < photons.size(); ++i) {
        const glm::vec3 offset = photons[i].position - query;
        d[i] = {glm::dot(offset, offset), static_cast<std::uint32_t>(i)};
    }
    const std::size_t n = std::min(nearest, d.size());
    std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(n - 1), d.end());
    const float radius_squared = d[n - 1].first;
    glm::vec3 total(0.0f);
    for (std::size_t k = 0; k + 1 < n; ++k) {
        total += photons[d[k].second].power;
    }
    return total / (3.14159265f * radius_squared);
}

void KdQuery(benchmark::State& state) {
    const SurfacePhotons1 surface(static_cast<std::size_t>(state.range(0)));
    const std::array<std::uint32_t, 1> surfaces{0};
    const PhotonDensity density(surface.map, surfaces, PhotonSelection::Full);
    const std::vector<PlainPhoton> photons = copy_photons(surface.map);
    DensitySettings settings;
    settings.nearest = 100;
    settings.max_radius = 10.0f;  // never caps: always the 100 nearest
    std::vector<std::pair<float, std::uint32_t>> scratch;
    const glm::vec3 normal(0.0f, 1.0f, 0.0f);
    double query_seconds = 0.0;
    double brute_seconds = 0.0;
    for (auto _ : state) {
        const Clock::time_point query_start = Clock::now();
        for (const glm::vec3& q : surface.queries) {
            benchmark::DoNotOptimize(density.irradiance(q, normal, settings));
        }
        const double query = seconds_since(query_start);
        const Clock::time_point brute_start = Clock::now();
        for (const glm::vec3& q : surface.queries) {
            benchmark::DoNotOptimize(brute_force_irradiance(photons, q, 100, scratch));
        }
        brute_seconds += seconds_since(brute_start);
        query_seconds += query;
        state.SetIterationTime(query);
    }
    const double queries =
        static_cast<double>(state.iterations()) * static_cast<double>(surface.queries.size());
    state.counters["query_ms"] = 1e3 * query_seconds / queries;
    state.counters["brute_ms"] = 1e3 * brute_seconds / queries;
    state.counters["ratio"] = query_seconds / brute_seconds;
}
BENCHMARK(KdQuery)->Arg(300)->Arg(500)->Arg(1000)->Arg(2000)->UseManualTime()->Unit(
    benchmark::kMillisecond);

// --- Scenes for the gather ----------------------------------------------------------------------

std::filesystem::path prepared(const std::string& name) {
    return luxel::testing::source_dir() / "assets" / "levels" / "prepared" / (name + ".glb");
}

/// A prepared level as a game holds it: photons traced once (frame 0, every group) and every
/// light-mapped surface's AIM built.
struct Level {
    ecs::Registry registry;
    world::SceneInstance instance;
    ecs::TransformSystem transforms{registry};
    std::unique_ptr<PhotonWorld> photons;
    std::unique_ptr<IlluminationMaps> maps;

    explicit Level(const std::string& name) {
        world::InstantiateOptions options;
        options.play_animations = false;
        instance = world::instantiate(
            registry, std::make_shared<scene::Scene>(scene::load_gltf(prepared(name))), options);
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

    /// `count` texels spread evenly over the floor: the lowest surface facing +y.
    [[nodiscard]] std::vector<GatherTexel> floor_texels(std::size_t count) const {
        std::vector<GatherTexel> best;
        float lowest = std::numeric_limits<float>::max();
        for (std::uint32_t s = 0; s < maps->surfaces().size(); ++s) {
            std::vector<GatherTexel> texels = maps->world_texels(s);
            if (texels.size() < count || texels.front().normal.y < 0.9f) {
                continue;
            }
            if (texels.front().position.y < lowest) {
                lowest = texels.front().position.y;
                best = std::move(texels);
            }
        }
        std::vector<GatherTexel> picked;
        for (std::size_t i = 0; i < count && !best.empty(); ++i) {
            picked.push_back(best[i * best.size() / count]);
        }
        return picked;
    }
};

/// The 12 triangles of the box [lo, hi], two per face, winding towards the inside when
/// `inward`; face f (-x, +x, -y, +y, -z, +z) is surface first_surface + f, its light-map UVs
/// spanning its own page.
TriangleMesh box_mesh(const glm::vec3& lo, const glm::vec3& hi, bool inward,
                      std::int32_t first_surface) {
    TriangleMesh mesh;
    const glm::vec3 centre = 0.5f * (lo + hi);
    const glm::vec3 half = 0.5f * (hi - lo);
    for (int face = 0; face < 6; ++face) {
        const int axis = face / 2;
        glm::vec3 outward(0.0f);
        outward[axis] = face % 2 == 0 ? -1.0f : 1.0f;
        const glm::vec3 facing = inward ? -outward : outward;
        glm::vec3 u(0.0f);
        u[(axis + 1) % 3] = 1.0f;
        const glm::vec3 v = glm::cross(facing, u);
        const glm::vec3 c = centre + outward * half;
        const glm::vec3 su = u * half;
        const glm::vec3 sv = v * half;
        const auto base = static_cast<std::uint32_t>(mesh.positions.size());
        mesh.positions.insert(mesh.positions.end(),
                              {c - su - sv, c + su - sv, c + su + sv, c - su + sv});
        mesh.lightmap_uvs.insert(mesh.lightmap_uvs.end(), {{0, 0}, {1, 0}, {1, 1}, {0, 1}});
        mesh.indices.insert(mesh.indices.end(),
                            {base, base + 1, base + 2, base, base + 2, base + 3});
        mesh.surface_ids.insert(mesh.surface_ids.end(), 2, first_surface + face);
        mesh.material_ids.insert(mesh.material_ids.end(), 2, 0u);
    }
    return mesh;
}

/// What a gather benchmark shoots into: a RayScene, the atlas the gatherer reads, and 64 floor
/// texels.
struct GatherScene {
    std::unique_ptr<Level> level;  // null for the box
    RayScene box;
    RadianceAtlas box_atlas;
    std::vector<GatherTexel> texels;

    [[nodiscard]] const RayScene& scene() const {
        return level ? level->photons->ray_scene() : box;
    }
    [[nodiscard]] const RadianceAtlas& atlas() const {
        return level ? level->maps->aim() : box_atlas;
    }
};

constexpr std::size_t kGatherTexels = 64;

/// The classic 34-triangle box: the 2 m box [-1, 1]^3 open at +z (10 triangles) and two blocks
/// standing on its floor (12 each); 18 surfaces, each on a 16^2 page of smoothly varying
/// radiance; 64 floor texels on a grid, none under a block.
std::unique_ptr<GatherScene> box_scene() {
    auto g = std::make_unique<GatherScene>();
    TriangleMesh walls = box_mesh(glm::vec3(-1.0f), glm::vec3(1.0f), true, 0);
    walls.positions.resize(20);
    walls.lightmap_uvs.resize(20);
    walls.indices.resize(30);
    walls.surface_ids.resize(10);
    walls.material_ids.resize(10);
    g->box.add_object(std::move(walls), glm::mat4(1.0f), false);
    const glm::vec3 block_lo[2] = {{-0.7f, -1.0f, -0.6f}, {0.1f, -1.0f, 0.1f}};
    const glm::vec3 block_hi[2] = {{-0.1f, 0.2f, 0.0f}, {0.7f, -0.4f, 0.7f}};
    for (int b = 0; b < 2; ++b) {
        g->box.add_object(box_mesh(block_lo[b], block_hi[b], false, 6 + 6 * b), glm::mat4(1.0f),
                          false);
    }
    g->box.commit();
    for (std::int32_t s = 0; s < 18; ++s) {
        RadiancePage page(16);
        for (int y = 0; y < page.size; ++y) {
            for (int x = 0; x < page.size; ++x) {
                const auto fx = static_cast<float>(x + s);
                const auto fy = static_cast<float>(y);
                page.at(x, y) = {0.6f + 0.4f * std::sin(0.3f * fx),
                                 0.5f + 0.3f * std::cos(0.2f * fy),
                                 0.4f + 0.2f * std::sin(0.1f * (fx + fy))};
            }
        }
        g->box_atlas.pages.push_back(std::move(page));
        g->box_atlas.surface_page.push_back(s);
    }
    for (int j = 0; j < 16 && g->texels.size() < kGatherTexels; ++j) {
        for (int i = 0; i < 16 && g->texels.size() < kGatherTexels; ++i) {
            const glm::vec3 p(-0.95f + 1.9f * static_cast<float>(i) / 15.0f, -1.0f,
                              -0.95f + 1.9f * static_cast<float>(j) / 15.0f);
            bool under_block = false;
            for (int b = 0; b < 2; ++b) {
                under_block = under_block || (p.x > block_lo[b].x && p.x < block_hi[b].x &&
                                              p.z > block_lo[b].z && p.z < block_hi[b].z);
            }
            if (!under_block) {
                g->texels.push_back({p, glm::vec3(0.0f, 1.0f, 0.0f)});
            }
        }
    }
    return g;
}

const GatherScene& gather_scene(std::int64_t which) {
    static std::map<std::int64_t, std::unique_ptr<GatherScene>> scenes;
    auto& slot = scenes[which];
    if (!slot) {
        if (which == 0) {
            slot = box_scene();
        } else {
            slot = std::make_unique<GatherScene>();
            slot->level = std::make_unique<Level>(which == 1 ? "cornell-13k" : "cornell-133k");
            slot->texels = slot->level->floor_texels(kGatherTexels);
        }
    }
    return *slot;
}

// --- Raw Embree: the RayScene's triangles in world space, one flat BVH -------------------------

struct EmbreeDeleter {
    void operator()(RTCDevice device) const { rtcReleaseDevice(device); }
    void operator()(RTCScene scene) const { rtcReleaseScene(scene); }
};

class FlatEmbreeScene {
  public:
    explicit FlatEmbreeScene(const RayScene& source)
        : device_(rtcNewDevice(nullptr)), scene_(rtcNewScene(device_.get())) {
        rtcSetSceneBuildQuality(scene_.get(), RTC_BUILD_QUALITY_HIGH);
        for (const ObjectId id : source.objects()) {
            const TriangleMesh& mesh = source.mesh(id);
            const glm::mat4 to_world =
                source.is_dynamic(id) ? source.transform(id) : glm::mat4(1.0f);
            RTCGeometry geometry = rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
            auto* vertices = static_cast<glm::vec3*>(
                rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                        sizeof(glm::vec3), mesh.positions.size()));
            auto* indices = static_cast<std::uint32_t*>(
                rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                        3 * sizeof(std::uint32_t), mesh.triangle_count()));
            for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
                vertices[v] = glm::vec3(to_world * glm::vec4(mesh.positions[v], 1.0f));
            }
            std::copy(mesh.indices.begin(), mesh.indices.end(), indices);
            rtcCommitGeometry(geometry);
            rtcAttachGeometry(scene_.get(), geometry);
            rtcReleaseGeometry(geometry);
        }
        rtcCommitScene(scene_.get());
    }

    [[nodiscard]] bool hits(const glm::vec3& origin, const glm::vec3& direction,
                            float max_distance) const {
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
        query.ray.tfar = max_distance;
        query.ray.mask = 0xFFFFFFFFu;
        query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        query.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene_.get(), &context, &query);
        return query.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    }

  private:
    std::unique_ptr<RTCDeviceTy, EmbreeDeleter> device_;
    std::unique_ptr<RTCSceneTy, EmbreeDeleter> scene_;
};

// --- Gather against raw rays ---------------------------------------------------------------------

struct Ray {
    glm::vec3 origin;
    glm::vec3 direction;
};

/// The per-texel rotation of the Halton pattern, as cpu_gather.cpp computes it (a copy: the
/// benchmark replays the gatherer's exact rays).
glm::dvec2 rotation_for(const glm::vec3& position) {
    std::uint32_t hash = 2166136261u;
    for (int axis = 0; axis < 3; ++axis) {
        std::uint32_t bits = 0;
        const float value = position[axis];
        std::memcpy(&bits, &value, sizeof(bits));
        hash = (hash ^ bits) * 16777619u;
    }
    hash ^= hash >> 16;
    hash *= 0x7feb352du;
    hash ^= hash >> 15;
    return {static_cast<double>(hash & 0xFFFFu) / 65536.0,
            static_cast<double>(hash >> 16) / 65536.0};
}

/// Every ray CpuGatherer::gather shoots for `texels` at `rays_per_texel` (to float rounding:
/// the gatherer tabulates the unrotated pattern and rotates the azimuth by the angle sum).
std::vector<Ray> gather_rays(const std::vector<GatherTexel>& texels, std::uint32_t rays_per_texel) {
    std::vector<Ray> rays;
    rays.reserve(texels.size() * rays_per_texel);
    for (const GatherTexel& texel : texels) {
        const glm::vec3 normal = glm::normalize(texel.normal);
        const glm::vec3 origin = offset_ray_origin(texel.position, normal);
        const glm::dvec2 rotation = rotation_for(texel.position);
        for (std::uint32_t i = 0; i < rays_per_texel; ++i) {
            glm::dvec2 u = halton2(i) + rotation;
            u -= glm::floor(u);
            rays.push_back({origin, cosine_direction(normal, u)});
        }
    }
    return rays;
}

void Gather(benchmark::State& state) {
    const GatherScene& g = gather_scene(state.range(0));
    const auto rays_per_texel = static_cast<std::uint32_t>(state.range(1));
    const RayScene& scene = g.scene();
    const FlatEmbreeScene flat(scene);
    constexpr float kMaxDistance = 1e6f;
    CpuGatherer gatherer(scene, g.atlas(), {rays_per_texel, kMaxDistance});
    const std::vector<Ray> rays = gather_rays(g.texels, rays_per_texel);
    std::vector<glm::vec3> irradiance(g.texels.size());

    double gather_seconds = 0.0;
    double scene_seconds = 0.0;
    double flat_seconds = 0.0;
    double gather_cpu = 0.0;
    double scene_cpu = 0.0;
    std::uint64_t hits = 0;
    for (auto _ : state) {
        const std::clock_t gather_cpu_start = std::clock();
        const Clock::time_point gather_start = Clock::now();
        gatherer.gather(g.texels, irradiance);
        benchmark::DoNotOptimize(irradiance.data());
        const double gathered = seconds_since(gather_start);
        gather_cpu += cpu_seconds_since(gather_cpu_start);
        gather_seconds += gathered;
        state.SetIterationTime(gathered);

        // The same rays through RayScene::intersect and nothing else.
        const std::clock_t scene_cpu_start = std::clock();
        const Clock::time_point scene_start = Clock::now();
        std::uint64_t scene_hits = 0;
        for (const Ray& ray : rays) {
            scene_hits +=
                scene.intersect(ray.origin, ray.direction, kMaxDistance).has_value() ? 1 : 0;
        }
        scene_seconds += seconds_since(scene_start);
        scene_cpu += cpu_seconds_since(scene_cpu_start);

        // And through rtcIntersect1 in one flat BVH.
        const Clock::time_point flat_start = Clock::now();
        std::uint64_t flat_hits = 0;
        for (const Ray& ray : rays) {
            flat_hits += flat.hits(ray.origin, ray.direction, kMaxDistance) ? 1 : 0;
        }
        flat_seconds += seconds_since(flat_start);
        hits = scene_hits;
        benchmark::DoNotOptimize(flat_hits);
    }
    const auto traced = static_cast<double>(state.iterations()) * static_cast<double>(rays.size());
    const double gather_rate = traced / gather_seconds;
    const double scene_rate = traced / scene_seconds;
    const double flat_rate = traced / flat_seconds;
    state.counters["ms_per_texel"] =
        1e3 * gather_seconds /
        (static_cast<double>(state.iterations()) * static_cast<double>(g.texels.size()));
    state.counters["gather_rays_per_s"] = gather_rate;
    state.counters["scene_rays_per_s"] = scene_rate;
    state.counters["flat_rays_per_s"] = flat_rate;
    state.counters["ratio"] = gather_rate / scene_rate;
    state.counters["cpu_ratio"] = scene_cpu / gather_cpu;
    state.counters["flat_ratio"] = gather_rate / flat_rate;
    state.counters["hit_fraction"] = static_cast<double>(hits) / static_cast<double>(rays.size());
    state.counters["triangles"] = static_cast<double>(scene.triangle_count());
}
BENCHMARK(Gather)
    ->ArgsProduct({{0, 1, 2}, {64, 256}})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

// --- AIM rebuild
// ----------------------------------------------------------------------------------

void AimRebuild(benchmark::State& state) {
    static const std::unique_ptr<Level> level = std::make_unique<Level>("cornell");
    IlluminationMaps& maps = *level->maps;
    const PhotonMap& map = level->photons->photon_map();
    std::vector<std::uint32_t> surfaces;
    std::size_t texels = 0;
    std::size_t photons = 0;
    for (std::uint32_t s = 0; s < maps.surfaces().size(); ++s) {
        if (!maps.surfaces()[s].texels.texels.empty()) {
            surfaces.push_back(s);
            texels += maps.surfaces()[s].texels.texels.size();
            photons += map.surface(s).hit_count();
        }
    }
    double total = 0.0;
    double largest = 0.0;
    for (auto _ : state) {
        double pass = 0.0;
        for (const std::uint32_t s : surfaces) {
            const Clock::time_point start = Clock::now();
            maps.rebuild_aim(s);
            const double one = seconds_since(start);
            largest = std::max(largest, one);
            pass += one;
        }
        total += pass;
        state.SetIterationTime(pass);
    }
    const auto passes = static_cast<double>(state.iterations());
    state.counters["surfaces"] = static_cast<double>(surfaces.size());
    state.counters["texels"] = static_cast<double>(texels);
    state.counters["photons"] = static_cast<double>(photons);
    state.counters["ms_per_surface"] =
        1e3 * total / (passes * static_cast<double>(surfaces.size()));
    state.counters["max_surface_ms"] = 1e3 * largest;
    state.counters["ms_per_texel"] = 1e3 * total / (passes * static_cast<double>(texels));
}
BENCHMARK(AimRebuild)->UseManualTime()->Unit(benchmark::kMillisecond);

// --- a gather unit's cost beyond its rays
// ----------------------------------------------------------------------------------

void GatherUnit(benchmark::State& state) {
    static const std::unique_ptr<Level> level = std::make_unique<Level>("two-rooms");
    IlluminationMaps& maps = *level->maps;
    std::uint32_t largest = 0;
    for (std::uint32_t s = 0; s < maps.surfaces().size(); ++s) {
        if (maps.surfaces()[s].texels.texels.size() >
            maps.surfaces()[largest].texels.texels.size()) {
            largest = s;
        }
    }
    constexpr std::size_t kUnitTexels = 20;
    constexpr int kUnits = 50;
    CpuGatherer gatherer(level->photons->ray_scene(), maps.aim(), {64, 1e6f});
    const std::vector<GatherTexel> world = maps.world_texels(largest);
    std::vector<glm::vec3> out(kUnitTexels);
    double unit_seconds = 0.0;
    double gather_seconds = 0.0;
    std::size_t at = 0;
    for (auto _ : state) {
        const Clock::time_point unit_start = Clock::now();
        for (int u = 0; u < kUnits; ++u) {
            benchmark::DoNotOptimize(maps.gather(largest, kUnitTexels, gatherer, 0.0));
        }
        const double units = seconds_since(unit_start);
        unit_seconds += units;
        const Clock::time_point gather_start = Clock::now();
        for (int u = 0; u < kUnits; ++u) {
            at = at + kUnitTexels > world.size() ? 0 : at;
            gatherer.gather(std::span<const GatherTexel>(world.data() + at, kUnitTexels), out);
            benchmark::DoNotOptimize(out.data());
            at += kUnitTexels;
        }
        gather_seconds += seconds_since(gather_start);
        state.SetIterationTime(units);
    }
    const double count = static_cast<double>(state.iterations()) * kUnits;
    state.counters["unit_ms"] = 1e3 * unit_seconds / count;
    state.counters["gather_ms"] = 1e3 * gather_seconds / count;
    state.counters["ratio"] = unit_seconds / std::max(gather_seconds, 1e-12);
    state.counters["surface_texels"] =
        static_cast<double>(maps.surfaces()[largest].texels.texels.size());
}
BENCHMARK(GatherUnit)->UseManualTime()->Unit(benchmark::kMillisecond);

// --- a seam stitch against a gather unit
// ----------------------------------------------------------------------------------

/// What stitching costs each pass that commits a surface on a seam: the sandbox's objects
/// (floors and ceilings of eight surfaces, walls of five to eight), each object's system solved
/// once per iteration, against the scheduler's gather unit (20 texels at 64 rays) timed in the
/// same run.
void SeamStitch(benchmark::State& state) {
    static const std::unique_ptr<Level> level = std::make_unique<Level>("sandbox");
    IlluminationMaps& maps = *level->maps;
    // One stitcher per object, as the gather passes hold them (samples grouped by entity).
    std::map<ecs::Entity, std::vector<SeamSample>> objects;
    for (const SeamSample& sample : maps.seam_samples()) {
        objects[maps.surfaces()[sample.surface_a].entity].push_back(sample);
    }
    SeamStitcher stitcher;
    std::vector<std::uint32_t> first_surfaces;
    for (auto& [entity, samples] : objects) {
        first_surfaces.push_back(samples.front().surface_a);
        stitcher.add_object(std::move(samples), maps.iim_pages());
    }
    // Every surface committed once, so each stitch solves.
    for (const SeamSample& sample : maps.seam_samples()) {
        stitcher.stitch(sample.surface_a, maps.iim_pages(), 0.0, 0.0);
        stitcher.stitch(sample.surface_b, maps.iim_pages(), 0.0, 0.0);
    }
    CpuGatherer gatherer(level->photons->ray_scene(), maps.aim(), {64, 1e6f});
    const std::vector<GatherTexel> texels = level->floor_texels(20);
    std::vector<glm::vec3> out(texels.size());
    double stitch_seconds = 0.0;
    double gather_seconds = 0.0;
    for (auto _ : state) {
        const Clock::time_point start = Clock::now();
        for (const std::uint32_t surface : first_surfaces) {
            stitcher.stitch(surface, maps.iim_pages(), 0.0, 0.0);
        }
        const double stitched = seconds_since(start);
        stitch_seconds += stitched;
        state.SetIterationTime(stitched);
        const Clock::time_point gather_start = Clock::now();
        gatherer.gather(texels, out);
        benchmark::DoNotOptimize(out.data());
        gather_seconds += seconds_since(gather_start);
    }
    const double iterations = static_cast<double>(state.iterations());
    const double per_object = stitch_seconds / (iterations * static_cast<double>(objects.size()));
    state.counters["objects"] = static_cast<double>(objects.size());
    state.counters["seam_texels"] = static_cast<double>(stitcher.texels());
    state.counters["stitch_ms"] = 1e3 * per_object;
    state.counters["gather_unit_ms"] = 1e3 * gather_seconds / iterations;
    state.counters["ratio"] = per_object / std::max(gather_seconds / iterations, 1e-12);
}
BENCHMARK(SeamStitch)->UseManualTime()->Unit(benchmark::kMillisecond);

// --- finding the seams at load, against loading the level
// ----------------------------------------------------------------------------------

/// What MapRegistry adds to a level's load by finding its light-map seams (find_seams per
/// object), against scene::load_gltf of the same file timed in the same run: cornell-133k, whose
/// floor is 130,000 triangles.
void FindSeams(benchmark::State& state) {
    static const std::unique_ptr<Level> level = std::make_unique<Level>("cornell-133k");
    const IlluminationMaps& maps = *level->maps;
    std::map<ecs::Entity, std::vector<SeamSurface>> objects;
    std::size_t triangles = 0;
    for (std::uint32_t s = 0; s < maps.surfaces().size(); ++s) {
        const SurfaceInfo& info = level->photons->surfaces()[s];
        const auto* instance = level->registry.try_get<scene::MeshInstance>(info.entity);
        const std::int32_t page = maps.aim().surface_page.at(s);
        if (instance == nullptr || info.primitive < 0 || page < 0) {
            continue;
        }
        const scene::Primitive& primitive =
            instance->geometry().primitives.at(static_cast<std::size_t>(info.primitive));
        triangles += primitive.triangle_count();
        const MapSurface& mapped = maps.surfaces()[s];
        objects[info.entity].push_back(
            {s, &primitive, page, mapped.texels.page_size, mapped.content, mapped.albedo});
    }
    double find_seconds = 0.0;
    double load_seconds = 0.0;
    std::size_t samples = 0;
    for (auto _ : state) {
        const Clock::time_point start = Clock::now();
        samples = 0;
        for (const auto& [entity, surfaces] : objects) {
            samples += find_seams(surfaces).size();
        }
        const double found = seconds_since(start);
        find_seconds += found;
        state.SetIterationTime(found);
        const Clock::time_point load_start = Clock::now();
        benchmark::DoNotOptimize(scene::load_gltf(prepared("cornell-133k")).meshes.size());
        load_seconds += seconds_since(load_start);
    }
    const double iterations = static_cast<double>(state.iterations());
    state.counters["triangles"] = static_cast<double>(triangles);
    state.counters["samples"] = static_cast<double>(samples);
    state.counters["find_ms"] = 1e3 * find_seconds / iterations;
    state.counters["load_ms"] = 1e3 * load_seconds / iterations;
    state.counters["ratio"] = find_seconds / std::max(load_seconds, 1e-12);
}
BENCHMARK(FindSeams)->UseManualTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
