// Light follows geometry (issue 19, docs/METHOD.md §4.5, §6.8): the Cornell box's cube rests on
// the floor and slides 0.3 m. Within two frames the floor where it stood must be lit and the
// floor it now covers dark, as in a solution converged from scratch with the cube already slid;
// without local passes and exact invalidation (the paper's behaviour) the footprint is still dark
// then, and either one alone fixes it. Deterministic: a ManualClock that never advances makes
// every unit free, so each frame does all the work queued (stability_support.hpp). What a player
// sees fades in per texel: the second test checks that the texels a local pass re-gathered show
// their new light within frames, not half a second.

#include <algorithm>
#include <cstdio>
#include <set>
#include <string>
#include <utility>
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

/// The texels of the named node's light-mapped surfaces, as (surface, index).
std::vector<std::pair<std::uint32_t, std::size_t>> texels_of(const Box& box,
                                                             const std::string& node) {
    std::vector<std::pair<std::uint32_t, std::size_t>> found;
    const auto& maps = box.level.lighting->maps();
    for (std::uint32_t s = 0; s < maps.surfaces().size(); ++s) {
        const auto* name = box.level.registry.try_get<scene::Name>(maps.surfaces()[s].entity);
        if (name != nullptr && name->value == node) {
            for (std::size_t i = 0; i < maps.surfaces()[s].texels.texels.size(); ++i) {
                found.emplace_back(s, i);
            }
        }
    }
    return found;
}

/// Slides the cube and runs until converged again; returns the share of `texels` whose passes
/// restarted (fell below what they had) at some frame, and how many full passes their surfaces
/// started meanwhile.
std::pair<double, std::uint32_t> restarted_after_slide(
    Box& box, const std::vector<std::pair<std::uint32_t, std::size_t>>& texels) {
    const auto& maps = box.level.lighting->maps();
    std::vector<std::uint32_t> passes;
    std::set<std::uint32_t> surfaces;
    for (const auto& [s, i] : texels) {
        passes.push_back(maps.refinement(s).texel_passes.at(i));
        surfaces.insert(s);
    }
    const auto started = [&] {
        std::uint32_t sum = 0;
        for (const std::uint32_t s : surfaces) {
            sum += maps.gather_state(s).started;
        }
        return sum;
    };
    const std::uint32_t started_before = started();
    std::vector<bool> restarted(texels.size(), false);
    box.slide();
    for (int f = 0; f < 600 && (f < 2 || !box.level.lighting->plan().census().converged); ++f) {
        box.level.frame(1e9);
        for (std::size_t k = 0; k < texels.size(); ++k) {
            const auto& [s, i] = texels[k];
            const std::uint32_t now = maps.refinement(s).texel_passes.at(i);
            restarted[k] = restarted[k] || now < passes[k];
            passes[k] = now;
        }
    }
    const std::uint32_t started_after = started();
    const auto count = static_cast<double>(std::count(restarted.begin(), restarted.end(), true));
    return {count / static_cast<double>(std::max<std::size_t>(texels.size(), 1)),
            started_after - started_before};
}

TEST(Footprint, TexelsTheMoveDidNotReachKeepTheirRefinement) {
    // The cube's move retraces most photon groups (their paths cross its old or new place),
    // so the ceiling's photons change and its surfaces gather full passes again; the light
    // there barely changes. luxel keeps the ceiling texels' averaged passes; restarting every
    // texel of a surface whose photons changed (change_test_sigmas 0, before issue 19) throws
    // them away.
    Box luxel(kLuxel);
    const auto ceiling = texels_of(luxel, "ceiling");
    ASSERT_GT(ceiling.size(), 100u);
    const auto [kept_restarted, kept_passes] = restarted_after_slide(luxel, ceiling);
    // The figure docs/RESULTS.md quotes (with the test off: every texel restarts).
    std::printf("ceiling texels restarted through the slide: %.1f%% (%u full passes)\n",
                100.0 * kept_restarted, kept_passes);
    EXPECT_GT(kept_passes, 0u) << "the ceiling should gather again after the move";
    EXPECT_LT(kept_restarted, 0.2);

    Box restart({true, true, kLuxel.change_blend_seconds, 0.0});
    const auto [all_restarted, all_passes] = restarted_after_slide(restart, ceiling);
    EXPECT_GT(all_passes, 0u);
    EXPECT_GT(all_restarted, 0.8);

    // Where the move did change the light, the texels restart: the floor the cube left.
    Box truth(kLuxel, true);
    const auto left = truth.floor_between(truth.rest, truth.slid);
    Box moved(kLuxel);
    const auto [left_restarted, left_passes] = restarted_after_slide(moved, left);
    EXPECT_GT(left_passes, 0u);
    EXPECT_GT(left_restarted, 0.9);
}

}  // namespace
