#include "config_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <type_traits>

#include <glm/gtc/quaternion.hpp>

#include "level.hpp"
#include "luxel/ecs/transform.hpp"
#include "luxel/lighting/components.hpp"
#include "luxel/lighting/reference/error_metrics.hpp"
#include "luxel/runtime/clock.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/runtime/image.hpp"
#include "luxel/world/animation_system.hpp"
#include "luxel/world/skinning.hpp"
#include "luxel/world/sky.hpp"
#include "luxel/world/vertex_wave.hpp"

namespace luxel::bench {
namespace {

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

/// The level instantiated with its animations posed at `time` (as luxel-ref poses it), then
/// frozen: only the scripted change moves.
world::SceneInstance posed_instance(ecs::Registry& registry,
                                    const std::shared_ptr<const scene::Scene>& source, double time,
                                    const std::optional<scene::SkySpec>& sky) {
    world::InstantiateOptions instantiate_options;
    instantiate_options.play_animations = true;
    instantiate_options.sky = sky;
    world::SceneInstance instance = world::instantiate(registry, source, instantiate_options);
    world::update_animations(registry, time);
    world::update_light_switches(registry, time);
    world::update_waves(registry, time);
    world::update_sky(registry);
    return instance;
}

/// relRMSE of the frame against the reference over the pixels without a light map whose
/// (2 margin + 1)^2 neighbourhood has none either (margin 0: every such pixel).
struct UnmappedError {
    double relrmse = -1.0;
    std::size_t pixels = 0;
};

/// relRMSE over RGB of `image` against `reference` on the pixels whose reference alpha is
/// above one half (the caustic reference's pixels that see a diffuse surface directly);
/// 0 where they hold nothing.
double masked_relative_rmse(const Image& image, const Image& reference) {
    double error = 0.0;
    double signal = 0.0;
    for (int y = 0; y < reference.height && y < image.height; ++y) {
        for (int x = 0; x < reference.width && x < image.width; ++x) {
            const glm::vec4 want = reference.pixel(x, y);
            if (!(want.a > 0.5f)) {
                continue;
            }
            const glm::dvec3 d =
                glm::dvec3(glm::vec3(image.pixel(x, y))) - glm::dvec3(glm::vec3(want));
            error += glm::dot(d, d);
            signal += glm::dot(glm::dvec3(glm::vec3(want)), glm::dvec3(glm::vec3(want)));
        }
    }
    return signal > 0.0 ? std::sqrt(error / signal) : 0.0;
}

UnmappedError unmapped_error(const FrameShot& shot, const Image& reference, int margin) {
    const int w = shot.image.width;
    const int h = shot.image.height;
    const auto unmapped = [&](int x, int y) {
        return x >= 0 && y >= 0 && x < w && y < h &&
               shot.unmapped[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) +
                             static_cast<std::size_t>(x)] != 0;
    };
    double diff = 0.0;
    double norm = 0.0;
    UnmappedError error;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            bool inside = true;
            for (int dy = -margin; dy <= margin && inside; ++dy) {
                for (int dx = -margin; dx <= margin && inside; ++dx) {
                    inside = unmapped(x + dx, y + dy);
                }
            }
            if (!inside) {
                continue;
            }
            ++error.pixels;
            const glm::vec4 a = shot.image.pixel(x, y);
            const glm::vec4 b = reference.pixel(x, y);
            for (int c = 0; c < 3; ++c) {
                const double d = static_cast<double>(a[c]) - static_cast<double>(b[c]);
                diff += d * d;
                norm += static_cast<double>(b[c]) * static_cast<double>(b[c]);
            }
        }
    }
    error.relrmse = error.pixels > 0 && norm > 0.0 ? std::sqrt(diff / norm) : -1.0;
    return error;
}

}  // namespace

