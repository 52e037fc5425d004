// Light follows geometry (issue 19, docs/METHOD.md §4.5, §6.8): the Cornell box's cube rests on
// the floor and slides 0.3 m. Within two frames the floor where it stood must be lit and the
// floor it now covers dark, as in a solution converged from scratch with the cube already slid;
// without local passes and exact invalidation (the paper's behaviour) the footprint is still dark
// then, and either one alone fixes it. Deterministic: a ManualClock that never advances makes
// every unit free, so each frame does all the work queued (stability_support.hpp). What a player
// sees fades in per texel: the second test checks that the texels a local pass re-gathered show
// their new light within frames, not half a second.

#include <vector>

#include "footprint_support.hpp"

namespace {

using namespace luxel;
using luxel::testing::kLuxel;
using luxel::testing::kPaper;
using luxel::testing::Response;

constexpr float kSlide = 0.3f;  ///< metres along +x, as luxel-bench's --change auto
constexpr std::uint32_t kRefinePasses = luxel::testing::kFootprintRefinePasses;

/// The Cornell box converged with its cube where it rests (or, for the truth, where it slides
/// to).
struct Box : luxel::testing::FootprintLevel {
    glm::mat4 slid{1.0f};

    explicit Box(const Response& response, bool slide_first = false)
        : FootprintLevel({"cornell", "moving cube", "floor"}, response,
                         [slide_first](FootprintLevel& box) {
                             if (slide_first) {
                                 move(box);
                             }
                         }) {
        if (slide_first) {
            slid = world_matrix();
        }
    }

    static void move(FootprintLevel& box) {
        box.level.registry.patch<ecs::Transform>(
            box.object, [](ecs::Transform& t) { t.translation.x += kSlide; });
        box.level.transforms.update();
    }

    void slide() {
        move(*this);
        slid = world_matrix();
    }
};

TEST(Footprint, TheFloorACubeLeavesIsLitAndTheFloorItCoversDarkWithinTwoFrames) {
    // What the method converges to with the cube already where it slides to.
    Box truth(kLuxel, true);
    const auto left = truth.floor_between(truth.rest, truth.slid);
    const auto covered = truth.floor_between(truth.slid, truth.rest);
    ASSERT_GT(left.size(), 20u);
    ASSERT_GT(covered.size(), 20u);
    const double lit = truth.mean_iim(left);
    ASSERT_GT(lit, 0.0);
    EXPECT_LT(truth.mean_iim(covered), 0.1 * lit);

    Box local({true, false});                     // local passes alone
    EXPECT_LT(local.mean_iim(left), 0.25 * lit);  // converged with the cube on it: dark
    local.slide();
    local.level.frame(1e9);
    // One frame: the local pass has re-gathered the texels near the cube, which restarts
    // their passes.
    const auto& maps = local.level.lighting->maps();
    for (const auto& [s, i] : left) {
        EXPECT_LT(maps.refinement(s).texel_passes.at(i), kRefinePasses) << "texel " << i;
    }
    local.level.frame(1e9);
    EXPECT_GT(local.mean_iim(left), 0.75 * lit);
    EXPECT_LT(local.mean_iim(covered), 0.25 * lit);

    // The paper's behaviour: the floor waits for its photons' change, which the probes have
    // not found yet.
    Box paper(kPaper);
    paper.slide();
    paper.level.frame(1e9);
    paper.level.frame(1e9);
    EXPECT_LT(paper.mean_iim(left), 0.5 * lit);
    EXPECT_GT(paper.mean_iim(covered), 0.5 * lit);

    // Exact invalidation alone (no local passes): the groups whose paths cross the cube's old
    // or new place are retraced in the frame of the move, so the floor's photons change at
    // once and its full pass follows.
    Box exact({false, true});
    exact.slide();
    exact.level.frame(1e9);
    exact.level.frame(1e9);
    EXPECT_GT(exact.mean_iim(left), 0.75 * lit);
    EXPECT_LT(exact.mean_iim(covered), 0.25 * lit);
}

TEST(Footprint, WhatThePlayerSeesFollowsWithinSixFramesAt30Hz) {
    Box truth(kLuxel, true);
    const auto left = truth.floor_between(truth.rest, truth.slid);
    const auto covered = truth.floor_between(truth.slid, truth.rest);
    ASSERT_GT(left.size(), 20u);
    const double lit = truth.mean_iim(left);
    ASSERT_GT(lit, 0.0);

    // Local passes fade in over change_blend_seconds (0.1 s, three frames at 30 Hz): two frames
    // for the local pass and its re-gather once the AIM is current (the first test), three of
    // fade, one to spare.
    constexpr int kFrames = 6;
    Box local(kLuxel);
    ASSERT_GT(local.level.lighting->maps().settings().blend_seconds,
              3.0 * local.level.lighting->maps().settings().change_blend_seconds);
    local.slide();
    for (int f = 0; f < kFrames; ++f) {
        local.level.frame(1e9);
    }
    EXPECT_GT(local.mean_shown(left), 0.75 * lit);
    EXPECT_LT(local.mean_shown(covered), 0.25 * lit);

    // The same light maps faded in over the refinement's half second: the committed IIM is
    // right, but what the player sees is still mostly the footprint.
    Box slow({true, true, lighting::IlluminationSettings{}.blend_seconds});
    slow.slide();
    for (int f = 0; f < kFrames; ++f) {
        slow.level.frame(1e9);
    }
    EXPECT_GT(slow.mean_iim(left), 0.75 * lit);
    EXPECT_LT(slow.mean_shown(left), 0.5 * lit);
}

}  // namespace
