// Issue 19's reproduction in a level luxel did not write: tests/levels/blender/crate-footprint.py
// builds a room in Blender and its glTF exporter writes it (crate-footprint.glb, prepared by
// luxel-prep). A crate rests on the floor when the level loads; its animation holds it for one
// second and then slides it 1.2 m over half a second. Played as a game plays it, frame by frame:
// once the crate stops, the floor where it stood must be lit in the indirect light and the floor
// it now covers dark, within frames. Deterministic (a clock that never advances: every frame
// does all the work queued, footprint_support.hpp).

#include <cstdint>
#include <cstdio>
#include <utility>
#include <vector>

#include "footprint_support.hpp"
#include "luxel/world/animation_system.hpp"

namespace {

using namespace luxel;
using luxel::testing::FootprintLevel;
using luxel::testing::kLuxel;
using luxel::testing::kPaper;

const luxel::testing::FootprintSetup kCrate{"crate-footprint", "Crate", "Floor"};
// Blender's exporter writes frame f at f / fps seconds: the slide's keys, frames 31 and 46 at
// 30 fps, are at 31/30 and 46/30 s.
constexpr double kSlideStarts = 31.0 / 30.0;
constexpr double kSlideEnds = 46.0 / 30.0;
constexpr double kDt = 1.0 / 30.0;
/// Frames the slide takes at 30 Hz (and one for the sum of the steps to reach its end).
constexpr int kSlideFrames = 16;

/// Puts every animation of the level at `seconds` and lets it play on (or not).
void pose_animations(FootprintLevel& crate, double seconds, bool playing) {
    for (const ecs::Entity entity : crate.level.instance.animations) {
        auto& player = crate.level.registry.get<world::AnimationPlayer>(entity);
        player.time = seconds;
        player.loop = false;
        player.playing = playing;
    }
}

/// The crate where its slide ends, at once (the truth converges there; a game that knocks a
/// crate away moves it so).
void jump_to_the_end(FootprintLevel& crate) {
    pose_animations(crate, kSlideEnds, true);
    world::update_animations(crate.level.registry, 0.0);
    crate.level.transforms.update();
    pose_animations(crate, kSlideEnds, false);
}

/// The floor the crate leaves and the floor it comes to cover, with the truth's light on the
/// first.
struct Truth {
    FootprintLevel level{kCrate, kLuxel, jump_to_the_end};
    glm::mat4 slid = level.world_matrix();
    std::vector<std::pair<std::uint32_t, std::size_t>> left = level.floor_between(level.rest, slid);
    std::vector<std::pair<std::uint32_t, std::size_t>> covered =
        level.floor_between(slid, level.rest);
    double lit = level.mean_iim(left);
};

void expect_a_real_footprint(const Truth& truth) {
    ASSERT_GT(glm::length(glm::vec3(truth.slid[3]) - glm::vec3(truth.level.rest[3])), 1.0f)
        << "the crate's animation should slide it 1.2 m";
    ASSERT_GT(truth.left.size(), 20u);
    ASSERT_GT(truth.covered.size(), 20u);
    ASSERT_GT(truth.lit, 0.0);
    EXPECT_LT(truth.level.mean_iim(truth.covered), 0.1 * truth.lit);
}

TEST(BlenderFootprint, TheFloorTheCrateLeavesIsLitWithinFramesOfItStopping) {
    const Truth truth;
    expect_a_real_footprint(truth);

    // The slide played frame by frame, as a game plays it: two frames after the crate stops
    // the maps are right, and four later (the 0.1 s change blend) what a player sees is too.
    FootprintLevel crate(kCrate, kLuxel);
    EXPECT_LT(crate.mean_iim(truth.left), 0.25 * truth.lit);  // converged with it there: dark
    pose_animations(crate, kSlideStarts, true);
    for (int f = 0; f < kSlideFrames + 2; ++f) {
        crate.level.frame(1e9, kDt);
    }
    EXPECT_NEAR(glm::length(glm::vec3(crate.world_matrix()[3]) - glm::vec3(truth.slid[3])), 0.0f,
                1e-4f);
    EXPECT_GT(crate.mean_iim(truth.left), 0.75 * truth.lit);
    EXPECT_LT(crate.mean_iim(truth.covered), 0.25 * truth.lit);
    for (int f = 0; f < 4; ++f) {
        crate.level.frame(1e9, kDt);
    }
    EXPECT_GT(crate.mean_shown(truth.left), 0.75 * truth.lit);
    EXPECT_LT(crate.mean_shown(truth.covered), 0.25 * truth.lit);
}

TEST(BlenderFootprint, ACrateKnockedAwayLeavesNoFootprintAndThePapersMethodDoes) {
    const Truth truth;
    expect_a_real_footprint(truth);

    // Moved at once: within two frames luxel's maps are right.
    FootprintLevel crate(kCrate, kLuxel);
    jump_to_the_end(crate);
    crate.level.frame(1e9, kDt);
    crate.level.frame(1e9, kDt);
    EXPECT_GT(crate.mean_iim(truth.left), 0.75 * truth.lit);
    EXPECT_LT(crate.mean_iim(truth.covered), 0.25 * truth.lit);

    // The paper's method (selective probes only: no local passes, no exact invalidation): the
    // probes have not found the paths the crate blocked, and the footprint stays dark.
    FootprintLevel paper(kCrate, kPaper);
    jump_to_the_end(paper);
    paper.level.frame(1e9, kDt);
    paper.level.frame(1e9, kDt);
    EXPECT_LT(paper.mean_iim(truth.left), 0.5 * truth.lit);
}

TEST(BlenderFootprint, TheFloorsAimFollowsTheCrateWithoutWaitingForItsPhotons) {
    // What the AIM decided from the old geometry is looked at again next to the change: the
    // floor under the crate's new place was open and lit, under its old place enclosed and
    // black. At a budget the floor's full rebuild (thousands of texels, asked for when its
    // photons' change passes aim_threshold) comes tens of frames later, and until then every
    // gather that sees the floor beside the crate (the crate's own faces) reads it as it was.
    // Here full rebuilds are never asked for by the photons (aim_threshold out of reach), so
    // only the local rebuild can move the floor's AIM.
    const Truth truth;
    expect_a_real_footprint(truth);
    const double lit = truth.level.mean_aim(truth.left);
    ASSERT_GT(lit, 0.0);
    // The crate's bottom face lies in the floor's plane: the texels under it are inside the
    // crate and enclosed, though its walls are a quarter metre away.
    EXPECT_LT(truth.level.mean_aim(truth.covered), 0.05 * lit);

    luxel::testing::Response local = kLuxel;
    local.aim_threshold = 1e30;
    FootprintLevel crate(kCrate, local);
    EXPECT_LT(crate.mean_aim(truth.left), 0.05 * lit);  // enclosed while the crate stood there
    EXPECT_GT(crate.mean_aim(truth.covered), 0.75 * lit);
    jump_to_the_end(crate);
    // The retraces exact invalidation queued, the local rebuild that waits for their photons,
    // and one frame to spare.
    constexpr int kFrames = 4;
    for (int f = 0; f < kFrames; ++f) {
        crate.level.frame(1e9, kDt);
    }
    std::printf(
        "floor AIM after %d frames, where the crate stood / stands: %.4f / %.4f (truth "
        "%.4f / %.4f)\n",
        kFrames, crate.mean_aim(truth.left), crate.mean_aim(truth.covered), lit,
        truth.level.mean_aim(truth.covered));
    EXPECT_NEAR(crate.mean_aim(truth.left), lit, 0.1 * lit);
    EXPECT_LT(crate.mean_aim(truth.covered), 0.05 * lit);

    // Without local passes the floor's AIM is still the one decided with the crate where it
    // stood, though exact invalidation retraced the photons at once.
    luxel::testing::Response photons_only{false, true};
    photons_only.aim_threshold = 1e30;
    FootprintLevel paper(kCrate, photons_only);
    jump_to_the_end(paper);
    for (int f = 0; f < kFrames; ++f) {
        paper.level.frame(1e9, kDt);
    }
    EXPECT_LT(paper.mean_aim(truth.left), 0.05 * lit);
    EXPECT_GT(paper.mean_aim(truth.covered), 0.75 * lit);
}

}  // namespace