ConfigRun::ConfigRun(const LevelRunContext& context, const BenchConfig& config)
    : context_(context),
      options_(*context.options),
      instance_(
          posed_instance(registry_, context.source, context.options->time, context.options->sky)) {
    result_.config = config;
    for (const std::string& node : options_.unmapped) {
        const ecs::Entity entity = instance_.find(node);
        if (entity == ecs::null_entity) {
            throw Error("--no-light-map " + node + ": " + context.file.string() +
                        " has no node of that name");
        }
        if (!registry_.has<lighting::LightmappedSurface>(entity)) {
            throw Error("--no-light-map " + node + ": node '" + node + "' of " +
                        context.file.string() + " has no light map to leave out");
        }
        registry_.remove<lighting::LightmappedSurface>(entity);
    }
    transforms_ = std::make_unique<ecs::TransformSystem>(registry_);
    transforms_->update();
    world::update_skins(registry_);  // skinned meshes follow their joints
    lighting_ =
        std::make_unique<lighting::LightingSystem>(registry_, *context.jobs, config.lighting());
    if (config.backend.rfind("gpu", 0) == 0) {
        // gpu: the hemi-plane as luxel runs it (turned each pass, the band it misses and the
        // light behind mirrors and glass traced by CPU rays); gpu-turn: turned, no CPU rays;
        // gpu-plane: the paper's plane alone.
        lighting::HemiPlaneSettings hemi;
        hemi.rotate = config.backend != "gpu-plane";
        if (config.backend != "gpu") {
            hemi.horizon_rays = 0;
            hemi.specular_rays = 0;
        }
        gpu_gatherer_ = std::make_unique<lighting::HemiPlaneGatherer>(
            lighting_->photons().ray_scene(), lighting_->maps().aim(), hemi, *context.shaders);
        lighting_->set_gatherer(gpu_gatherer_.get());
    }
    if (options_.image.enabled) {
        // A level without a camera is seen from the default view, as luxel-sandbox and
        // luxel-ref see it (the warning at load says which).
        if (const auto& spec = options_.image.camera) {
            camera_ = lighting::reference::ReferenceCamera::look_at(
                spec->eye, spec->target, glm::radians(spec->fov_degrees), options_.image.width,
                options_.image.height);
        } else {
            camera_ = ref::level_camera(registry_, instance_, options_.image.width,
                                        options_.image.height);
        }
        if (!camera_) {
            camera_ = ref::default_camera(options_.image.width, options_.image.height);
        }
        // kernel=layer: the caustic layer where a pixel has a light map, Larsen's splat elsewhere.
        const bool layer = config.kernel.rfind("layer", 0) == 0;
        const FrameChoices choices{config.kernel == "layer" ? lighting::CausticKernel::Larsen
                                   : layer                  ? parse_kernel(config.kernel.substr(6))
                                                            : parse_kernel(config.kernel),
                                   config.aa == "on",
                                   config.lightmap == "bicubic",
                                   config.sky_edges == "on",
                                   layer,
                                   static_cast<float>(config.footprint_scale),
                                   static_cast<float>(config.footprint_min)};
        view_ =
            std::make_unique<FrameView>(registry_, *lighting_, *camera_, choices, *context.shaders);
    }
}

ConfigRun::~ConfigRun() = default;

RunResult ConfigRun::run() {
    static_phase();
    if (context_.change) {
        change_phase();
    }
    if (options_.animate > 0) {
        animated_phase();
    }
    result_.active_frames = active_ms_.size();
    result_.ms_median = percentile(active_ms_, 0.5);
    result_.ms_p95 = percentile(active_ms_, 0.95);
    return result_;
}

bool ConfigRun::frame(double budget) {
    now_ += options_.dt;
    transforms_->update();
    world::update_skins(registry_);  // skinned meshes follow their joints
    Stopwatch clock;
    const lighting::LightingStats& stats = lighting_->update(budget, now_);
    const double ms = clock.elapsed_ms();
    result_.frame_ms.push_back(ms);
    if (stats.schedule.units_done > 0) {
        active_ms_.push_back(ms);
        return true;
    }
    return false;
}

void ConfigRun::capture_reference_scene() {
    // luxel-ref's check, before the reference allocates anything per texel.
    ref::check_reference_memory(
        context_.file, lighting::reference::ReferenceScene::count_texels(lighting_->maps()),
        options_.load_limits);
    scene_ = std::make_unique<lighting::reference::ReferenceScene>(
        lighting::reference::ReferenceScene::from_world(lighting_->photons(), lighting_->maps()));
    regions_ = texel_regions(*scene_);
}

