// A room lit through a window by a sky, in a level Blender's exporter wrote
// (tests/levels/blender/sky-window.py, issue 20): the sky comes from the scene's custom property
// as Blender writes it; with the sun off, the room receives the sky's light only through the
// window; with the window shut it receives none at all, neither photons nor gathered light.

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "luxel/ecs/transform_system.hpp"
#include "luxel/lighting/components.hpp"
#include "luxel/lighting/core/lighting_system.hpp"
#include "luxel/lighting/sky_portal.hpp"
#include "luxel/runtime/jobs.hpp"
#include "luxel/scene/gltf.hpp"
#include "luxel/world/scene_instance.hpp"
#include "map_test_scenes.hpp"
#include "test_paths.hpp"
#include "texel_visit.hpp"

namespace {

using namespace luxel;

std::shared_ptr<const scene::Scene> sky_window() {
    return std::make_shared<scene::Scene>(scene::load_gltf(
        luxel::testing::source_dir() / "assets" / "levels" / "prepared" / "sky-window.glb"));
}

/// A pane filling the window's 1.2 x 1.0 m opening edge to edge, in the wall's plane, facing out
/// of the room (glTF space: the back wall is the plane z = -2, the opening x in [-0.6, 0.6],
/// y in [1, 2]). In the plane, not in front of it: grazing rays would slip through a gap.
std::shared_ptr<const scene::Scene> shutter() {
    auto s = std::make_shared<scene::Scene>();
    s->materials.emplace_back();
    scene::Primitive p;
    p.material = 0;
    const float z = -2.0f;
    p.positions = {{-0.6f, 1.0f, z}, {0.6f, 1.0f, z}, {0.6f, 2.0f, z}, {-0.6f, 2.0f, z}};
    p.normals.assign(4, glm::vec3(0.0f, 0.0f, -1.0f));
    // Counter-clockwise seen from -z (outside).
    p.indices = {0, 2, 1, 0, 3, 2};
    s->meshes.push_back({"shutter", {p}});
    return s;
}

struct Room {
    ecs::Registry registry;
    ecs::TransformSystem transforms{registry};
    JobSystem jobs{2};
    std::unique_ptr<lighting::LightingSystem> lighting;
    double time = 0.0;

    /// `portal`: keep the window's portal (the level's), or drop it (photons from the disc).
    /// `per_group`: photons per group, 32 groups (256: 8,192 photons).
    explicit Room(bool shut, bool portal = true, std::uint32_t per_group = 256) {
        const world::SceneInstance instance = world::instantiate(registry, sky_window());
        EXPECT_NE(instance.sky, ecs::null_entity);
        EXPECT_EQ(registry.size<lighting::SkyPortal>(), 1u);
        if (!portal) {
            std::vector<ecs::Entity> portals;
            for (auto [entity, opening] : registry.view<lighting::SkyPortal>()) {
                portals.push_back(entity);
            }
            for (const ecs::Entity entity : portals) {
                registry.remove<lighting::SkyPortal>(entity);
            }
        }
        // The sky alone: the sun off.
        for (auto [entity, sun] : registry.view<lighting::DirectionalLight>()) {
            sun.enabled = false;
        }
        if (shut) {
            const ecs::Entity pane = registry.create();
            registry.emplace<scene::MeshInstance>(pane, shutter(), 0);
            registry.emplace<ecs::Transform>(pane, ecs::Transform{});
        }
        transforms.update();
        // 8,192 photons; converged once every group has been probed (32 frames).
        lighting = std::make_unique<lighting::LightingSystem>(
            registry, jobs, luxel::testing::closed_form_config(per_group, 32));
    }

    int converge() { return luxel::testing::converge(transforms, *lighting, time); }

