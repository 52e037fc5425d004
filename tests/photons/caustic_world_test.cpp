// Caustics fed by the ECS: lists per (generator, light), what invalidates them, the slice
// schedule under movement, no cost without generators, and thread-count independence.

#include <cstring>

#include <gtest/gtest.h>

#include "luxel/ecs/transform_system.hpp"
#include "luxel/lighting/components.hpp"
#include "luxel/lighting/core/photon_world.hpp"
#include "luxel/scene/gltf.hpp"
#include "luxel/world/animation_system.hpp"
#include "luxel/world/scene_instance.hpp"

namespace {

using namespace luxel;

struct CausticLevel {
    ecs::Registry registry;
    world::SceneInstance instance;
    ecs::TransformSystem transforms{registry};
    std::unique_ptr<lighting::PhotonWorld> photons;
    JobSystem jobs;

    explicit CausticLevel(const std::string& name, int threads = 2,
                          std::uint32_t photons_per_pair = 2'000)
        : jobs(threads) {
        world::InstantiateOptions options;
        options.play_animations = false;
        instance = world::instantiate(registry,
                                      std::make_shared<scene::Scene>(scene::load_gltf(
                                          std::filesystem::path(LUXEL_TEST_SOURCE_DIR) / "assets" /
                                          "levels" / (name + ".glb"))),
                                      options);
        transforms.update();
        lighting::PhotonWorldSettings settings;
        settings.caustics.photons_per_pair = photons_per_pair;
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
    CausticLevel level("cornell");
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
    ASSERT_EQ(one.size(), two.size());
    EXPECT_EQ(std::memcmp(one.data(), two.data(), one.size() * sizeof(lighting::CausticPhoton)), 0);
}

}  // namespace