std::string ConfigRun::file_name(const char* phase, const char* extension) const {
    std::ostringstream name;
    name << result_.config.method << "_" << result_.config.budget_ms << "ms_" << phase << extension;
    return name.str();
}

void ConfigRun::frame_reference(const std::string& change, ReferenceImage& into) {
    into = reference_image_for(options_.out / "cache", context_.pose + ";change=" + change, *scene_,
                               *camera_, options_.reference, options_.image, *context_.jobs);
    result_.reference_seconds += into.from_cache ? 0.0 : into.seconds;
}

double ConfigRun::image_error(const ReferenceImage& reference, bool last, bool after) {
    const FrameShot shot = view_->render(now_);
    const double error = lighting::reference::image_relative_rmse(shot.image, reference.image);
    if (!after) {
        // Where the irradiance probes light (no light map): the same relRMSE over those
        // pixels alone, which a whole-frame figure dilutes with every light-mapped wall; and
        // over their interior (the whole 5x5 neighbourhood without a light map), which leaves
        // out the silhouettes, where a dark receiver against a bright wall makes edge aliasing
        // weigh as much as the probes' error.
        const UnmappedError all = unmapped_error(shot, reference.image, 0);
        const UnmappedError interior = unmapped_error(shot, reference.image, 2);
        result_.unmapped_pixels = all.pixels;
        result_.image_unmapped = all.relrmse;
        result_.unmapped_interior_pixels = interior.pixels;
        result_.image_unmapped_interior = interior.relrmse;
    }
    if (options_.image.caustic_pixels && !after) {
        const Image caustics = view_->render_caustics(now_);
        result_.caustic_pixels = masked_relative_rmse(caustics, reference.caustic_pixels);
        result_.reference_se_caustic_pixels = reference.caustic_pixels_se;
        if (last) {
            write_side_by_side(options_.out / "frames" / file_name("static_caustics", ".png"),
                               caustics, reference.caustic_pixels);
            write_exr(options_.out / "frames" / file_name("static_caustics", ".exr"), caustics);
        }
    }
    if (last) {
        const char* phase = after ? "after" : "static";
        write_side_by_side(options_.out / "frames" / file_name(phase, ".png"), shot.image,
                           reference.image);
        // The frame itself, linear, for luxel-frame-error against the cached reference frame.
        write_exr(options_.out / "frames" / file_name(phase, ".exr"), shot.image);
    }
    if (!after) {
        frame_gpu_ms_.push_back(shot.frame_gpu_ms);
        caustic_gpu_ms_.push_back(shot.caustic_gpu_ms);
    }
    return error;
}

Checkpoint ConfigRun::measure(const ReferenceMaps& reference, std::uint32_t at, bool after) {
    const RealTimeMaps maps = read_real_time(*lighting_, *scene_, now_);
    const bool last = (!after && at == options_.frames) || (after && at == options_.after);
    if (last && options_.dump_maps) {
        write_maps_json(options_.out / "maps" / file_name(after ? "after" : "static", ".json"),
                        *scene_, maps, reference);
    }
    const MapErrors errors = map_errors(maps, reference, regions_);
    result_.caustic_photons = maps.caustic_photons;
    result_.caustic_unbinned = maps.caustic_unbinned;
    Checkpoint checkpoint{at, after, false, 0.0, errors.indirect, errors.caustic, std::nullopt};
    checkpoint.indirect_region = errors.indirect_region;
    checkpoint.indirect_p99 = errors.indirect_p99;
    // Frames are rendered at checkpoints only (after the change: every checkpoint-th
    // frame and the last), not at every frame the indirect curve samples.
    const bool checkpoint_frame = at % options_.checkpoint == 0 || last;
    if (view_ && checkpoint_frame) {
        checkpoint.image = image_error(after ? frame_after_ : frame_before_, last, after);
    }
    result_.checkpoints.push_back(checkpoint);
    return checkpoint;
}