    /// Summed over every light-mapped texel: the AIM's and the IIM's green.
    struct Totals {
        double aim = 0.0;
        double iim = 0.0;
        std::size_t texels = 0;
    };
    [[nodiscard]] Totals totals() const {
        Totals out;
        luxel::testing::for_each_texel(
            lighting->maps(), [&](std::uint32_t, const glm::vec3& aim, const glm::vec3& iim) {
                out.aim += aim.g;
                out.iim += iim.g;
                ++out.texels;
            });
        return out;
    }
};

TEST(SkyWindow, BlendersSceneCustomPropertyIsTheLevelsSky) {
    const auto level = sky_window();
    EXPECT_EQ(level->sky.kind, scene::SkySpec::Kind::Daylight);
    EXPECT_EQ(level->sky.irradiance, 1.0f);
    EXPECT_EQ(level->sky.turbidity, 3.0f);
}

TEST(SkyWindow, TheSkyLightsTheRoomThroughTheWindowAndNotAtAllWhenItIsShut) {
    Room open(false);
    ASSERT_LE(open.converge(), 100);
    const Room::Totals lit = open.totals();
    const std::size_t hits = open.lighting->photons().photon_map().stored_hit_count();
    Room shut(true);
    ASSERT_LE(shut.converge(), 100);
    const Room::Totals dark = shut.totals();
    const std::size_t shut_hits = shut.lighting->photons().photon_map().stored_hit_count();
    std::printf(
        "[ figures  ] sky-window, sky only: open %zu photon hits, AIM sum %.3f, IIM sum "
        "%.3f over %zu texels; shut %zu hits, AIM %.3g, IIM %.3g\n",
        hits, lit.aim, lit.iim, lit.texels, shut_hits, dark.aim, dark.iim);
    EXPECT_GT(lit.texels, 1000u);
    EXPECT_GT(hits, 100u);
    EXPECT_GT(lit.aim, 0.0);
    EXPECT_GT(lit.iim, 0.0);
    // Shut: not one photon inside (the room is closed and one-sided; the pane's outside and
    // the walls' backs take them all). A few gather rays still find the sky: the walls are
    // separate meshes whose node translations the exporter rounded (the ceiling at
    // 2.5999999 m, a wall's top at 2.5999999523), and a ray along a corner slips through a
    // crack of 1e-7 m. Measured: 2e-6 of the open room's gathered light; 1e-5 allowed.
    EXPECT_EQ(dark.texels, lit.texels);
    EXPECT_EQ(dark.aim, 0.0);
    EXPECT_LT(dark.iim, 1e-5 * lit.iim);
}

TEST(SkyWindow, ThePortalSendsTheSkysPhotonsThroughTheWindowAndTheyCarryTheSameLight) {
    // The same 8,192 sky photons, from the scene's disc (most land on the walls' outsides) and
    // from the window's portal (each looks back at the sky through the opening): the light in
    // the room agrees within the disc's noise, with many times the photons inside.
    Room disc(false, false);
    ASSERT_LE(disc.converge(), 100);
    Room portal(false, true);
    ASSERT_LE(portal.converge(), 100);
    const Room::Totals from_disc = disc.totals();
    const Room::Totals from_portal = portal.totals();
    const std::size_t disc_hits = disc.lighting->photons().photon_map().stored_hit_count();
    const std::size_t portal_hits = portal.lighting->photons().photon_map().stored_hit_count();
    std::printf(
        "[ figures  ] sky-window, sky only, 8,192 photons: from the disc %zu hits inside, AIM "
        "sum %.3f; through the portal %zu hits, AIM sum %.3f (%+.1f%%); IIM sums %.3f, %.3f\n",
        disc_hits, from_disc.aim, portal_hits, from_portal.aim,
        100.0 * (from_portal.aim / from_disc.aim - 1.0), from_disc.iim, from_portal.iim);
    // Measured: 328 and 8,977 hits, the AIM sums 6.2% apart; with 64 times the photons 1.0%
    // apart (DISABLED_ThePortalAndTheDiscAgreeWithManyPhotons): the disc's noise, not a bias
    // of the portal's.
    EXPECT_GT(portal_hits, 8 * disc_hits);
    EXPECT_NEAR(from_portal.aim / from_disc.aim, 1.0, 0.2);
    // The gathers read the sky directly either way; only their bounce off the AIM differs
    // (measured 4%).
    EXPECT_NEAR(from_portal.iim / from_disc.iim, 1.0, 0.1);
}

// Left out of the suite for its time (16 s on two cores); run it with
// --gtest_also_run_disabled_tests.
TEST(SkyWindow, DISABLED_ThePortalAndTheDiscAgreeWithManyPhotons) {
    // 524,288 sky photons each way: the disc's noise no longer hides a bias of the portal's.
    // Measured: 19,385 and 573,878 hits inside, AIM sums 1.0% apart.
    Room disc(false, false, 16384);
    ASSERT_LE(disc.converge(), 100);
    Room portal(false, true, 16384);
    ASSERT_LE(portal.converge(), 100);
    const double ratio = portal.totals().aim / disc.totals().aim;
    std::printf(
        "[ figures  ] sky-window, 524,288 sky photons: from the disc %zu hits inside, "
        "through the portal %zu; AIM sums %+.2f%% apart\n",
        disc.lighting->photons().photon_map().stored_hit_count(),
        portal.lighting->photons().photon_map().stored_hit_count(), 100.0 * (ratio - 1.0));
    EXPECT_NEAR(ratio, 1.0, 0.03);
}

}  // namespace
