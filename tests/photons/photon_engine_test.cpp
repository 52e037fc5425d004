// Selective photon emission: energy, Russian roulette, probes that detect change, compact
// groups and determinism (the map's own storage: photon_map_test.cpp).

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "luxel/lighting/core/halton.hpp"
#include "luxel/lighting/core/photon_map.hpp"
#include "luxel/lighting/core/selective_emitter.hpp"
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
        run_probes(scene, materials, lights, map, frame, jobs, invalid);
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
            if (map.diverges(g, p, hops)) {
                affected.push_back(g);
                break;
            }
        }
    }
    ASSERT_FALSE(affected.empty());
    // Within M frames every affected group's probes have found the change, and no other group.
    invalid.clear();
    for (std::uint64_t frame = 0; frame < settings.per_group; ++frame) {
        run_probes(scene, materials, lights, map, frame, jobs, invalid);
    }
    std::sort(invalid.begin(), invalid.end());
    invalid.erase(std::unique(invalid.begin(), invalid.end()), invalid.end());
    EXPECT_EQ(invalid, affected);
    EXPECT_LT(affected.size(), settings.groups);  // locality: not everything
    // Retracing them brings the map back in step: no probe diverges any more.
    retrace_groups(scene, materials, lights, map, affected, jobs);
    invalid.clear();
    for (std::uint64_t frame = 0; frame < settings.per_group; ++frame) {
        run_probes(scene, materials, lights, map, frame, jobs, invalid);
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
            for (std::size_t i = 0; i < map.surface(s).hit_count(); ++i) {
                hits.push_back(map.hit(s, i));
            }
        }
        return hits;
    };
    const auto one = run(1);
    const auto two = run(2);
    ASSERT_EQ(one.size(), two.size());
    ASSERT_GT(one.size(), 3000u);
    EXPECT_EQ(std::memcmp(one.data(), two.data(), one.size() * sizeof(StoredHit)), 0);
}

}  // namespace
