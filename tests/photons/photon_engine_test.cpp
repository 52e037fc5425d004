// Selective photon emission: energy, Russian roulette, probes that detect change, compact
// groups, determinism, and storage that does not drift.

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "luxel/lighting/core/halton.hpp"
#include "luxel/lighting/core/photon_map.hpp"
#include "luxel/lighting/core/selective_emitter.hpp"
#include "luxel/lighting/core/surface_deltas.hpp"
#include "photon_test_scenes.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;

double total_stored_energy(const PhotonMap& map) {
    double total = 0.0;
    for (std::uint32_t s = 0; s < map.surface_count(); ++s) {
        total += map.surface(s).stored_energy.value();
    }
    return total;
}

struct BoxWorld {
    RayScene scene;
    std::vector<TraceMaterial> materials;
    explicit BoxWorld(float albedo) {
        materials.push_back({Scattering::Diffuse, glm::vec3(albedo), glm::vec3(1.0f), 1.5f});
        scene.add_object(luxel::testing::inward_box(glm::vec3(0.0f), 1.0f, 0, 0), glm::mat4(1.0f),
                         false);
        scene.commit();
    }
};

std::vector<std::uint32_t> all(std::uint32_t count) {
    std::vector<std::uint32_t> groups(count);
    std::iota(groups.begin(), groups.end(), 0u);
    return groups;
}

TEST(PhotonEnergy, FirstHitsInAClosedBoxCarryTheLightsPower) {
    BoxWorld world(0.0f);  // black walls: every photon is stored once
    LightSource light;
    light.kind = LightKind::Point;
    light.position = {0.2f, -0.1f, 0.3f};
    light.power = glm::vec3(30.0f, 20.0f, 10.0f);
    const SelectiveSettings settings;  // 77 x 40
    PhotonMap map(6, settings.groups);
    const LightPhotons photons(PhotonEmitter(light, {}), 0, 1, settings);
    const LightPhotons* lights[] = {&photons};
    JobSystem jobs(2);
    const auto groups = all(settings.groups);
    const auto stats = retrace_groups(world.scene, world.materials, lights, map, groups, jobs);
    EXPECT_EQ(stats.trace.photons, 77u * 40u);
    EXPECT_EQ(map.stored_hit_count(), 77u * 40u);
    EXPECT_NEAR(total_stored_energy(map), 60.0, 60.0 * 0.005);
    // Each of the six faces gets its share of the sphere of directions, within QMC error.
    for (std::uint32_t s = 0; s < 6; ++s) {
        EXPECT_GT(map.surface(s).stored_energy.value(), 60.0 / 6.0 * 0.5) << "face " << s;
    }
}

TEST(PhotonEnergy, RussianRouletteStoresTheGeometricSeries) {
    for (float albedo : {0.3f, 0.5f, 0.8f}) {
        BoxWorld world(albedo);
        LightSource light;
        light.power = glm::vec3(10.0f);
        SelectiveSettings settings;
        settings.groups = 77;
        settings.per_group = 200;
        PhotonMap map(6, settings.groups);
        const LightPhotons photons(PhotonEmitter(light, {}), 0, 7, settings);
        const LightPhotons* lights[] = {&photons};
        JobSystem jobs(2);
        retrace_groups(world.scene, world.materials, lights, map, all(settings.groups), jobs);
        // Every stored hit carries the photon's unchanged power (grey albedo: power * rho / p =
        // power), and a photon is stored 1 / (1 - rho) times on average.
        const double expected = 30.0 / (1.0 - static_cast<double>(albedo));
        EXPECT_NEAR(total_stored_energy(map), expected, expected * 0.01) << "albedo " << albedo;
    }
}

TEST(PhotonGroups, PartitionIsExactCompactAndDeterministic) {
    const auto groups = partition_into_groups(77, 40);
    ASSERT_EQ(groups.size(), 77u);
    std::vector<std::uint64_t> every;
    for (const auto& group : groups) {
        ASSERT_EQ(group.size(), 40u);
        EXPECT_TRUE(std::is_sorted(group.begin(), group.end()));
        every.insert(every.end(), group.begin(), group.end());
        // Compact: the group's points fit in a box far smaller than the unit square.
        glm::dvec2 lo(1.0);
        glm::dvec2 hi(0.0);
        for (std::uint64_t index : group) {
            lo = glm::min(lo, halton2(index));
            hi = glm::max(hi, halton2(index));
        }
        EXPECT_LT((hi.x - lo.x) * (hi.y - lo.y), 4.0 / 77.0);
    }
    std::sort(every.begin(), every.end());
    for (std::size_t i = 0; i < every.size(); ++i) {
        ASSERT_EQ(every[i], i + 1);  // each index exactly once
    }
    EXPECT_EQ(partition_into_groups(77, 40), groups);
}

