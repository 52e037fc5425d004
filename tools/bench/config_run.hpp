#pragma once

// One configuration's run through a level: the live level, its lighting system and (for the
// image error) its frame view, and the measurements taken phase by phase: static until
// converged, the scripted change, the level's animation.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bench_config.hpp"
#include "bench_options.hpp"
#include "bench_run.hpp"
#include "frame_view.hpp"
#include "image_reference.hpp"
#include "luxel/ecs/registry.hpp"
#include "luxel/ecs/transform_system.hpp"
#include "luxel/lighting/core/lighting_system.hpp"
#include "luxel/lighting/gpu/hemi_plane_gatherer.hpp"
#include "luxel/lighting/reference/reference_scene.hpp"
#include "luxel/runtime/jobs.hpp"
#include "luxel/runtime/shader_library.hpp"
#include "luxel/scene/scene.hpp"
#include "luxel/world/scene_instance.hpp"
#include "map_error.hpp"
#include "reference_cache.hpp"

namespace luxel::bench {

/// What every configuration's run of one level shares (Bench holds it).
struct LevelRunContext {
    const Options* options = nullptr;
    std::filesystem::path file;
    std::shared_ptr<const scene::Scene> source;
    std::optional<Change> change;
    std::string pose;  ///< the cache key's level and pose part
    JobSystem* jobs = nullptr;
    ShaderLibrary* shaders = nullptr;  ///< null when no GL context was made
};

class ConfigRun {
  public:
    ConfigRun(const LevelRunContext& context, const BenchConfig& config);
    ~ConfigRun();
    ConfigRun(const ConfigRun&) = delete;
    ConfigRun& operator=(const ConfigRun&) = delete;

    /// Runs every phase the options ask for and returns what was measured.
    RunResult run();

  private:
    /// One frame of lighting at `budget` ms; whether the scheduler ran any work.
    bool frame(double budget);
    /// The reference scene of the live level as it stands now.
    void capture_reference_scene();
    [[nodiscard]] std::string file_name(const char* phase, const char* extension) const;
    void frame_reference(const std::string& change, ReferenceImage& into);
    /// The error of the frame as rendered now; at the phase's last frame its picture too.
    double image_error(const ReferenceImage& reference, bool last, bool after);
    Checkpoint measure(const ReferenceMaps& reference, std::uint32_t at, bool after);

    void static_phase();
    void change_phase();
    void animated_phase();

    const LevelRunContext& context_;
    const Options& options_;
    RunResult result_;
    ecs::Registry registry_;
    world::SceneInstance instance_;
    std::unique_ptr<ecs::TransformSystem> transforms_;
    std::unique_ptr<lighting::LightingSystem> lighting_;
    std::unique_ptr<lighting::HemiPlaneGatherer> gpu_gatherer_;
    std::optional<lighting::reference::ReferenceCamera> camera_;
    std::unique_ptr<FrameView> view_;
    std::unique_ptr<lighting::reference::ReferenceScene> scene_;
    std::vector<std::uint32_t> regions_;  ///< texel_regions(*scene_)
    double now_ = 0.0;
    std::vector<double> active_ms_;
    /// The reference frames of the pose before and after the change (none without the image).
    ReferenceImage frame_before_;
    ReferenceImage frame_after_;
    /// GPU ms of the static checkpoints' renders (one sample each: their median is reported).
    std::vector<double> frame_gpu_ms_;
    std::vector<double> caustic_gpu_ms_;
};

}  // namespace luxel::bench
