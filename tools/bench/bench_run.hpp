#pragma once

// What one luxel-bench invocation measures per configuration (RunResult, Checkpoint), and the
// Bench that holds the level, the jobs and the GL context for all of its runs; each
// configuration's run is a ConfigRun (config_run.hpp).

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bench_config.hpp"
#include "bench_options.hpp"
#include "luxel/runtime/gl_context.hpp"
#include "luxel/runtime/jobs.hpp"
#include "luxel/runtime/shader_library.hpp"
#include "luxel/scene/scene.hpp"

namespace luxel::bench {

struct Checkpoint {
    std::uint32_t frame = 0;  ///< frames since the start of its phase
    bool after_change = false;
    bool animated = false;  ///< in the animated phase (--animate)
    double time = 0.0;      ///< animated: seconds of animation played since the pose
    double indirect = 0.0;  ///< light-map relRMSE
    double caustic = 0.0;
    std::optional<double> image;  ///< image relRMSE; none when the image is off
    /// The indirect light's local error (MapErrors): worst 8x8-texel region, 99th-percentile
    /// texel.
    double indirect_region = 0.0;
    double indirect_p99 = 0.0;
};

struct RunResult {
    BenchConfig config;
    std::vector<double> frame_ms;  ///< real lighting ms of every frame (static, then after)
    /// Median and 95th percentile over the active frames: those in which the scheduler ran
    /// work (a converged static scene costs nothing and would pull the median to zero).
    double ms_median = 0.0;
    double ms_p95 = 0.0;
    std::size_t active_frames = 0;
    /// The last static frame that ran lighting work (1-based; 0: none).
    std::uint32_t static_work_frames = 0;
    double indirect = 0.0;  ///< at the end of the static phase ("converged")
    double caustic = 0.0;
    /// The converged indirect light's local error (Checkpoint::indirect_region, indirect_p99).
    double indirect_region = 0.0;
    double indirect_p99 = 0.0;
    bool changed = false;
    double indirect_at_change = 0.0;  ///< after the move, before any lighting work
    double indirect_after = 0.0;      ///< at the end of the frames after the change
    /// Frames after the change until the indirect error is under twice `indirect`; -1: not
    /// within the frames run.
    int recovery_frames = -1;
    std::vector<double> after_indirect;  ///< per frame after the change (frame 1 first)
    /// The local error after the change: at the change, at the end, per frame (frame 1 first).
    double region_at_change = 0.0;
    double region_after = 0.0;
    double p99_at_change = 0.0;
    double p99_after = 0.0;
    std::vector<double> after_region;
    std::vector<double> after_p99;
    /// The caustic light maps' error per frame after the change (frame 1 first): how fast the
    /// moved caustic is back.
    std::vector<double> after_caustic;
    /// Frames after the change until the global, the worst-region and the 99th-percentile
    /// errors are all under twice their converged values (a dark patch the global error
    /// dilutes holds this back); -1: not within the frames run.
    int recovery_frames_local = -1;
    std::vector<Checkpoint> checkpoints;
    /// The references' own relative standard errors: direct, indirect, caustic.
    std::array<double, 3> reference_se{};
    std::array<double, 3> reference_se_after{};
    double reference_seconds = 0.0;  ///< computing (not loading) the references this run
    std::size_t caustic_photons = 0;
    std::size_t caustic_unbinned = 0;
    /// The image error (--image): the real-time frame against the reference frame of the same
    /// camera, at the end of the static frames and of the frames after the change.
    bool image_measured = false;
    double image = 0.0;
    double image_net = 0.0;  ///< net_of_reference_noise(image, reference_se_image)
    /// The image relRMSE over the pixels without a light map alone (the irradiance probes'
    /// receivers) at the last static checkpoint; -1 where the frame has none.
    double image_unmapped = -1.0;
    std::size_t unmapped_pixels = 0;
    /// The same over their interior: pixels whose 5x5 neighbourhood has no light map either.
    double image_unmapped_interior = -1.0;
    std::size_t unmapped_interior_pixels = 0;
    double image_after = 0.0;
    double reference_se_image = 0.0;
    /// --caustic-pixels: the caustic term's relRMSE over the pixels that see a diffuse surface
    /// directly, against the reference's pixel-resolution caustic, at the last static
    /// checkpoint (-1: not measured), and that reference's own expected relRMSE.
    double caustic_pixels = -1.0;
    double reference_se_caustic_pixels = 0.0;
    double reference_se_image_after = 0.0;
    /// Median over the static checkpoints' renders: FrameRenderer's passes, the caustic pass.
    double frame_gpu_ms = 0.0;
    double caustic_gpu_ms = 0.0;
    /// The animated phase (--animate): the indirect error at each checkpoint against the
    /// reference of that instant; its median and largest value.
    std::vector<double> animated_indirect;
    double animated_indirect_median = 0.0;
    double animated_indirect_max = 0.0;
};

/// Holds the level, the jobs and (for the image error and the GPU gather backend) the GL
/// context for all runs of one luxel-bench invocation.
class Bench {
  public:
    /// Loads the level file; throws luxel::Error if it cannot.
    Bench(const Options& options, const std::filesystem::path& level_file);
    ~Bench();

    [[nodiscard]] RunResult run(const BenchConfig& config);
    /// The change that runs after the static phase (resolved from --change), if any.
    [[nodiscard]] const std::optional<Change>& change() const { return change_; }
    /// The GL renderer and version, or empty when no context was needed.
    [[nodiscard]] std::string gl_description() const;

  private:
    const Options* options_;
    std::filesystem::path file_;
    std::shared_ptr<const scene::Scene> source_;
    std::optional<Change> change_;
    std::string pose_;  ///< the cache key's level and pose part
    std::unique_ptr<JobSystem> jobs_;
    std::unique_ptr<GlContext> gl_;  ///< before every GL object of a run, and outlives them
    std::unique_ptr<ShaderLibrary> shaders_;
};

}  // namespace luxel::bench