void ConfigRun::static_phase() {
    const BenchConfig& config = result_.config;
    if (frame(config.budget_ms)) {
        result_.static_work_frames = 1;
    }
    capture_reference_scene();
    const ReferenceMaps before =
        reference_for(options_.out / "cache", context_.pose + ";change=none", *scene_,
                      options_.reference, *context_.jobs);
    result_.reference_se = before.relative_standard_error;
    result_.reference_seconds += before.from_cache ? 0.0 : before.seconds;
    if (view_) {
        frame_reference("none", frame_before_);
        result_.image_measured = true;
        result_.reference_se_image = frame_before_.relative_standard_error;
    }
    for (std::uint32_t f = 1; f <= options_.frames; ++f) {
        if (f > 1 && frame(config.budget_ms)) {
            result_.static_work_frames = f;
        }
        if (f % options_.checkpoint == 0 || f == options_.frames) {
            const Checkpoint errors = measure(before, f, false);
            result_.indirect = errors.indirect;
            result_.caustic = errors.caustic;
            result_.indirect_region = errors.indirect_region;
            result_.indirect_p99 = errors.indirect_p99;
            result_.image = errors.image.value_or(0.0);
        }
    }
    result_.image_net = net_of_reference_noise(result_.image, result_.reference_se_image);
    result_.frame_gpu_ms = percentile(frame_gpu_ms_, 0.5);
    result_.caustic_gpu_ms = percentile(caustic_gpu_ms_, 0.5);
    std::fprintf(stderr,
                 "luxel-bench: %s @ %g ms: converged indirect %.4f (worst region %.4f, p99 texel "
                 "%.4f), caustic %.4f",
                 config.method.c_str(), config.budget_ms, result_.indirect, result_.indirect_region,
                 result_.indirect_p99, result_.caustic);
    if (result_.image_measured) {
        std::fprintf(stderr, ", image %.4f (%.4f net of the reference's noise %.4f)", result_.image,
                     result_.image_net, result_.reference_se_image);
        if (result_.caustic_pixels >= 0.0) {
            std::fprintf(stderr, ", caustic at pixel resolution %.4f (reference noise %.4f)",
                         result_.caustic_pixels, result_.reference_se_caustic_pixels);
        }
        if (result_.unmapped_pixels > 0) {
            std::fprintf(stderr,
                         ", pixels without a light map %.4f (%zu pixels; interior %.4f, %zu)",
                         result_.image_unmapped, result_.unmapped_pixels,
                         result_.image_unmapped_interior, result_.unmapped_interior_pixels);
        }
    }
    std::fprintf(stderr, "\n");
}

