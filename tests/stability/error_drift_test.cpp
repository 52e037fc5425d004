// Error against the reference over a long run (issue 12): the Cornell box with its cube sliding
// (the sphere's orbit stopped, so the scene repeats every 6 s), lighting only, no rendering.
// Every time the cube is back where it started, the IIM's indirect relRMSE against ONE reference
// of that pose must not have grown: nothing in the real-time state (photon paths, AIM, IIM and
// their fade time stamps, compensated sums, scheduler queues) may drift as frames accumulate.
//
// Determinism: the lighting system runs on a ManualClock that never advances, so every unit
// costs 0 ms on its clock and each frame does all the work queued (every diverged group
// retraced, every AIM and IIM due rebuilt); what a frame does depends on the scene and on the
// state, never on the machine's load.
//
// CI runs 4 cycles (800 frames, ~5 s), 2 under the sanitizers (the 4 took 229 s there, the
// sanitized suite's longest test; 2 still compare a checkpoint with the next one, and the plain
// build checks all 4); the full check is as long as the long run's (~10 min):
//     LUXEL_LONG_RUN_FRAMES=100000 build/bin/luxel_stability_tests --gtest_filter='ErrorDrift.*'

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <glm/gtc/constants.hpp>

#include "luxel/lighting/reference/error_metrics.hpp"
#include "luxel/lighting/reference/reference_integrator.hpp"
#include "stability_support.hpp"

