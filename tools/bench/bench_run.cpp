#include "bench_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <type_traits>

#include <glm/gtc/quaternion.hpp>

#include "frame_view.hpp"
#include "image_reference.hpp"
#include "level.hpp"
#include "luxel/ecs/transform.hpp"
#include "luxel/ecs/transform_system.hpp"
#include "luxel/lighting/components.hpp"
#include "luxel/lighting/core/lighting_system.hpp"
#include "luxel/lighting/gpu/hemi_plane_gatherer.hpp"
#include "luxel/lighting/reference/error_metrics.hpp"
#include "luxel/lighting/reference/reference_scene.hpp"
#include "luxel/runtime/clock.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/scene/gltf.hpp"
#include "luxel/world/animation_system.hpp"
#include "luxel/world/scene_instance.hpp"
#include "map_error.hpp"
#include "reference_cache.hpp"

namespace luxel::bench {
namespace {

/// The node "auto" moves: the Cornell box's cube, when the level has one.
constexpr const char* kAutoNode = "moving cube";
constexpr float kAutoOffset = 0.3f;  ///< metres along +x: the cube slides 0.7 m in its animation

double percentile(std::vector<double> values, double p) {
    if (values.empty()) {
        return 0.0;
    }
    std::sort(values.begin(), values.end());
    // Nearest rank: the smallest value with at least p of the values at or below it.
    const auto rank = static_cast<std::size_t>(std::ceil(p * static_cast<double>(values.size())));
    return values[std::min(values.size() - 1, rank > 0 ? rank - 1 : 0)];
}

std::string describe(const Change& change) {
    std::ostringstream out;
    out << change.node << ":";
    switch (change.kind) {
        case Change::Kind::Move:
            out << change.offset.x << "," << change.offset.y << "," << change.offset.z;
            break;
        case Change::Kind::Turn:
            out << "turn=" << change.axis.x << "," << change.axis.y << "," << change.axis.z << ","
                << change.degrees;
            break;
        case Change::Kind::Off:
            out << "off";
            break;
        case Change::Kind::On:
            out << "on";
            break;
    }
    return out.str();
}

/// Sets the `enabled` flag of whichever light the entity carries; false when it has none.
bool switch_light(ecs::Registry& registry, ecs::Entity entity, bool on) {
    bool found = false;
    const auto set = [&](auto* light) {
        if (light != nullptr) {
            registry.patch<std::remove_pointer_t<decltype(light)>>(
                entity, [&](auto& l) { l.enabled = on; });
            found = true;
        }
    };
    set(registry.try_get<lighting::PointLight>(entity));
    set(registry.try_get<lighting::SpotLight>(entity));
    set(registry.try_get<lighting::DirectionalLight>(entity));
    set(registry.try_get<lighting::AreaLight>(entity));
    return found;
}

/// Applies the scripted change to the live scene.
void apply(const Change& change, ecs::Registry& registry, ecs::Entity entity,
           const std::string& level) {
    switch (change.kind) {
        case Change::Kind::Move:
            registry.patch<ecs::Transform>(
                entity, [&](ecs::Transform& t) { t.translation += change.offset; });
            break;
        case Change::Kind::Turn:
            registry.patch<ecs::Transform>(entity, [&](ecs::Transform& t) {
                t.rotation = glm::angleAxis(glm::radians(change.degrees), change.axis) * t.rotation;
            });
            break;
        case Change::Kind::Off:
        case Change::Kind::On:
            if (!switch_light(registry, entity, change.kind == Change::Kind::On)) {
                throw Error("--change " + describe(change) + ": node '" + change.node + "' of " +
                            level + " carries no light to switch");
            }
            break;
    }
}

bool sweeps_gpu_backend(const Options& options) {
    return std::any_of(options.sweeps.begin(), options.sweeps.end(), [](const Sweep& sweep) {
        return sweep.knob == "backend" &&
               std::find(sweep.values.begin(), sweep.values.end(), "gpu") != sweep.values.end();
    });
}

}  // namespace

Bench::Bench(const Options& options, const std::filesystem::path& level_file)
    : options_(&options), file_(level_file) {
    // load_gltf's errors already start with the file's path.
    source_ = std::make_shared<scene::Scene>(scene::load_gltf(level_file, options.load_limits));
    if (options.parsed_change) {
        change_ = options.parsed_change;
    } else if (options.change == "auto") {
        for (const scene::Node& node : source_->nodes) {
            if (node.name == kAutoNode) {
                change_ = Change{};
                change_->node = kAutoNode;
                change_->offset = {kAutoOffset, 0.0f, 0.0f};
            }
        }
    }
    if (change_) {
        const bool found =
            std::any_of(source_->nodes.begin(), source_->nodes.end(),
                        [&](const scene::Node& n) { return n.name == change_->node; });
        if (!found) {
            throw Error("--change: " + file_.string() + " has no node named '" + change_->node +
                        "'");
        }
    }
    std::ostringstream pose;
    pose << "level=" << level_file.filename().string()
         << ";bytes=" << std::filesystem::file_size(level_file) << ";time=" << options.time;
    pose_ = pose.str();
    jobs_ = std::make_unique<JobSystem>(options.threads);
    if (options.image.enabled || sweeps_gpu_backend(options)) {
        gl_ = make_headless_context();
        shaders_ = std::make_unique<ShaderLibrary>();
        std::fprintf(stderr, "luxel-bench: GL %s\n", gl_description().c_str());
    }
}

Bench::~Bench() = default;

std::string Bench::gl_description() const {
    if (!gl_) {
        return {};
    }
    return gl_->info().renderer + ", " + gl_->info().version + " (" +
           std::string(backend_name(gl_->backend())) + ")";
}

RunResult Bench::run(const BenchConfig& config) {
    const Options& options = *options_;
    RunResult result;
    result.config = config;
    ecs::Registry registry;
    world::InstantiateOptions instantiate_options;
    instantiate_options.play_animations = true;
    // Posed at --time as luxel-ref poses it, then frozen: only the scripted change moves.
    const world::SceneInstance instance =
        world::instantiate(registry, source_, instantiate_options);
    world::update_animations(registry, options.time);
    world::update_light_switches(registry, options.time);
    ecs::TransformSystem transforms(registry);
    transforms.update();
    lighting::LightingSystem lighting(registry, *jobs_, config.lighting());
    std::unique_ptr<lighting::HemiPlaneGatherer> gpu_gatherer;
    if (config.backend == "gpu") {
        gpu_gatherer = std::make_unique<lighting::HemiPlaneGatherer>(
            lighting.photons().ray_scene(), lighting.maps().aim(), lighting::HemiPlaneSettings{},
            *shaders_);
        lighting.set_gatherer(gpu_gatherer.get());
    }
    std::optional<lighting::reference::ReferenceCamera> camera;
    std::unique_ptr<FrameView> view;
    if (options.image.enabled) {
        camera = ref::level_camera(registry, instance, options.image.width, options.image.height);
        if (!camera) {
            throw Error(file_.string() +
                        " has no camera for the image error (--no-image leaves it out)");
        }
        view = std::make_unique<FrameView>(registry, lighting, *camera, parse_kernel(config.kernel),
                                           *shaders_);
    }
    double now = 0.0;
    std::unique_ptr<lighting::reference::ReferenceScene> scene;
    std::vector<double> active_ms;
    const auto frame = [&](double budget) {
        now += options.dt;
        transforms.update();
        Stopwatch clock;
        const lighting::LightingStats& stats = lighting.update(budget, now);
        const double ms = clock.elapsed_ms();
        result.frame_ms.push_back(ms);
        if (stats.schedule.units_done > 0) {
            active_ms.push_back(ms);
            return true;
        }
        return false;
    };
    const auto file_name = [&](const char* phase, const char* extension) {
        std::ostringstream name;
        name << config.method << "_" << config.budget_ms << "ms_" << phase << extension;
        return name.str();
    };
    const auto dump = [&](const RealTimeMaps& maps, const ReferenceMaps& reference,
                          const char* phase) {
        if (options.dump_maps) {
            write_maps_json(options.out / "maps" / file_name(phase, ".json"), *scene, maps,
                            reference);
        }
    };
    const std::filesystem::path cache = options.out / "cache";

    if (frame(config.budget_ms)) {
        result.static_work_frames = 1;
    }
    scene = std::make_unique<lighting::reference::ReferenceScene>(
        lighting::reference::ReferenceScene::from_world(lighting.photons(), lighting.maps()));
    const ReferenceMaps before =
        reference_for(cache, pose_ + ";change=none", *scene, options.reference, *jobs_);
    result.reference_se = before.relative_standard_error;
    result.reference_seconds += before.from_cache ? 0.0 : before.seconds;
    // The reference frames of the pose before and after the change (none without the image).
    ReferenceImage frame_before;
    ReferenceImage frame_after;
    const auto frame_reference = [&](const std::string& change, ReferenceImage& into) {
        into = reference_image_for(cache, pose_ + ";change=" + change, *scene, *camera,
                                   options.reference, options.image, *jobs_);
        result.reference_seconds += into.from_cache ? 0.0 : into.seconds;
    };
    if (view) {
        frame_reference("none", frame_before);
        result.image_measured = true;
        result.reference_se_image = frame_before.relative_standard_error;
    }
    // GPU ms of the static checkpoints' renders (one sample each: their median is reported).
    std::vector<double> frame_gpu_ms;
    std::vector<double> caustic_gpu_ms;
    // The error of the frame as rendered now; at the phase's last frame its picture too.
    const auto image_error = [&](const ReferenceImage& reference, bool last, bool after) {
        const FrameShot shot = view->render(now);
        const double error = lighting::reference::image_relative_rmse(shot.image, reference.image);
        if (last) {
            write_side_by_side(
                options.out / "frames" / file_name(after ? "after" : "static", ".png"), shot.image,
                reference.image);
        }
        if (!after) {
            frame_gpu_ms.push_back(shot.frame_gpu_ms);
            caustic_gpu_ms.push_back(shot.caustic_gpu_ms);
        }
        return error;
    };
    const auto measure = [&](const ReferenceMaps& reference, std::uint32_t at, bool after) {
        const RealTimeMaps maps = read_real_time(lighting, *scene, now);
        const bool last = (!after && at == options.frames) || (after && at == options.after);
        if (last) {
            dump(maps, reference, after ? "after" : "static");
        }
        const MapErrors errors = map_errors(maps, reference);
        result.caustic_photons = maps.caustic_photons;
        result.caustic_unbinned = maps.caustic_unbinned;
        Checkpoint checkpoint{at, after, false, 0.0, errors.indirect, errors.caustic, std::nullopt};
        // Frames are rendered at checkpoints only (after the change: every checkpoint-th
        // frame and the last), not at every frame the indirect curve samples.
        const bool checkpoint_frame = at % options.checkpoint == 0 || last;
        if (view && checkpoint_frame) {
            checkpoint.image = image_error(after ? frame_after : frame_before, last, after);
        }
        result.checkpoints.push_back(checkpoint);
        return checkpoint;
    };
    for (std::uint32_t f = 1; f <= options.frames; ++f) {
        if (f > 1 && frame(config.budget_ms)) {
            result.static_work_frames = f;
        }
        if (f % options.checkpoint == 0 || f == options.frames) {
            const Checkpoint errors = measure(before, f, false);
            result.indirect = errors.indirect;
            result.caustic = errors.caustic;
            result.image = errors.image.value_or(0.0);
        }
    }
    result.image_net = net_of_reference_noise(result.image, result.reference_se_image);
    result.frame_gpu_ms = percentile(frame_gpu_ms, 0.5);
    result.caustic_gpu_ms = percentile(caustic_gpu_ms, 0.5);
    std::fprintf(stderr, "luxel-bench: %s @ %g ms: converged indirect %.4f, caustic %.4f",
                 config.method.c_str(), config.budget_ms, result.indirect, result.caustic);
    if (result.image_measured) {
        std::fprintf(stderr, ", image %.4f (%.4f net of the reference's noise %.4f)", result.image,
                     result.image_net, result.reference_se_image);
    }
    std::fprintf(stderr, "\n");

    if (change_) {
        result.changed = true;
        const ecs::Entity entity = instance.find(change_->node);
        apply(*change_, registry, entity, file_.string());
        transforms.update();
        // A zero budget syncs the move into the photon world and the maps without doing any
        // lighting work: the reference of the new pose needs the moved geometry.
        lighting.update(0.0, now);
        scene = std::make_unique<lighting::reference::ReferenceScene>(
            lighting::reference::ReferenceScene::from_world(lighting.photons(), lighting.maps()));
        const ReferenceMaps after = reference_for(cache, pose_ + ";change=" + describe(*change_),
                                                  *scene, options.reference, *jobs_);
        result.reference_se_after = after.relative_standard_error;
        result.reference_seconds += after.from_cache ? 0.0 : after.seconds;
        if (view) {
            frame_reference(describe(*change_), frame_after);
            result.reference_se_image_after = frame_after.relative_standard_error;
        }
        result.indirect_at_change = measure(after, 0, true).indirect;
        for (std::uint32_t f = 1; f <= options.after; ++f) {
            frame(config.budget_ms);
            const Checkpoint errors = measure(after, f, true);
            result.after_indirect.push_back(errors.indirect);
            result.indirect_after = errors.indirect;
            result.image_after = errors.image.value_or(result.image_after);
            if (result.recovery_frames < 0 && errors.indirect < 2.0 * result.indirect) {
                result.recovery_frames = static_cast<int>(f);
            }
        }
        // Only every checkpoint-th frame after the change is kept in the checkpoint table
        // (the per-frame curve is after_indirect).
        std::erase_if(result.checkpoints, [&](const Checkpoint& c) {
            return c.after_change && c.frame % options.checkpoint != 0 && c.frame != 0 &&
                   c.frame != options.after;
        });
        std::fprintf(stderr,
                     "luxel-bench: %s @ %g ms: after the change indirect %.4f -> %.4f, back under "
                     "2x converged in %d frames",
                     config.method.c_str(), config.budget_ms, result.indirect_at_change,
                     result.indirect_after, result.recovery_frames);
        if (result.image_measured) {
            std::fprintf(stderr, "; image %.4f at the end (reference noise %.4f)",
                         result.image_after, result.reference_se_image_after);
        }
        std::fprintf(stderr, "\n");
    }

    if (options.animate > 0) {
        // The level's animation plays from the pose (after the change, which the animation
        // may override on the nodes it drives); at every checkpoint a reference of that
        // instant, cached under its time, judges the light maps.
        const std::string changed = change_ ? describe(*change_) : "none";
        for (std::uint32_t f = 1; f <= options.animate; ++f) {
            world::update_animations(registry, options.dt);
            world::update_light_switches(registry, options.dt);
            frame(config.budget_ms);
            if (f % options.checkpoint != 0 && f != options.animate) {
                continue;
            }
            const double played = static_cast<double>(f) * options.dt;
            std::ostringstream instant;
            instant << pose_ << ";change=" << changed << ";animated=" << played;
            scene = std::make_unique<lighting::reference::ReferenceScene>(
                lighting::reference::ReferenceScene::from_world(lighting.photons(),
                                                                lighting.maps()));
            const ReferenceMaps reference =
                reference_for(cache, instant.str(), *scene, options.reference, *jobs_);
            result.reference_seconds += reference.from_cache ? 0.0 : reference.seconds;
            const MapErrors errors = map_errors(read_real_time(lighting, *scene, now), reference);
            Checkpoint checkpoint{f,           false, true, played, errors.indirect, errors.caustic,
                                  std::nullopt};
            result.checkpoints.push_back(checkpoint);
            result.animated_indirect.push_back(errors.indirect);
        }
        result.animated_indirect_median = percentile(result.animated_indirect, 0.5);
        result.animated_indirect_max =
            *std::max_element(result.animated_indirect.begin(), result.animated_indirect.end());
        std::fprintf(stderr,
                     "luxel-bench: %s @ %g ms: animated %u frames, indirect median %.4f, "
                     "largest %.4f over %zu checkpoints\n",
                     config.method.c_str(), config.budget_ms, options.animate,
                     result.animated_indirect_median, result.animated_indirect_max,
                     result.animated_indirect.size());
    }
    result.active_frames = active_ms.size();
    result.ms_median = percentile(active_ms, 0.5);
    result.ms_p95 = percentile(active_ms, 0.95);
    return result;
}

}  // namespace luxel::bench