void ConfigRun::change_phase() {
    const BenchConfig& config = result_.config;
    const Change& change = *context_.change;
    result_.changed = true;
    apply(change, registry_, instance_.find(change.node), context_.file.string());
    world::update_sky(registry_);  // a turned sun turns its daylight sky (time of day)
    transforms_->update();
    world::update_skins(registry_);  // skinned meshes follow their joints
    // A zero budget syncs the move into the photon world and the maps without doing any
    // lighting work: the reference of the new pose needs the moved geometry.
    lighting_->update(0.0, now_);
    capture_reference_scene();
    const ReferenceMaps after =
        reference_for(options_.out / "cache", context_.pose + ";change=" + describe(change),
                      *scene_, options_.reference, *context_.jobs);
    result_.reference_se_after = after.relative_standard_error;
    result_.reference_seconds += after.from_cache ? 0.0 : after.seconds;
    if (view_) {
        frame_reference(describe(change), frame_after_);
        result_.reference_se_image_after = frame_after_.relative_standard_error;
    }
    const Checkpoint at_change = measure(after, 0, true);
    result_.indirect_at_change = at_change.indirect;
    result_.region_at_change = at_change.indirect_region;
    result_.p99_at_change = at_change.indirect_p99;
    for (std::uint32_t f = 1; f <= options_.after; ++f) {
        frame(config.budget_ms);
        const Checkpoint errors = measure(after, f, true);
        result_.after_indirect.push_back(errors.indirect);
        result_.after_region.push_back(errors.indirect_region);
        result_.after_p99.push_back(errors.indirect_p99);
        result_.after_caustic.push_back(errors.caustic);
        result_.indirect_after = errors.indirect;
        result_.region_after = errors.indirect_region;
        result_.p99_after = errors.indirect_p99;
        result_.image_after = errors.image.value_or(result_.image_after);
        const bool global = errors.indirect < 2.0 * result_.indirect;
        if (result_.recovery_frames < 0 && global) {
            result_.recovery_frames = static_cast<int>(f);
        }
        const bool local = global && errors.indirect_region < 2.0 * result_.indirect_region &&
                           errors.indirect_p99 < 2.0 * result_.indirect_p99;
        if (result_.recovery_frames_local < 0 && local) {
            result_.recovery_frames_local = static_cast<int>(f);
        }
    }
    // Only every checkpoint-th frame after the change is kept in the checkpoint table
    // (the per-frame curve is after_indirect).
    std::erase_if(result_.checkpoints, [&](const Checkpoint& c) {
        return c.after_change && c.frame % options_.checkpoint != 0 && c.frame != 0 &&
               c.frame != options_.after;
    });
    std::fprintf(stderr,
                 "luxel-bench: %s @ %g ms: after the change indirect %.4f -> %.4f, back under "
                 "2x converged in %d frames; worst region %.4f -> %.4f, p99 texel %.4f -> "
                 "%.4f, all three under 2x converged in %d frames",
                 config.method.c_str(), config.budget_ms, result_.indirect_at_change,
                 result_.indirect_after, result_.recovery_frames, result_.region_at_change,
                 result_.region_after, result_.p99_at_change, result_.p99_after,
                 result_.recovery_frames_local);
    if (result_.image_measured) {
        std::fprintf(stderr, "; image %.4f at the end (reference noise %.4f)", result_.image_after,
                     result_.reference_se_image_after);
    }
    if (at_change.caustic > 0.0 && !result_.after_caustic.empty()) {
        std::fprintf(stderr, "; caustic %.4f -> %.4f", at_change.caustic,
                     result_.after_caustic.back());
    }
    std::fprintf(stderr, "\n");
}

void ConfigRun::animated_phase() {
    // The level's animation plays from the pose (after the change, which the animation
    // may override on the nodes it drives); at every checkpoint a reference of that
    // instant, cached under its time, judges the light maps.
    const BenchConfig& config = result_.config;
    const std::string changed = context_.change ? describe(*context_.change) : "none";
    for (std::uint32_t f = 1; f <= options_.animate; ++f) {
        world::update_animations(registry_, options_.dt);
        world::update_light_switches(registry_, options_.dt);
        world::update_waves(registry_, options_.dt);
        world::update_sky(registry_);
        frame(config.budget_ms);
        if (f % options_.checkpoint != 0 && f != options_.animate) {
            continue;
        }
        const double played = static_cast<double>(f) * options_.dt;
        std::ostringstream instant;
        instant << context_.pose << ";change=" << changed << ";animated=" << played;
        capture_reference_scene();
        const ReferenceMaps reference = reference_for(options_.out / "cache", instant.str(),
                                                      *scene_, options_.reference, *context_.jobs);
        result_.reference_seconds += reference.from_cache ? 0.0 : reference.seconds;
        const MapErrors errors =
            map_errors(read_real_time(*lighting_, *scene_, now_), reference, regions_);
        Checkpoint checkpoint{f,           false, true, played, errors.indirect, errors.caustic,
                              std::nullopt};
        checkpoint.indirect_region = errors.indirect_region;
        checkpoint.indirect_p99 = errors.indirect_p99;
        result_.checkpoints.push_back(checkpoint);
        result_.animated_indirect.push_back(errors.indirect);
    }
    result_.animated_indirect_median = percentile(result_.animated_indirect, 0.5);
    result_.animated_indirect_max =
        *std::max_element(result_.animated_indirect.begin(), result_.animated_indirect.end());
    std::fprintf(stderr,
                 "luxel-bench: %s @ %g ms: animated %u frames, indirect median %.4f, "
                 "largest %.4f over %zu checkpoints\n",
                 config.method.c_str(), config.budget_ms, options_.animate,
                 result_.animated_indirect_median, result_.animated_indirect_max,
                 result_.animated_indirect.size());
}

}  // namespace luxel::bench