TEST(PhotonProbes, AStaticSceneNeverDivergesAndAMovedCubeIsFoundWithinMFrames) {
    RayScene scene;
    std::vector<TraceMaterial> materials = {
        {Scattering::Diffuse, glm::vec3(0.6f), glm::vec3(1.0f), 1.5f},
        {Scattering::Diffuse, glm::vec3(0.6f), glm::vec3(1.0f), 1.5f}};
    scene.add_object(luxel::testing::inward_box(glm::vec3(0.0f), 2.0f, 0, 0), glm::mat4(1.0f),
                     false);
    const ObjectId cube =
        scene.add_object(luxel::testing::outward_box(0.25f, 1),
                         glm::translate(glm::mat4(1.0f), {1.0f, -1.5f, 0.0f}), true);
    scene.commit();
    LightSource light;
    light.position = {0.0f, 1.5f, 0.0f};
    light.power = glm::vec3(50.0f);
    SelectiveSettings settings;
    settings.groups = 32;
    settings.per_group = 16;
    PhotonMap map(6, settings.groups);
    const LightPhotons photons(PhotonEmitter(light, {}), 0, 3, settings);
    const LightPhotons* lights[] = {&photons};
    JobSystem jobs(2);
    retrace_groups(scene, materials, lights, map, all(settings.groups), jobs);

    std::vector<std::uint32_t> invalid;
    for (std::uint64_t frame = 0; frame < settings.per_group; ++frame) {
        run_probes(scene, materials, lights, map, frame, settings.tolerance, jobs, invalid);
    }
    EXPECT_TRUE(invalid.empty()) << invalid.size() << " groups diverged in a static scene";

    // Which groups' stored paths touch the cube's old or new place? Trace them all and look.
    scene.set_transform(cube, glm::translate(glm::mat4(1.0f), {-0.5f, -1.5f, 0.3f}));
    scene.commit();
    std::vector<std::uint32_t> affected;
    for (std::uint32_t g = 0; g < settings.groups; ++g) {
        TraceCounters counters;
        const TracedGroup now = photons.trace_group(scene, materials, g, counters);
        for (std::uint32_t p = 0; p < settings.per_group; ++p) {
            const std::span<const TracedHop> hops(now.hops.data() + now.starts[p],
                                                  now.starts[p + 1] - now.starts[p]);
            if (map.diverges(g, p, hops, settings.tolerance)) {
                affected.push_back(g);
                break;
            }
        }
    }
    ASSERT_FALSE(affected.empty());
    // Within M frames every affected group's probes have found the change, and no other group.
    invalid.clear();
    for (std::uint64_t frame = 0; frame < settings.per_group; ++frame) {
        run_probes(scene, materials, lights, map, frame, settings.tolerance, jobs, invalid);
    }
    std::sort(invalid.begin(), invalid.end());
    invalid.erase(std::unique(invalid.begin(), invalid.end()), invalid.end());
    EXPECT_EQ(invalid, affected);
    EXPECT_LT(affected.size(), settings.groups);  // locality: not everything
    // Retracing them brings the map back in step: no probe diverges any more.
    retrace_groups(scene, materials, lights, map, affected, jobs);
    invalid.clear();
    for (std::uint64_t frame = 0; frame < settings.per_group; ++frame) {
        run_probes(scene, materials, lights, map, frame, settings.tolerance, jobs, invalid);
    }
    EXPECT_TRUE(invalid.empty());
}

