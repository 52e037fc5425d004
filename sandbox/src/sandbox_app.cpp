#include "sandbox_app.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "luxel/lighting/core/cost_model.hpp"
#include "luxel/runtime/clock.hpp"
#include "luxel/runtime/log.hpp"
#include "luxel/scene/gltf.hpp"
#include "luxel/world/animation_system.hpp"
#include "luxel/world/skinning.hpp"
#include "luxel/world/sky.hpp"
#include "luxel/world/vertex_wave.hpp"

namespace luxel::sandbox {
namespace {

/// "lighting warm-up converged after 120 updates (3400 ms: iim_gather 2900 ms, ...)", or why
/// it stopped. One that could
/// not progress is a warning naming the level: it stays dark or without indirect light.
void log_warm_up(const scene::Scene& level, const lighting::WarmUpResult& warm_up, double ms) {
    const std::string spent = lighting::describe_time(warm_up);
    const std::string took =
        std::to_string(warm_up.updates) + (warm_up.updates == 1 ? " update (" : " updates (") +
        std::to_string(static_cast<int>(ms)) + " ms" + (spent.empty() ? "" : ": " + spent) + ")";
    if (warm_up.end == lighting::WarmUpEnd::Converged) {
        log::info("lighting warm-up converged after " + took);
        return;
    }
    const std::string stopped =
        "lighting warm-up stopped after " + took + ": " + lighting::describe(warm_up);
    if (warm_up.end == lighting::WarmUpEnd::NoProgress) {
        log::warn(level.in_file(stopped));
    } else {
        log::info(stopped);
    }
}

}  // namespace

std::string level_display_name(const std::string& name_or_path) {
    const auto& names = level_names();
    if (std::find(names.begin(), names.end(), name_or_path) != names.end()) {
        return name_or_path;
    }
    return std::filesystem::path(name_or_path).stem().string();
}

SandboxApp::SandboxApp(const AppSettings& settings, JobSystem& jobs, const ShaderLibrary& shaders)
    : level_name_(level_display_name(settings.level)),
      level_file_(resolve_level(settings.level)),
      shaders_(&shaders),
      path_({}, 1.0f),
      budget_ms_(settings.budget_ms),
      width_(settings.width),
      height_(settings.height) {
    const Stopwatch loading;
    // What the level lacks, said once at load in the words luxel-ref and luxel-bench use, and
    // a level luxel-prep never prepared prepared now. The sandbox level walks its own scripted
    // path and needs no camera (camera_path_for).
    prep::PlayableLevel playable{settings.load_limits, {}, settings.auto_prep};
    playable.check.uses_camera = level_name_ != "sandbox";
    scene_ = prep::load_playable(level_file_, playable, jobs);
    world::InstantiateOptions instantiate;
    instantiate.sky = settings.sky;
    instance_ = world::instantiate(registry_, scene_, instantiate);
    const std::size_t bounces = add_bounces(registry_, instance_, *scene_);
    // The pose the first frame shows, before anything is lit: the animations and light switches
    // at t = 0 and the game's bounce at its start. Without it the loading screen lit the glTF
    // rest pose (a lamp hanging straight that starts at 30 degrees) and the first frames showed
    // its light until the budget caught up (issue 28).
    world::update_animations(registry_, 0.0);
    world::update_light_switches(registry_, 0.0);
    world::update_waves(registry_, 0.0);
    world::update_sky(registry_);
    update_bounces(registry_, 0.0);
    transforms_.update();
    world::update_skins(registry_);  // skinned meshes follow their joints
    path_ = camera_path_for(level_name_, *scene_);
    lighting_ = std::make_unique<lighting::LightingSystem>(registry_, jobs);
    renderer::FrameSettings frame;
    frame.width = width_;
    frame.height = height_;
    frame.anti_aliasing = settings.anti_aliasing;
    frame.soft_shadows = settings.soft_shadows;
    frame.bicubic_light_maps = settings.bicubic_light_maps;
    frame.sky_edge_coverage = settings.sky_edges;
    renderer_ = std::make_unique<renderer::FrameRenderer>(registry_, *lighting_, frame, shaders);
    // The loading screen: the first photon maps, AIMs and IIMs are built at once, so the game
    // starts lit and the per-frame budget only has to follow changes.
    const Stopwatch warming;
    // A progress line, rewritten in place as the frame counter is: the loading takes seconds.
    const auto show = [](const lighting::WarmUpProgress& progress) {
        std::fprintf(stderr, "  lighting warm-up %3d%% after %.1f s\r",
                     static_cast<int>(std::floor(100.0 * progress.share)),
                     progress.elapsed_ms / 1000.0);
        std::fflush(stderr);
    };
    const lighting::WarmUpResult warm_up = lighting_->warm_up(0.0, settings.warm_up_ms, show);
    std::fputs("\n", stderr);
    warm_up_ms_ = warming.elapsed_ms();
    log_warm_up(*scene_, warm_up, warm_up_ms_);
    log::info("level '" + level_name_ + "' from " + level_file_.string() + ": " +
              std::to_string(scene_->nodes.size()) + " nodes, " +
              std::to_string(scene_->animations.size()) + " animations, " +
              std::to_string(bounces) + " bounced by the game, loaded in " +
              std::to_string(static_cast<int>(loading.elapsed_ms())) + " ms");
}

SandboxApp::FrameResult SandboxApp::frame(double time, double dt,
                                          const renderer::FrameCamera& camera, bool frozen) {
    FrameResult result;
    // 1. Game systems move entities: glTF animations, light switches, the bounce system.
    if (!frozen) {
        world::update_animations(registry_, dt);
        world::update_light_switches(registry_, dt);
        world::update_waves(registry_, dt);  // water moves its vertices
        update_bounces(registry_, time);
        world::update_sky(registry_);  // a daylight sky turns with its sun
    }
    transforms_.update();
    world::update_skins(registry_);  // skinned meshes follow their joints

    // 2-4. Lighting: sync through the ECS change lists, scheduled work within the budget; what
    // the camera sees gathers first.
    const Stopwatch lighting_watch;
    lighting_->set_view(lighting::ViewHint{camera.projection * camera.view});
    const lighting::LightingStats& stats = lighting_->update(budget_ms_, time);
    result.lighting_ms = lighting_watch.elapsed_ms();

    // 5. Render. The renderer makes the caustic pass while the FeaturePlan has caustic data
    // and runs it between its G-buffer and its composite, so the photons are splatted against
    // this frame's depth and composited into this frame.
    const renderer::FrameTimings& timings = renderer_->render(camera, time);

    RunReport::Frame& report = result.report;
    report.lighting_ms = result.lighting_ms;
    report.budget_ms = budget_ms_;
    for (std::size_t pass = 0; pass < renderer::kRenderPassCount; ++pass) {
        report.pass_ms[std::string(renderer::name(static_cast<renderer::RenderPass>(pass)))] =
            timings.milliseconds[pass];
    }
    report.counters["photons_traced"] = static_cast<double>(stats.photons_traced);
    report.counters["caustic_photons_traced"] = static_cast<double>(stats.caustic_photons_traced);
    report.counters["aim_texels"] = static_cast<double>(stats.aim_texels);
    report.counters["texels_gathered"] = static_cast<double>(stats.texels_gathered);
    report.counters["probes_gathered"] = static_cast<double>(stats.probes_gathered);
    report.counters["work_units"] = static_cast<double>(stats.schedule.units_done);
    // Where the budget went, per kind of unit, and what came before the scheduler (change
    // tracking, the ray scene's commit): a moving character's cost shows here.
    double scheduled_ms = 0.0;
    for (std::size_t k = 0; k < lighting::kWorkKindCount; ++k) {
        const double ms = stats.schedule.kinds[k].ms;
        report.counters[std::string(lighting::name(static_cast<lighting::WorkKind>(k))) + "_ms"] =
            ms;
        scheduled_ms += ms;
    }
    report.counters["outside_units_ms"] = std::max(0.0, result.lighting_ms - scheduled_ms);
    report.counters["units_pending"] = static_cast<double>(stats.schedule.pending_after());
    report.counters["stored_hits"] = static_cast<double>(stats.stored_hits);
    report.counters["passes_active"] = static_cast<double>(lighting_->plan().active_count());
    return result;
}

}  // namespace luxel::sandbox