namespace {

using namespace luxel;

/// dt 0.03 s: the cube's 6 s slide is 200 frames, a multiple of the 40-frame probe cycle (one
/// photon of each group a frame) and of the 8 caustic slices, so every checkpoint finds the
/// probes and slices at the same phase as well as the cube at the same place.
constexpr double kDt = 0.03;
constexpr int kCycleFrames = 200;

int frames_to_run() {
    if (const char* text = std::getenv("LUXEL_LONG_RUN_FRAMES")) {
        const int frames = std::atoi(text);
        if (frames >= 2 * kCycleFrames) {
            return frames;
        }
    }
#ifdef LUXEL_SANITIZE
    return 2 * kCycleFrames;
#else
    return 4 * kCycleFrames;
#endif
}

/// The reference's texels, kept apart from the ReferenceScene: the scene reads the live
/// RayScene, which moves with the cube after the reference is taken.
struct ReferenceTexels {
    struct Texel {
        std::uint32_t surface = 0;
        int x = 0;
        int y = 0;
    };
    std::vector<Texel> texels;
    std::vector<double> area;
    std::vector<glm::dvec3> indirect;  ///< W/m^2
    double relative_standard_error = 0.0;
};

/// The indirect component of the pose the level is in now, by the reference's photon
/// estimate. 2e6 photons: a relative standard error of ~7% (luxel-bench's 2e8 give 0.69%),
/// which is fine here: the same reference judges every checkpoint, so its noise is a fixed
/// offset and cannot make the error drift.
ReferenceTexels reference_now(const lighting::LightingSystem& lighting, JobSystem& jobs) {
    using namespace lighting::reference;
    const ReferenceScene scene = ReferenceScene::from_world(lighting.photons(), lighting.maps());
    ReferenceSettings settings;
    settings.indirect = IndirectMethod::Photons;
    settings.samples_per_pass = 0;  // no path samples: only the indirect photons are needed
    settings.caustics.photons_per_pass = 1000;
    settings.indirect_photons.photons_per_pass = 1'000'000;
    ReferenceIntegrator integrator(scene, settings);
    for (int pass = 0; pass < 2; ++pass) {
        integrator.run_pass(jobs);
    }
    ReferenceTexels out;
    out.indirect = integrator.irradiance(Component::Indirect);
    out.area = scene.texel_areas();
    out.relative_standard_error = integrator.relative_standard_error(Component::Indirect);
    for (const ReferenceSurface& surface : scene.surfaces()) {
        for (const ReferenceTexel& texel : surface.texels) {
            out.texels.push_back({surface.surface, texel.x, texel.y});
        }
    }
    return out;
}

/// The IIM as shown at `now` as irradiance per reference texel: Radiance-content texels hold
/// albedo E / pi and are divided back.
std::vector<glm::dvec3> shown_indirect(const lighting::IlluminationMaps& maps,
                                       const ReferenceTexels& reference, double now) {
    std::vector<glm::dvec3> out(reference.texels.size(), glm::dvec3(0.0));
    for (std::size_t i = 0; i < reference.texels.size(); ++i) {
        const auto& texel = reference.texels[i];
        const std::int32_t page = maps.aim().surface_page.at(texel.surface);
        if (page < 0) {
            continue;
        }
        const lighting::MapSurface& surface = maps.surfaces()[texel.surface];
        glm::dvec3 scale(1.0);
        if (surface.content == lighting::IimContent::Radiance) {
            for (int c = 0; c < 3; ++c) {
                const double albedo = surface.albedo[c];
                scale[c] = albedo > 0.0 ? glm::pi<double>() / albedo : 0.0;
            }
        }
        const glm::vec3 shown =
            maps.iim_pages()[static_cast<std::size_t>(page)].shown(texel.x, texel.y, now);
        out[i] = glm::dvec3(shown) * scale;
    }
    return out;
}

TEST(ErrorDrift, CornellIndirectErrorDoesNotGrowOverALongRun) {
    const int frames = frames_to_run();
    ManualClock clock;
    luxel::testing::LitLevel level(luxel::testing::load_prepared("cornell"),
                                   luxel::testing::stability_config(77, 40), true, clock);
    int playing = 0;
    for (auto [entity, player] : level.registry.view<world::AnimationPlayer>()) {
        const auto& animation =
            player.source->animations.at(static_cast<std::size_t>(player.animation));
        player.playing = animation.name == "cube slide";
        playing += player.playing ? 1 : 0;
        if (player.playing) {
            ASSERT_NEAR(animation.duration(), kCycleFrames * kDt, 1e-6)
                << "the cube's cycle is no longer 6 s: kDt and kCycleFrames need changing";
        }
    }
    ASSERT_EQ(playing, 1) << "prepared/cornell.glb has no 'cube slide' animation";

    JobSystem jobs(2);
    ReferenceTexels reference;
    std::vector<double> errors;
    for (int frame = 1; frame <= frames; ++frame) {
        level.frame(4.0, kDt);
        if (frame % kCycleFrames != 0) {
            continue;
        }
        if (reference.texels.empty()) {
            reference = reference_now(*level.lighting, jobs);
            ASSERT_FALSE(reference.texels.empty());
        }
        const std::vector<glm::dvec3> shown =
            shown_indirect(level.lighting->maps(), reference, level.time);
        errors.push_back(
            lighting::reference::relative_rmse(shown, reference.indirect, reference.area));
        std::printf("[ figures  ] frame %d (cycle %d): indirect relRMSE %.5f\n", frame,
                    frame / kCycleFrames, errors.back());
        ASSERT_TRUE(std::isfinite(errors.back()));
    }
    ASSERT_GE(errors.size(), 2u);
    double lowest = errors.front();
    double highest = errors.front();
    for (const double e : errors) {
        lowest = std::min(lowest, e);
        highest = std::max(highest, e);
    }
    std::printf(
        "[ figures  ] %d frames, %zu checkpoints: indirect relRMSE first %.5f, last %.5f "
        "(ratio %.4f), range %.5f..%.5f; reference relative standard error %.4f\n",
        frames, errors.size(), errors.front(), errors.back(),
        errors.front() > 0.0 ? errors.back() / errors.front() : 0.0, lowest, highest,
        reference.relative_standard_error);
    // The run is deterministic and the scene periodic, but the state at a checkpoint is not a
    // function of the pose alone: a group is retraced when its probe's path has moved by more
    // than a tolerance, an AIM or IIM rebuilt when its delta passes 5% (aim_threshold,
    // iim_threshold), so the maps lag the scene by an amount that depends on where the last
    // rebuilds fell in earlier cycles. That scatter is bounded by the thresholds and does not
    // grow: over 30 cycles (6,000 frames) the checkpoints stayed within 0.2364..0.2457, at
    // most 1.04x the first. 1.1x the first error allows 2.5x that scatter; no further noise
    // term is needed, since the reference's own noise (7%) is the same at every checkpoint. A
    // drift (stale paths, AIM or IIM that stop being rebuilt, fade time stamps losing
    // precision, sums wandering) grows with the run and crosses it.
    EXPECT_LE(errors.back(), 1.1 * errors.front());
    luxel::testing::for_each_texel(level.lighting->maps(),
                                   [&](std::uint32_t, const glm::vec3& aim, const glm::vec3& iim) {
                                       ASSERT_TRUE(luxel::testing::finite_non_negative(aim));
                                       ASSERT_TRUE(luxel::testing::finite_non_negative(iim));
                                   });
}

}  // namespace