TEST(PhotonDeterminism, OneAndTwoThreadsStoreIdenticalPhotons) {
    auto run = [](int threads) {
        BoxWorld world(0.7f);
        LightSource light;
        light.kind = LightKind::Spot;
        light.position = {0.0f, 0.9f, 0.0f};
        light.direction = {0.0f, -1.0f, 0.0f};
        light.power = glm::vec3(40.0f);
        const SelectiveSettings settings;
        PhotonMap map(6, settings.groups);
        const LightPhotons photons(PhotonEmitter(light, {}), 0, 11, settings);
        const LightPhotons* lights[] = {&photons};
        JobSystem jobs(threads);
        retrace_groups(world.scene, world.materials, lights, map, all(settings.groups), jobs);
        std::vector<StoredHit> hits;
        for (std::uint32_t s = 0; s < 6; ++s) {
            hits.insert(hits.end(), map.surface(s).hits.begin(), map.surface(s).hits.end());
        }
        return hits;
    };
    const auto one = run(1);
    const auto two = run(2);
    ASSERT_EQ(one.size(), two.size());
    ASSERT_GT(one.size(), 3000u);
    EXPECT_EQ(std::memcmp(one.data(), two.data(), one.size() * sizeof(StoredHit)), 0);
}

TEST(PhotonMapStorage, AMillionAddRemoveCyclesDoNotDrift) {
    // Powers spanning twelve orders of magnitude, stored and removed group by group.
    PhotonMap map(4, 64);
    std::uint64_t cycles = 0;
    for (int round = 0; round < 400; ++round) {
        for (std::uint32_t g = 0; g < 64; ++g) {
            TracedGroup traced;
            traced.starts.push_back(0);
            for (int k = 0; k < 40; ++k) {
                const double scale = std::pow(10.0, -6.0 + 12.0 * radical_inverse(3, cycles + 1));
                const auto power = static_cast<float>(scale * (1.0 + radical_inverse(5, cycles)));
                traced.hops.push_back({glm::vec3(float(k)), glm::vec3(power, 0.5f * power, 0.0f),
                                       static_cast<std::int32_t>((g + k) % 4), kNoObject,
                                       static_cast<std::uint32_t>(k % 3)});
                traced.starts.push_back(static_cast<std::uint32_t>(traced.hops.size()));
                ++cycles;
            }
            map.replace_group(g, traced);
        }
    }
    EXPECT_GE(cycles, 1'000'000u);
    for (std::uint32_t s = 0; s < 4; ++s) {
        const double running = map.surface(s).stored_energy.value();
        const double recount = map.recount_energy(s);
        EXPECT_NEAR(running, recount, 1e-9 * std::abs(recount)) << "surface " << s;
        // Back-references stay consistent: every hit's owner hop points back at it.
        for (std::uint32_t slot = 0; slot < map.surface(s).hits.size(); ++slot) {
            const StoredHit& hit = map.surface(s).hits[slot];
            ASSERT_LT(hit.group_index(), 64u);
        }
    }
    for (std::uint32_t g = 0; g < 64; ++g) {
        map.clear_group(g);
    }
    EXPECT_EQ(map.stored_hit_count(), 0u);
    for (std::uint32_t s = 0; s < 4; ++s) {
        EXPECT_NEAR(map.surface(s).stored_energy.value(), 0.0, 1e-9);
    }
}

TEST(PhotonMapStorage, DeltasCountStoredAndRemovedEnergyAndReset) {
    PhotonMap map(1, 1);
    TracedGroup traced;
    traced.starts = {0, 2};
    traced.hops = {{glm::vec3(0.0f), glm::vec3(1.0f), 0, kNoObject, 0},
                   {glm::vec3(1.0f), glm::vec3(0.5f), 0, kNoObject, 1}};
    map.replace_group(0, traced);
    SurfaceDeltas deltas;
    EXPECT_DOUBLE_EQ(deltas.full(map, 0), 4.5);
    EXPECT_DOUBLE_EQ(deltas.indirect(map, 0), 1.5);
    deltas.consume_full(map, 0);
    EXPECT_DOUBLE_EQ(deltas.full(map, 0), 0.0);
    EXPECT_DOUBLE_EQ(deltas.indirect(map, 0), 1.5);
    map.replace_group(0, traced);  // removes 4.5 and stores 4.5
    EXPECT_DOUBLE_EQ(deltas.full(map, 0), 9.0);
    EXPECT_DOUBLE_EQ(deltas.indirect(map, 0), 4.5);
    // A second reader keeps its own position: what the first consumed is still new to it.
    SurfaceDeltas other;
    EXPECT_DOUBLE_EQ(other.full(map, 0), 13.5);
    other.consume_indirect(map, 0);
    EXPECT_DOUBLE_EQ(other.indirect(map, 0), 0.0);
    EXPECT_DOUBLE_EQ(deltas.indirect(map, 0), 4.5);
    EXPECT_EQ(sizeof(StoredHit), 32u);
}

}  // namespace
