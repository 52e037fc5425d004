// The order of local passes after a change (issue 19, docs/METHOD.md §6.8), on the Cornell box's
// cube. Slid 0.3 m: the texels close to its old or new box gather first, then the cube's own
// surfaces (which carry their light with them), then the farther texels; a surface's marked
// texels are split so, the floor's first local pass leaving its farther texels for a later one.
// Turned 45 degrees: the cube's own surfaces, every texel of which now faces other things,
// gather first. Time is a TickingClock (a
// millisecond a read), so the small budget runs a few units a frame, the same on every machine.

#include <algorithm>
#include <cstdio>
#include <functional>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "footprint_support.hpp"
#include "ticking_clock.hpp"

namespace {

using namespace luxel;

/// How close a point lies to a change's box, as a share of the box's half-diagonal (1 inside,
/// 0 at the half-diagonal and beyond): written here from the definition, not taken from the
/// code under test.
float closeness(const glm::vec3& p, const lighting::GeometryChange& box) {
    const glm::vec3 nearest = glm::clamp(p, box.min, box.max);
    const float half_diagonal = 0.5f * glm::length(box.max - box.min);
    return std::max(0.0f, 1.0f - glm::length(p - nearest) / half_diagonal);
}

/// A local pass's place in the order: a turned object's own surface, then texels all close to
/// a change (over half the half-diagonal), then a slid object's own surface, then the rest.
enum Tier { kFar = 0, kSlid = 1, kClose = 2, kTurned = 3 };

struct FirstPass {
    std::uint32_t surface = 0;
    Tier tier = kFar;
    bool cube = false;
    bool floor = false;
    std::size_t left = 0;  ///< texels still marked when it started
};

/// Converges cornell, changes the cube's transform, and lists each surface's first local pass
/// in the order they start, frame by frame at a 2 ms budget.
std::vector<FirstPass> first_local_passes(const std::function<void(ecs::Transform&)>& change,
                                          bool turned) {
    const luxel::testing::TickingClock clock;
    luxel::testing::LitLevel level(luxel::testing::load_prepared("cornell"),
                                   luxel::testing::footprint_config(luxel::testing::kLuxel), false,
                                   clock);
    EXPECT_LE(level.converge(600), 600) << level.pending();
    const auto& maps = level.lighting->maps();
    const ecs::Entity cube = level.instance.find("moving cube");
    std::vector<std::uint32_t> started(maps.surfaces().size());
    for (std::uint32_t s = 0; s < started.size(); ++s) {
        started[s] = maps.gather_state(s).started;
    }
    level.registry.patch<ecs::Transform>(cube, change);
    level.frame(0.0);  // a paused frame: the change is taken in, no unit runs
    const std::vector<lighting::GeometryChange> boxes =
        level.lighting->photons().geometry_changes();
    EXPECT_FALSE(boxes.empty());

    std::vector<FirstPass> order;
    std::vector<bool> passed(started.size(), false);
    for (int frame = 0; frame < 400; ++frame) {
        level.frame(2.0);
        for (std::uint32_t s = 0; s < started.size(); ++s) {
            const lighting::GatherPassState& state = maps.gather_state(s);
            if (state.started == started[s]) {
                continue;
            }
            started[s] = state.started;
            if (!state.local || passed[s]) {
                continue;
            }
            passed[s] = true;
            const auto& mapped = maps.surfaces()[s];
            FirstPass pass;
            pass.surface = s;
            pass.cube = mapped.entity == cube;
            const auto* name = level.registry.try_get<scene::Name>(mapped.entity);
            pass.floor = name != nullptr && name->value == "floor";
            pass.left = state.changed_count;
            float least = 1.0f;
            for (const std::uint32_t i : state.subset) {
                const glm::vec3 p(mapped.to_world *
                                  glm::vec4(mapped.texels.texels[i].position, 1.0f));
                float close = 0.0f;
                for (const auto& box : boxes) {
                    close = std::max(close, closeness(p, box));
                }
                least = std::min(least, close);
            }
            pass.tier = pass.cube ? (turned ? kTurned : kSlid) : least > 0.5f ? kClose : kFar;
            order.push_back(pass);
        }
    }
    // Every marked texel is gathered in the end.
    for (std::uint32_t s = 0; s < maps.surfaces().size(); ++s) {
        EXPECT_EQ(maps.gather_state(s).changed_count, 0u) << "surface " << s;
    }
    return order;
}

void expect_tiers_in_order(const std::vector<FirstPass>& order) {
    for (std::size_t k = 1; k < order.size(); ++k) {
        EXPECT_LE(order[k].tier, order[k - 1].tier)
            << "local pass " << k << " (surface " << order[k].surface << ") came after a pass of "
            << "a lower tier (surface " << order[k - 1].surface << ")";
    }
}

TEST(LocalOrder, TheTexelsClosestToASlidCubeGatherFirst) {
    const std::vector<FirstPass> order =
        first_local_passes([](ecs::Transform& t) { t.translation.x += 0.3f; }, false);
    ASSERT_GE(order.size(), 3u);
    expect_tiers_in_order(order);
    std::size_t cube = 0;
    std::size_t close = 0;
    std::size_t floor_left = 0;
    for (const FirstPass& pass : order) {
        cube += pass.cube ? 1 : 0;
        close += pass.tier == kClose ? 1 : 0;
        floor_left += pass.floor ? pass.left : 0;
    }
    EXPECT_GT(cube, 0u) << "the cube's own surfaces gathered no local pass";
    EXPECT_GT(floor_left, 0u) << "the floor's first passes took every marked texel";
    std::printf(
        "[ figures  ] slid: %zu first local passes, %zu of close texels, %zu of the "
        "cube; %zu floor texels left to later passes\n",
        order.size(), close, cube, floor_left);
}

TEST(LocalOrder, ATurnedCubesOwnSurfacesGatherFirst) {
    const std::vector<FirstPass> order = first_local_passes(
        [](ecs::Transform& t) {
            t.rotation =
                glm::angleAxis(glm::radians(45.0f), glm::vec3(0.0f, 1.0f, 0.0f)) * t.rotation;
        },
        true);
    ASSERT_GE(order.size(), 3u);
    expect_tiers_in_order(order);
    std::size_t cube = 0;
    for (const FirstPass& pass : order) {
        cube += pass.cube ? 1 : 0;
    }
    ASSERT_GT(cube, 0u);
    for (std::size_t k = 0; k < cube; ++k) {
        EXPECT_TRUE(order[k].cube) << "local pass " << k << " is surface " << order[k].surface;
    }
    std::printf("[ figures  ] turned: the cube's %zu surfaces first of %zu first local passes\n",
                cube, order.size());
}

}  // namespace
