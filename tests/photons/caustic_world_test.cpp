// Caustics fed by the ECS: lists per (generator, light), what invalidates them, the slice
// schedule under movement, no cost without generators, and thread-count independence.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <span>
#include <vector>

#include <gtest/gtest.h>

#include "luxel/ecs/transform_system.hpp"
#include "luxel/lighting/components.hpp"
#include "luxel/lighting/core/photon_world.hpp"
#include "luxel/scene/gltf.hpp"
#include "luxel/world/animation_system.hpp"
#include "luxel/world/scene_instance.hpp"
#include "luxel/world/vertex_wave.hpp"
#include "test_paths.hpp"

namespace {

using namespace luxel;

struct CausticLevel {
    ecs::Registry registry;
    world::SceneInstance instance;
    ecs::TransformSystem transforms{registry};
    std::unique_ptr<lighting::PhotonWorld> photons;
    JobSystem jobs;

    /// `refinement_photons` 0 (the default here): no progressive generations, so the slice
    /// schedule alone is seen. `stand_in`: CausticSettings::stand_in.
    explicit CausticLevel(const std::string& name, int threads = 2,
                          std::uint32_t photons_per_pair = 2'000,
                          std::uint32_t refinement_photons = 0,
                          std::uint32_t max_photons = 1'000'000, bool stand_in = true)
        : jobs(threads) {
        world::InstantiateOptions options;
        options.play_animations = false;
        instance = world::instantiate(
            registry,
            std::make_shared<scene::Scene>(scene::load_gltf(luxel::testing::source_dir() /
                                                            "assets" / "levels" / (name + ".glb"))),
            options);
        transforms.update();
        lighting::PhotonWorldSettings settings;
        settings.caustics.photons_per_pair = photons_per_pair;
        settings.caustics.refinement_photons = refinement_photons;
        settings.caustics.max_photons = max_photons;
        settings.caustics.stand_in = stand_in;
        photons = std::make_unique<lighting::PhotonWorld>(registry, settings);
        photons->sync();
    }
    /// One frame: animations advance by `dt` seconds (0: nothing moves), then sync and one
    /// caustic slice.
    lighting::CausticFrameStats frame(std::uint64_t index, double dt = 0.0) {
        if (dt > 0.0) {
            for (ecs::Entity animation : instance.animations) {
                registry.get<world::AnimationPlayer>(animation).playing = true;
            }
            world::update_animations(registry, dt);
        }
        transforms.update();
        photons->sync();
        return photons->update_caustics(index, jobs);
    }
    [[nodiscard]] const lighting::CausticPhotonList& only_list() const {
        return photons->caustics().front().photons;
    }
};

TEST(CausticWorld, NoGeneratorMeansNoListsAndNoCausticPhotons) {
    CausticLevel level("two-rooms");  // plaster, wood and paint: nothing specular
    for (std::uint64_t frame = 0; frame < 12; ++frame) {
        const auto stats = level.frame(frame, 1.0 / 30.0);  // the door swings meanwhile
        EXPECT_EQ(stats.slices_retraced, 0u);
        EXPECT_EQ(stats.trace.photons, 0u);
        EXPECT_EQ(stats.trace.segments, 0u);
    }
    EXPECT_TRUE(level.photons->caustics().empty());
    EXPECT_EQ(level.photons->caustic_totals().bytes, 0u);

    // The Cornell box has one: its list exists until the component goes.
    CausticLevel cornell("cornell");
    ASSERT_EQ(cornell.photons->caustics().size(), 1u);
    EXPECT_GT(cornell.frame(0).trace.photons, 0u);
    cornell.registry.remove<lighting::CausticGenerator>(cornell.instance.find("glass sphere"));
    const auto after = cornell.frame(1);
    EXPECT_TRUE(cornell.photons->caustics().empty());
    EXPECT_EQ(after.trace.photons, 0u);
    EXPECT_EQ(cornell.photons->caustic_totals().bytes, 0u);
}

TEST(CausticWorld, AfterKFramesOfMovementTheListHasBeenRetracedExactlyOnce) {
    // The slice schedule alone: stand-ins (METHOD 7.6) rewrite slices they did not retrace.
    CausticLevel level("cornell", 2, 2'000, 0, 1'000'000, false);
    ASSERT_EQ(level.photons->caustics().size(), 1u);
    ASSERT_EQ(level.only_list().slice_count(), 8u);
    auto expect_retraces = [&](std::uint64_t times) {
        ASSERT_EQ(level.photons->caustics().size(), 1u);
        for (std::uint32_t k = 0; k < 8; ++k) {
            EXPECT_EQ(level.only_list().slice_retraces(k), times) << "slice " << k;
        }
    };
    // A new list fills over K frames, one slice each.
    for (std::uint64_t frame = 0; frame < 8; ++frame) {
        const auto stats = level.frame(frame);
        EXPECT_EQ(stats.slices_retraced, 1u);
        EXPECT_EQ(stats.trace.photons,
                  level.only_list().slice_size(static_cast<std::uint32_t>(frame)));
    }
    expect_retraces(1);
    // The glass sphere focuses light onto the floor.
    EXPECT_GT(level.only_list().stored_count(), 200u);
    // Nothing moves: nothing is traced.
    for (std::uint64_t frame = 8; frame < 16; ++frame) {
        EXPECT_EQ(level.frame(frame).trace.photons, 0u);
    }
    expect_retraces(1);
    // K frames of movement (the sphere orbits, the cube slides): each slice once more.
    for (std::uint64_t frame = 16; frame < 24; ++frame) {
        EXPECT_EQ(level.frame(frame, 1.0 / 30.0).slices_retraced, 1u);
    }
    expect_retraces(2);
    // Movement stops. The slices traced before the last move are stale: the K - 1 other than
    // the one traced in that last frame (slice 23 mod 8 = 7) are retraced once more, then quiet.
    for (std::uint64_t frame = 24; frame < 31; ++frame) {
        EXPECT_EQ(level.frame(frame).slices_retraced, 1u);
    }
    for (std::uint32_t k = 0; k < 8; ++k) {
        EXPECT_EQ(level.only_list().slice_retraces(k), k == 7 ? 2u : 3u) << "slice " << k;
    }
    EXPECT_EQ(level.frame(31).trace.photons, 0u);
}

TEST(CausticWorld, ALightChangeInvalidatesOnlyItsOwnLists) {
    CausticLevel level("caustics", 2, 1'000);
    // Three generators (brass ring, glass sphere, water) times three lights.
    ASSERT_EQ(level.photons->caustics().size(), 9u);
    for (std::uint64_t frame = 0; frame < 8; ++frame) {
        level.frame(frame);
    }
    EXPECT_GT(level.photons->caustic_totals().stored, 1000u);
    const ecs::Entity box_light = level.instance.find("box light");
    ASSERT_NE(box_light, ecs::null_entity);
    level.registry.patch<ecs::Transform>(box_light,
                                         [](ecs::Transform& t) { t.translation.x += 0.2f; });
    level.transforms.update();
    level.photons->sync();
    int invalidated = 0;
    for (const lighting::CausticPair& pair : level.photons->caustics()) {
        EXPECT_EQ(pair.photons.needs_retrace(), pair.light == box_light);
        invalidated += pair.photons.needs_retrace() ? 1 : 0;
    }
    EXPECT_EQ(invalidated, 3);
    // Switching it off removes its lists; back on, they come back empty and are retraced.
    level.registry.patch<lighting::PointLight>(box_light,
                                               [](lighting::PointLight& l) { l.enabled = false; });
    level.photons->sync();
    EXPECT_EQ(level.photons->caustics().size(), 6u);
    level.registry.patch<lighting::PointLight>(box_light,
                                               [](lighting::PointLight& l) { l.enabled = true; });
    level.photons->sync();
    EXPECT_EQ(level.photons->caustics().size(), 9u);
}

TEST(CausticWorld, TheGeneratorComponentSetsTheOptics) {
    CausticLevel level("cornell");
    const ecs::Entity sphere = level.instance.find("glass sphere");
    const glm::vec3 centre = level.registry.get<ecs::WorldTransform>(sphere).position();
    auto optics_at_sphere = [&] {
        // From 0.5 m above the centre (the sphere's radius is 0.25 m, the ceiling 1.5 m up).
        const auto hit = level.photons->ray_scene().intersect(centre + glm::vec3(0, 0.5f, 0),
                                                              glm::vec3(0, -1, 0));
        EXPECT_TRUE(hit.has_value());
        return level.photons->materials().at(hit->material);
    };
    EXPECT_EQ(optics_at_sphere().scattering, lighting::Scattering::Dielectric);
    EXPECT_FLOAT_EQ(optics_at_sphere().ior, 1.5f);
    for (std::uint64_t frame = 0; frame < 8; ++frame) {
        level.frame(frame);
    }
    ASSERT_FALSE(level.only_list().needs_retrace());
    level.registry.patch<lighting::CausticGenerator>(sphere, [](lighting::CausticGenerator& g) {
        g.ior = 1.33f;
        g.tint = glm::vec3(0.5f);
    });
    level.photons->sync();
    EXPECT_TRUE(level.only_list().needs_retrace());
    EXPECT_FLOAT_EQ(optics_at_sphere().ior, 1.33f);
    EXPECT_FLOAT_EQ(optics_at_sphere().tint.g, 0.5f);
    level.registry.patch<lighting::CausticGenerator>(
        sphere, [](lighting::CausticGenerator& g) { g.transmission = 0.0f; });
    level.photons->sync();
    EXPECT_EQ(optics_at_sphere().scattering, lighting::Scattering::Mirror);
}

/// Where the sun's light through the water lands on the pool floor (y = -0.4 m, x in [-1, 1],
/// z in [0.5, 2.5]), folded onto one wavelength: the share of its caustic photons' power at
/// each phase of u = d . (x, z) / wavelength, in 20 bins. A travelling wave's caustic is a
/// travelling pattern of bright lines; folding it onto the wave's phase gathers every line's
/// photons into one profile, so photon noise hardly shows.
std::vector<double> pool_floor_profile(const CausticLevel& level, ecs::Entity water,
                                       ecs::Entity sun, const world::WaveParameters& wave) {
    constexpr int kBins = 20;
    std::vector<double> bins(kBins, 0.0);
    double total = 0.0;
    for (const lighting::CausticPair& pair : level.photons->caustics()) {
        if (pair.generator != water || pair.light != sun) {
            continue;
        }
        for (std::uint32_t k = 0; k < pair.photons.slice_count(); ++k) {
            for (const lighting::CausticPhoton& photon : pair.photons.slice(k)) {
                // The pool's floor, away from its walls' shadows and reflections.
                if (std::abs(photon.position.y + 0.4f) > 0.01f ||
                    std::abs(photon.position.x) > 0.8f ||
                    std::abs(photon.position.z - 1.5f) > 0.8f) {
                    continue;
                }
                const double u =
                    (wave.direction.x * photon.position.x + wave.direction.y * photon.position.z) /
                    wave.wavelength;
                const double phase = u - std::floor(u);
                const int bin = std::min(static_cast<int>(phase * kBins), kBins - 1);
                const double power = photon.power.x + photon.power.y + photon.power.z;
                bins[static_cast<std::size_t>(bin)] += power;
                total += power;
            }
        }
    }
    for (double& bin : bins) {
        bin = total > 0.0 ? bin / total : 0.0;
    }
    return bins;
}

/// Half the L1 distance between two profiles of shares, the second turned by `shift` bins:
/// 0 the same, 1 nowhere alike.
double profile_change(const std::vector<double>& a, const std::vector<double>& b, int shift = 0) {
    const auto n = static_cast<int>(a.size());
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        sum += std::abs(a[static_cast<std::size_t>(i)] -
                        b[static_cast<std::size_t>(((i - shift) % n + n) % n)]);
    }
    return 0.5 * sum;
}

TEST(CausticWorld, TheCausticThroughMovingWaterFollowsTheWave) {
    CausticLevel level("caustics", 2, 20'000);
    const ecs::Entity water = level.instance.find("water surface");
    const ecs::Entity sun = level.instance.find("sun");
    ASSERT_NE(water, ecs::null_entity);
    ASSERT_NE(sun, ecs::null_entity);
    ASSERT_TRUE(level.registry.has<world::VertexWave>(water));
    const world::WaveParameters wave = level.registry.get<world::VertexWave>(water).wave;
    const double period = wave.wavelength / wave.speed;
    std::uint64_t frame = 0;
    // The wave steps by `dt`, then the lists are retraced in full (K slices, K frames).
    const auto profile_after = [&](double dt) {
        if (dt > 0.0) {
            EXPECT_EQ(world::update_waves(level.registry, dt), 1u);
        }
        for (int k = 0; k < 8; ++k) {
            level.frame(frame++);
        }
        EXPECT_FALSE(level.photons->caustics_pending());
        return pool_floor_profile(level, water, sun, wave);
    };
    const std::vector<double> start = profile_after(0.0);
    // The crests focus the sun into bright lines: the profile is far from flat.
    const double brightest = *std::max_element(start.begin(), start.end());
    const double darkest = *std::min_element(start.begin(), start.end());
    // A quarter period later the crests have moved a quarter wavelength along the wave, and
    // the lines with them: five of the twenty bins.
    const std::vector<double> quarter = profile_after(period / 4.0);
    // Back at the start of the next period: the same shape, the same caustic.
    const std::vector<double> again = profile_after(3.0 * period / 4.0);
    const double moved = profile_change(quarter, start);
    const double followed = profile_change(quarter, start, 5);
    const double returned = profile_change(again, start);
    std::printf(
        "pool floor caustic over one wavelength: brightest/darkest bin %.2f; a quarter "
        "period later %.3f of its power moved, %.3f against the start moved a quarter "
        "wavelength; %.4f after a whole period\n",
        brightest / darkest, moved, followed, returned);
    EXPECT_GT(brightest, 1.5 * darkest);
    EXPECT_GT(moved, 3.0 * followed);
    EXPECT_LT(followed, 0.05);
    EXPECT_LT(returned, 0.01);
}

/// The glass sphere's caustic on cornell's floor (y within its 1.5 cm bumps of 0, x and z in [-1,
/// 1]): irradiance in 24 x 24 cells, watts per square metre per channel summed.
std::vector<double> floor_irradiance(const lighting::CausticPhotonList& list) {
    constexpr int kCells = 24;
    constexpr double kCellArea = (2.0 / kCells) * (2.0 / kCells);
    std::vector<double> cells(kCells * kCells, 0.0);
    for (std::uint32_t k = 0; k < list.slice_count(); ++k) {
        for (const lighting::CausticPhoton& photon : list.slice(k)) {
            if (std::abs(photon.position.y) > 0.03f || std::abs(photon.position.x) >= 1.0f ||
                std::abs(photon.position.z) >= 1.0f) {
                continue;
            }
            const auto x = static_cast<int>((photon.position.x + 1.0f) / 2.0f * kCells);
            const auto z = static_cast<int>((photon.position.z + 1.0f) / 2.0f * kCells);
            cells[static_cast<std::size_t>(z * kCells + x)] +=
                (photon.power.x + photon.power.y + photon.power.z) / kCellArea;
        }
    }
    return cells;
}

/// relRMSE of `estimate` against `reference` over the cells the reference lights.
double relative_rmse(const std::vector<double>& estimate, const std::vector<double>& reference) {
    double error = 0.0;
    double norm = 0.0;
    for (std::size_t i = 0; i < reference.size(); ++i) {
        error += (estimate[i] - reference[i]) * (estimate[i] - reference[i]);
        norm += reference[i] * reference[i];
    }
    return norm > 0.0 ? std::sqrt(error / norm) : 0.0;
}

TEST(CausticWorld, AStillCausticRefinesGenerationByGenerationAndItsNoiseFalls) {
    // 2,000 photons a generation, refinement room for 7 more generations.
    CausticLevel level("cornell", 2, 2'000, 14'000);
    ASSERT_EQ(level.photons->caustics().size(), 1u);
    const lighting::CausticPhotonList& list = level.only_list();
    EXPECT_EQ(list.generation_limit(), 8u);
    std::uint64_t frame = 0;
    for (; frame < 8; ++frame) {
        const auto stats = level.frame(frame);
        EXPECT_EQ(stats.slices_retraced, 1u);
        EXPECT_EQ(stats.slices_refined, 0u);
    }
    ASSERT_FALSE(list.needs_retrace());
    EXPECT_EQ(list.generations(), 1u);
    const std::vector<double> first = floor_irradiance(list);
    const glm::dvec3 first_power = list.stored_power();
    // Still: one refinement slice a frame; a generation counts once its K slices are in.
    for (; frame < 8 + 7 * 8; ++frame) {
        const auto stats = level.frame(frame);
        EXPECT_EQ(stats.slices_retraced, 0u);
        EXPECT_EQ(stats.slices_refined, 1u);
        EXPECT_EQ(list.generations(), 1u + (frame - 8 + 1) / 8) << "frame " << frame;
    }
    EXPECT_EQ(list.generations(), 8u);
    EXPECT_EQ(list.slice_count(), 64u);
    EXPECT_EQ(level.frame(frame++).trace.photons, 0u) << "at its limit the list rests";
    // The eight generations carry the pair's power once, not eight times.
    const glm::dvec3 refined_power = list.stored_power();
    EXPECT_NEAR(refined_power.x / first_power.x, 1.0, 0.05);
    // Against 64,000 photons: the same Halton sequence, so both estimates are subsets of the
    // reference's points; the error of n of its N photons is the noise of n times
    // sqrt(1 - n / N), and 16,000 photons should show about 0.31 of 2,000's error.
    CausticLevel reference("cornell", 2, 64'000);
    for (std::uint64_t f = 0; f < 8; ++f) {
        reference.frame(f);
    }
    const std::vector<double> truth = floor_irradiance(reference.only_list());
    const double before = relative_rmse(first, truth);
    const double after = relative_rmse(floor_irradiance(list), truth);
    std::printf(
        "cornell floor caustic, relRMSE against 64k photons: %.1f%% with 2k, %.1f%% "
        "with 8 generations of 2k\n",
        100.0 * before, 100.0 * after);
    EXPECT_LT(after, 0.55 * before);

    // A change drops the generations at once, the first generation keeping its power.
    const ecs::Entity cube = level.instance.find("moving cube");
    ASSERT_NE(cube, ecs::null_entity);
    level.registry.patch<ecs::Transform>(cube, [](ecs::Transform& t) { t.translation.x += 0.05f; });
    level.transforms.update();
    level.photons->sync();
    EXPECT_EQ(list.generations(), 1u);
    EXPECT_EQ(list.slice_count(), 8u);
    EXPECT_TRUE(list.needs_retrace());
    EXPECT_NEAR(list.stored_power().x / first_power.x, 1.0, 0.05);
    EXPECT_EQ(level.frame(frame++).slices_refined, 0u) << "retraces come first";
}

/// Caustic power (the channels summed) each light-mapped surface receives from `photons`.
void add_by_surface(std::span<const lighting::CausticPhoton> photons, std::map<int, double>& out) {
    for (const lighting::CausticPhoton& photon : photons) {
        out[photon.surface] += photon.power.x + photon.power.y + photon.power.z;
    }
}

TEST(CausticWorld, OverlappingGeneratorsCountEachLightsCausticOnce) {
    // The caustics level's ring spot sees the brass ring and, in some of the same directions,
    // another generator's sphere: those pairs' cones overlap. Against one list per
    // light aimed at a sphere around the whole scene, which samples every path once whichever
    // generator it meets first, the lists of the light's pairs together must land the same
    // caustic power on every surface. Counted twice where the cones overlap, the spot's caustic
    // came out 13% too bright on the floor (and one floor tile 17% in luxel-bench).
    CausticLevel level("caustics", 2, 20'000);
    for (std::uint64_t frame = 0; frame < 8; ++frame) {
        level.frame(frame);
    }
    const lighting::RayScene& rays = level.photons->ray_scene();
    const glm::vec3 lo = rays.bounds_min();
    const glm::vec3 hi = rays.bounds_max();
    const lighting::BoundingSphere whole{0.5f * (lo + hi), 0.5f * glm::length(hi - lo)};
    int lights_checked = 0;
    for (const lighting::LightPhotons* light : level.photons->active_lights()) {
        const lighting::LightSource& source = light->emitter().light();
        std::map<int, double> pairs;
        int pair_count = 0;
        for (const lighting::CausticPair& pair : level.photons->caustics()) {
            if (pair.photons.emitter().kind() != source.kind) {
                continue;  // the level has one light of each kind
            }
            ++pair_count;
            ASSERT_FALSE(pair.photons.needs_retrace());
            for (std::uint32_t k = 0; k < pair.photons.slice_count(); ++k) {
                add_by_surface(pair.photons.slice(k), pairs);
            }
        }
        ASSERT_EQ(pair_count, 3);
        lighting::CausticPhotonList everything(160'000, 8, 1234);
        everything.set_emitter(lighting::CausticEmitter(source, whole, whole));
        for (std::uint32_t k = 0; k < 8; ++k) {
            everything.retrace_slice(rays, level.photons->materials(), k, 16, level.jobs);
        }
        std::map<int, double> truth;
        for (std::uint32_t k = 0; k < everything.slice_count(); ++k) {
            add_by_surface(everything.slice(k), truth);
        }
        double total = 0.0;
        double total_truth = 0.0;
        for (const auto& [surface, power] : truth) {
            total_truth += power;
            total += pairs[surface];
        }
        ASSERT_GT(total_truth, 0.0);
        EXPECT_NEAR(total / total_truth, 1.0, 0.03)
            << "light kind " << static_cast<int>(source.kind);
        for (const auto& [surface, power] : truth) {
            if (power < 0.1 * total_truth) {
                continue;  // too few photons to judge against the noise
            }
            std::printf("light kind %d, surface %d: %.4f W, %.3f of the whole-scene list's\n",
                        static_cast<int>(source.kind), surface, pairs[surface],
                        pairs[surface] / power);
            EXPECT_NEAR(pairs[surface] / power, 1.0, 0.05)
                << "light kind " << static_cast<int>(source.kind) << ", surface " << surface;
        }
        ++lights_checked;
    }
    EXPECT_EQ(lights_checked, 3);
}

TEST(CausticWorld, ManyLightsShareTheCausticPhotonBudgetByPower) {
    // Cornell's glass sphere under 200 more lamps of 0.1 to 2 W: 201 pairs of 10,000 photons
    // would hold 2 million; a budget of 40,000 gives each pair a share by the power its light
    // sends toward the sphere. The caustic power landed is what 2,000 photons a pair land.
    const auto add_lamps = [](CausticLevel& level) {
        for (int i = 0; i < 200; ++i) {
            const ecs::Entity lamp = level.registry.create();
            const float watts = 0.1f + 1.9f * static_cast<float>(i % 20) / 19.0f;
            level.registry.emplace<lighting::PointLight>(lamp, glm::vec3(watts), 0.0f, true);
            const float x = -0.8f + 1.6f * static_cast<float>(i % 20) / 19.0f;
            const float z = -0.8f + 1.6f * static_cast<float>(i / 20) / 9.0f;
            level.registry.emplace<ecs::Transform>(lamp, glm::vec3(x, 1.7f, z));
        }
        level.transforms.update();
        level.photons->sync();
    };
    CausticLevel shared("cornell", 2, 10'000, 0, 40'000);
    add_lamps(shared);
    const auto pairs = shared.photons->caustics();
    ASSERT_EQ(pairs.size(), 201u);
    std::uint64_t photons = 0;
    double total_power = 0.0;
    for (const lighting::CausticPair& pair : pairs) {
        photons += pair.photons.photon_count();
        total_power += pair.photons.emitter().nominal_power();
        EXPECT_GE(pair.photons.photon_count(), 8u) << "at least a photon per slice";
    }
    EXPECT_LE(photons, 40'000u);
    EXPECT_GT(photons, 40'000u - 201u) << "only rounding down is left over";
    for (const lighting::CausticPair& pair : pairs) {
        const double expected =
            std::floor(40'000.0 * pair.photons.emitter().nominal_power() / total_power);
        EXPECT_EQ(pair.photons.photon_count(), static_cast<std::uint32_t>(std::max(expected, 8.0)));
    }
    // Without a budget every pair keeps its full count.
    CausticLevel full("cornell", 2, 2'000, 0, 0);
    add_lamps(full);
    for (const lighting::CausticPair& pair : full.photons->caustics()) {
        EXPECT_EQ(pair.photons.photon_count(), 2'000u);
    }
    for (std::uint64_t frame = 0; frame < 8; ++frame) {
        shared.frame(frame);
        full.frame(frame);
    }
    glm::dvec3 shared_power(0.0);
    glm::dvec3 full_power(0.0);
    for (std::size_t i = 0; i < pairs.size(); ++i) {
        shared_power += pairs[i].photons.stored_power();
        full_power += full.photons->caustics()[i].photons.stored_power();
    }
    std::printf(
        "201 pairs, caustic power stored: %.4f W with 40,000 photons shared, %.4f W with "
        "2,000 per pair\n",
        shared_power.x, full_power.x);
    EXPECT_NEAR(shared_power.x / full_power.x, 1.0, 0.03);
}

TEST(CausticWorld, RefinementPhotonsAreSharedByPower) {
    CausticLevel level("caustics", 2, 1'000, 40'000);
    ASSERT_EQ(level.photons->caustics().size(), 9u);
    double total_power = 0.0;
    std::uint32_t extra = 0;
    for (const lighting::CausticPair& pair : level.photons->caustics()) {
        total_power += pair.photons.emitter().nominal_power();
        extra += (pair.photons.generation_limit() - 1) * 1'000;
    }
    EXPECT_LE(extra, 40'000u);
    EXPECT_GT(extra, 40'000u - 9u * 1'000u) << "only rounding down is left over";
    for (const lighting::CausticPair& pair : level.photons->caustics()) {
        const double share = pair.photons.emitter().nominal_power() / total_power;
        const double expected = 1.0 + std::floor(share * 40.0);
        EXPECT_EQ(pair.photons.generation_limit(), static_cast<std::uint32_t>(expected));
    }
}

/// Every photon a caustic list holds, slice by slice.
std::vector<lighting::CausticPhoton> all_photons(const lighting::CausticPhotonList& list) {
    std::vector<lighting::CausticPhoton> photons;
    for (std::uint32_t k = 0; k < list.slice_count(); ++k) {
        photons.insert(photons.end(), list.slice(k).begin(), list.slice(k).end());
    }
    return photons;
}

/// Whether two photon lists hold the same photons byte for byte (a list may be empty: a pair
/// whose photons all missed).
bool same_bytes(const std::vector<lighting::CausticPhoton>& a,
                const std::vector<lighting::CausticPhoton>& b) {
    return a.size() == b.size() &&
           (a.empty() ||
            std::memcmp(a.data(), b.data(), a.size() * sizeof(lighting::CausticPhoton)) == 0);
}

/// Moves a node of the level by `offset` metres and syncs the photon world.
void move_node(CausticLevel& level, const char* name, const glm::vec3& offset) {
    const ecs::Entity entity = level.instance.find(name);
    ASSERT_NE(entity, ecs::null_entity) << name;
    level.registry.patch<ecs::Transform>(entity,
                                         [&](ecs::Transform& t) { t.translation += offset; });
    level.transforms.update();
    level.photons->sync();
}

TEST(CausticWorld, AMoveReAimsOnlyTheListsWhosePathsPassWhereItHappened) {
    // The glass sphere moves 0.2 m: its own lists must be retraced, and any list whose photons
    // passed where it was or where it is; the others keep their photons. Kept or retraced,
    // every list must then hold exactly the photons of a level where the sphere stood there
    // from the start (the same seeds, the same scene): a kept list whose paths the move did
    // change would differ.
    const glm::vec3 offset(0.2f, 0.0f, 0.0f);
    CausticLevel level("caustics", 2, 2'000);
    for (std::uint64_t frame = 0; frame < 8; ++frame) {
        level.frame(frame);
    }
    std::vector<std::vector<lighting::CausticPhoton>> before;
    for (const lighting::CausticPair& pair : level.photons->caustics()) {
        before.push_back(all_photons(pair.photons));
    }
    move_node(level, "glass sphere", offset);
    std::size_t kept = 0;
    const auto pairs = level.photons->caustics();
    ASSERT_EQ(pairs.size(), 9u);
    for (std::size_t i = 0; i < pairs.size(); ++i) {
        if (!pairs[i].photons.needs_retrace()) {
            ++kept;
            const auto now = all_photons(pairs[i].photons);
            EXPECT_TRUE(same_bytes(now, before[i])) << "list " << i;
        }
    }
    std::printf("the glass sphere moved 0.2 m: %zu of 9 caustic lists kept their photons\n", kept);
    EXPECT_GE(kept, 1u) << "lists whose paths pass far from the sphere need no retrace";
    EXPECT_LE(kept, 6u) << "the sphere's own three lists are retraced";
    for (std::uint64_t frame = 8; frame < 16; ++frame) {
        level.frame(frame);
    }

    CausticLevel moved("caustics", 2, 2'000);
    move_node(moved, "glass sphere", offset);
    for (std::uint64_t frame = 0; frame < 8; ++frame) {
        moved.frame(frame);
    }
    const auto expected = moved.photons->caustics();
    ASSERT_EQ(expected.size(), pairs.size());
    for (std::size_t i = 0; i < pairs.size(); ++i) {
        ASSERT_FALSE(pairs[i].photons.needs_retrace());
        const auto got = all_photons(pairs[i].photons);
        const auto want = all_photons(expected[i].photons);
        EXPECT_TRUE(same_bytes(got, want)) << "list " << i;
    }
}

TEST(CausticWorld, AfterAMoveTheCausticIsInItsNewPlaceFromTheFirstRetracedSlice) {
    // Cornell's glass sphere, settled, moves 0.35 m; two frames retrace two slices of eight.
    // Against the caustic of a level where the sphere stood there from the start: with
    // stand-ins the two fresh slices carry the whole caustic where it now is (noisier);
    // without, three quarters of it stay where the sphere was.
    const glm::vec3 offset(0.35f, 0.0f, 0.0f);
    CausticLevel truth("cornell", 2, 16'000);
    move_node(truth, "glass sphere", offset);
    for (std::uint64_t frame = 0; frame < 8; ++frame) {
        truth.frame(frame);
    }
    const std::vector<double> want = floor_irradiance(truth.only_list());
    const glm::dvec3 want_power = truth.only_list().stored_power();

    auto after_one_slice = [&](bool stand_in) {
        CausticLevel level("cornell", 2, 2'000, 0, 1'000'000, stand_in);
        for (std::uint64_t frame = 0; frame < 8; ++frame) {
            level.frame(frame);
        }
        const lighting::CausticPhotonList& list = level.only_list();
        EXPECT_FALSE(list.needs_retrace());
        move_node(level, "glass sphere", offset);
        EXPECT_EQ(list.catching_up(), stand_in);
        EXPECT_EQ(level.frame(8).slices_retraced, 1u);
        EXPECT_FALSE(list.standing_in()) << "one slice of eight shows beside the stale ones";
        EXPECT_EQ(level.frame(9).slices_retraced, 1u);
        EXPECT_EQ(list.standing_in(), stand_in);
        const double error = relative_rmse(floor_irradiance(list), want);
        const double power = list.stored_power().x / want_power.x;
        // The rest of the slices: the list is current, nothing stands in, the stored photons
        // as traced.
        for (std::uint64_t frame = 10; frame < 16; ++frame) {
            level.frame(frame);
        }
        EXPECT_FALSE(list.needs_retrace());
        EXPECT_FALSE(list.standing_in());
        EXPECT_FALSE(list.catching_up());
        return std::pair{error, power};
    };
    const auto [fresh, fresh_power] = after_one_slice(true);
    const auto [stale, stale_power] = after_one_slice(false);  // the old place's power
    std::printf(
        "cornell's sphere moved 0.35 m, two slices of 8 retraced: floor caustic relRMSE %.1f%% "
        "with stand-ins, %.1f%% with the stale slices in view (power %.3f and %.3f of the "
        "truth's)\n",
        100.0 * fresh, 100.0 * stale, fresh_power, stale_power);
    EXPECT_LT(fresh, 0.7 * stale);
    // Two slices of 250 photons carry the pair's power: within their noise of the truth's.
    EXPECT_NEAR(fresh_power, 1.0, 0.1);
    EXPECT_TRUE(std::isfinite(stale_power));
}

TEST(CausticWorld, ASliceTracedInPartsIsTheSliceTracedWholeAndShowsOnlyWhenComplete) {
    // Two generations of 2,000 photons, K = 8: slices of 250 photons.
    CausticLevel whole("cornell", 2, 2'000, 2'000);
    for (std::uint64_t frame = 0; frame < 16; ++frame) {
        whole.frame(frame);
    }
    ASSERT_EQ(whole.only_list().generations(), 2u);

    // The scheduler's way: units of 100 photons, each going on to the next slice when one is
    // complete: 40 units for 16 slices of 250.
    CausticLevel parts("cornell", 2, 2'000, 2'000);
    const lighting::CausticPhotonList& list = parts.only_list();
    EXPECT_EQ(parts.photons->caustic_photons_left(false), 250u);
    auto stats = parts.photons->trace_caustic_unit(100, true, parts.jobs);
    EXPECT_EQ(stats.trace.photons, 100u);
    EXPECT_EQ(stats.slices_retraced, 0u);
    EXPECT_EQ(list.stored_count(), 0u) << "a part of a slice is not shown";
    EXPECT_EQ(parts.photons->caustic_photons_left(false), 150u);
    int units = 1;
    std::uint32_t retraced = 0;
    std::uint32_t refined = 0;
    while (parts.photons->caustics_pending() || parts.photons->caustics_refining()) {
        stats = parts.photons->trace_caustic_unit(100, true, parts.jobs);
        retraced += stats.slices_retraced;
        refined += stats.slices_refined;
        ++units;
        ASSERT_LT(units, 100);
    }
    EXPECT_EQ(units, 40);
    EXPECT_EQ(retraced, 8u);
    EXPECT_EQ(refined, 8u);
    EXPECT_EQ(list.generations(), 2u);
    const auto a = all_photons(whole.only_list());
    const auto b = all_photons(list);
    EXPECT_TRUE(same_bytes(a, b));
    // Without refinement (the warm-up) a current list has no unit work.
    EXPECT_EQ(parts.photons->trace_caustic_unit(100, false, parts.jobs).trace.photons, 0u);

    // A change in the middle of a slice discards the part traced in the old scene.
    const ecs::Entity cube = parts.instance.find("moving cube");
    parts.registry.patch<ecs::Transform>(cube, [](ecs::Transform& t) { t.translation.x += 0.05f; });
    parts.transforms.update();
    parts.photons->sync();
    parts.photons->trace_caustic_unit(100, true, parts.jobs);
    parts.registry.patch<ecs::Transform>(cube, [](ecs::Transform& t) { t.translation.x -= 0.05f; });
    parts.transforms.update();
    parts.photons->sync();
    EXPECT_EQ(parts.photons->caustic_photons_left(false), 250u) << "the part was dropped";
}

TEST(CausticWorld, ACatchingUpCausticOffersAllItNeedsAndAUnitTakesItAcrossSlices) {
    // 2,000 photons in slices of 250, up to three generations (4,000 refinement photons).
    CausticLevel level("cornell", 2, 2'000, 4'000);
    const lighting::CausticPhotonList& list = level.only_list();
    for (int unit = 0;
         unit < 100 && (level.photons->caustics_pending() || level.photons->caustics_refining());
         ++unit) {
        level.photons->trace_caustic_unit(1'000, true, level.jobs);
    }
    ASSERT_EQ(list.generations(), 3u);
    EXPECT_EQ(level.photons->caustic_photons_left(true), 0u) << "settled";

    move_node(level, "glass sphere", glm::vec3(0.2f, 0.0f, 0.0f));
    ASSERT_TRUE(list.catching_up());
    // The warm-up's estimate stays a slice; a frame may take all 24 slices back to three
    // generations, as far as its caustic share has room.
    EXPECT_EQ(level.photons->caustic_photons_left(false), 250u);
    EXPECT_EQ(level.photons->caustic_photons_left(true), 24u * 250u);
    const lighting::CausticFrameStats stats =
        level.photons->trace_caustic_unit(24 * 250, true, level.jobs);
    EXPECT_EQ(stats.slices_retraced, 8u);
    EXPECT_EQ(stats.slices_refined, 16u);
    EXPECT_EQ(list.generations(), 3u);
    EXPECT_FALSE(list.catching_up());
    EXPECT_EQ(level.photons->caustic_photons_left(true), 0u);
}

TEST(CausticWorld, OneAndTwoThreadsStoreIdenticalCausticPhotons) {
    auto run = [](int threads) {
        CausticLevel level("caustics", threads, 3'000);
        for (std::uint64_t frame = 0; frame < 8; ++frame) {
            level.frame(frame);
        }
        std::vector<lighting::CausticPhoton> photons;
        for (const lighting::CausticPair& pair : level.photons->caustics()) {
            for (std::uint32_t k = 0; k < pair.photons.slice_count(); ++k) {
                photons.insert(photons.end(), pair.photons.slice(k).begin(),
                               pair.photons.slice(k).end());
            }
        }
        return photons;
    };
    const auto one = run(1);
    const auto two = run(2);
    ASSERT_GT(one.size(), 2000u);
    EXPECT_TRUE(same_bytes(one, two));
}

}  // namespace
