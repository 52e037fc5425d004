#include "bench_run.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "config_run.hpp"
#include "luxel/prep/auto_prep.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/scene/gltf.hpp"

namespace luxel::bench {
namespace {

/// The node "auto" moves: the Cornell box's cube, when the level has one.
constexpr const char* kAutoNode = "moving cube";
constexpr float kAutoOffset = 0.3f;  ///< metres along +x: the cube slides 0.7 m in its animation

bool sweeps_gpu_backend(const Options& options) {
    return std::any_of(options.sweeps.begin(), options.sweeps.end(), [](const Sweep& sweep) {
        return sweep.knob == "backend" &&
               std::any_of(sweep.values.begin(), sweep.values.end(),
                           [](const std::string& v) { return v.rfind("gpu", 0) == 0; });
    });
}

}  // namespace

Bench::Bench(const Options& options, const std::filesystem::path& level_file)
    : options_(&options), file_(level_file) {
    jobs_ = std::make_unique<JobSystem>(options.threads);
    // What the level lacks, once, in luxel-sandbox's and luxel-ref's words (the image error is
    // the only use of the level's camera), and the level prepared at load if luxel-prep never
    // did. load_gltf's errors already start with the file's path.
    prep::PlayableLevel playable{options.load_limits, {}, options.auto_prep};
    playable.check.uses_camera = options.image.enabled;
    source_ = prep::load_playable(level_file, playable, *jobs_);
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
    if (options.sky) {
        // Another sky is another level to the references.
        pose << ";sky=" << scene::describe(*options.sky);
        if (options.sky->kind == scene::SkySpec::Kind::Map) {
            std::error_code error;
            pose << ",bytes=" << std::filesystem::file_size(options.sky->map, error);
        }
    }
    pose_ = pose.str();
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
    const LevelRunContext context{options_, file_,       source_,       change_,
                                  pose_,    jobs_.get(), shaders_.get()};
    ConfigRun run(context, config);
    return run.run();
}

}  // namespace luxel::bench
