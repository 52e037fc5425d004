// Light follows geometry (issue 19, docs/METHOD.md §4.5, §6.8): the Cornell box's cube rests on
// the floor and slides 0.3 m. Within two frames the floor where it stood must be lit and the
// floor it now covers dark, as in a solution converged from scratch with the cube already slid;
// without local passes and exact invalidation (the paper's behaviour) the footprint is still dark
// then, and either one alone fixes it. Deterministic: a ManualClock that never advances makes
// every unit free, so each frame does all the work queued (stability_support.hpp). What a player
// sees fades in per texel: the second test checks that the texels a local pass re-gathered show
// their new light within frames, not half a second.

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "luxel/ecs/transform.hpp"
#include "luxel/scene/components.hpp"
#include "stability_support.hpp"

namespace {

using namespace luxel;

constexpr float kSlide = 0.3f;   ///< metres along +x, as luxel-bench's --change auto
constexpr float kHalf = 0.25f;   ///< the cube's half size
constexpr float kInset = 0.06f;  ///< texels this far inside a footprint's edge count
constexpr std::uint32_t kRefinePasses = 4;

/// How the lighting answers a move: luxel's defaults, or with parts off (the paper: neither
/// local passes nor exact invalidation).
struct Response {
    bool local_passes = true;
    bool exact_invalidation = true;
    double change_blend_seconds = lighting::IlluminationSettings{}.change_blend_seconds;
};
constexpr Response kLuxel{};
constexpr Response kPaper{false, false};

lighting::LightingConfig footprint_config(const Response& response) {
    lighting::LightingConfig config = luxel::testing::stability_config(77, 40);
    config.maps.refine_passes = kRefinePasses;
    config.maps.local_passes = response.local_passes;
    config.photons.selective.exact_invalidation = response.exact_invalidation;
    config.maps.change_blend_seconds = response.change_blend_seconds;
    return config;
}

/// Whether a world point lies under the cube placed by `world` (its footprint, inset).
bool under(const glm::mat4& world, const glm::vec3& point) {
    const glm::vec3 local = glm::vec3(glm::inverse(world) * glm::vec4(point, 1.0f));
    const float edge = kHalf - kInset;
    return std::abs(local.x) < edge && std::abs(local.z) < edge && local.y < -0.15f;
}

/// The Cornell box on a clock that never advances, converged with the cube where it rests.
struct Box {
    const ManualClock clock;
    luxel::testing::LitLevel level;
    ecs::Entity cube;
    std::vector<std::uint32_t> floor;  ///< the floor's light-mapped surfaces (luxel-prep's charts)
    glm::mat4 rest{1.0f};
    glm::mat4 slid{1.0f};

    explicit Box(const Response& response, bool slide_first = false)
        : level(luxel::testing::load_prepared("cornell"), footprint_config(response), false, clock),
          cube(level.instance.find("moving cube")) {
        rest = level.registry.get<ecs::WorldTransform>(cube).matrix;
        if (slide_first) {
            slide();
        }
        EXPECT_LE(level.converge(600), 600) << level.pending();
        const auto& maps = level.lighting->maps();
        for (std::uint32_t s = 0; s < maps.surfaces().size(); ++s) {
            const auto* name = level.registry.try_get<scene::Name>(maps.surfaces()[s].entity);
            if (name != nullptr && name->value == "floor" &&
                !maps.surfaces()[s].texels.texels.empty()) {
                floor.push_back(s);
            }
        }
    }

    void slide() {
        level.registry.patch<ecs::Transform>(cube,
                                             [](ecs::Transform& t) { t.translation.x += kSlide; });
        level.transforms.update();
        slid = level.registry.get<ecs::WorldTransform>(cube).matrix;
    }

    /// The floor texels (surface, index) under the cube placed by `in` and not by `out`.
    [[nodiscard]] std::vector<std::pair<std::uint32_t, std::size_t>> floor_between(
        const glm::mat4& in, const glm::mat4& out) const {
        std::vector<std::pair<std::uint32_t, std::size_t>> found;
        for (const std::uint32_t s : floor) {
            const auto world = level.lighting->maps().world_texels(s);
            for (std::size_t i = 0; i < world.size(); ++i) {
                if (under(in, world[i].position) && !under(out, world[i].position)) {
                    found.emplace_back(s, i);
                }
            }
        }
        return found;
    }

    /// The mean committed IIM over floor texels.
    [[nodiscard]] double mean_iim(
        const std::vector<std::pair<std::uint32_t, std::size_t>>& texels) const {
        return mean_over(texels, [](const lighting::IimPage& page, int x, int y) {
            return page.current.at(x, y);
        });
    }

    /// The mean IIM a player sees now (the fade-in included) over floor texels.
    [[nodiscard]] double mean_shown(
        const std::vector<std::pair<std::uint32_t, std::size_t>>& texels) const {
        return mean_over(texels, [this](const lighting::IimPage& page, int x, int y) {
            return page.shown(x, y, level.time);
        });
    }

    template <typename Read>
    [[nodiscard]] double mean_over(const std::vector<std::pair<std::uint32_t, std::size_t>>& texels,
                                   Read read) const {
        const auto& maps = level.lighting->maps();
        double sum = 0.0;
        for (const auto& [s, i] : texels) {
            const auto page = static_cast<std::size_t>(maps.aim().surface_page[s]);
            const auto& texel = maps.surfaces()[s].texels.texels[i];
            const glm::vec3 v = read(maps.iim_pages()[page], texel.x, texel.y);
            sum += static_cast<double>(v.x + v.y + v.z) / 3.0;
        }
        return texels.empty() ? 0.0 : sum / static_cast<double>(texels.size());
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
