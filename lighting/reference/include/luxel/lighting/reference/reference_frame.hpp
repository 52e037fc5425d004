#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/lighting/reference/path_estimator.hpp"
#include "luxel/lighting/reference/reference_scene.hpp"
#include "luxel/runtime/image.hpp"
#include "luxel/runtime/jobs.hpp"

/// Reference frames (docs/METHOD.md §10.1): the linear HDR image of a camera by path tracing with
/// next-event estimation, the image error's reference.
namespace luxel::lighting::reference {

/// A camera as OpenGL sees it: view and projection matrices (NDC z in [-1, 1]) and the image
/// size. Rows of the image run top first.
struct ReferenceCamera {
    glm::mat4 view{1.0f};
    glm::mat4 projection{1.0f};
    int width = 320;
    int height = 240;

    /// A perspective camera at `eye` looking at `target`, `vertical_fov` radians.
    [[nodiscard]] static ReferenceCamera look_at(const glm::vec3& eye, const glm::vec3& target,
                                                 float vertical_fov, int width, int height,
                                                 const glm::vec3& up = {0.0f, 1.0f, 0.0f});
    /// The world-space ray through image point (x, y) in pixels (top-left origin); the
    /// direction is unit. Works for perspective and orthographic projections.
    void ray(double x, double y, glm::vec3& origin, glm::vec3& direction) const;
};

struct ReferenceFrameSettings {
    std::uint32_t samples_per_pass = 4;  ///< per pixel, jittered within the pixel
    PathSettings paths;
    std::uint32_t seed = 1;
};

/// Progressive like ReferenceIntegrator: per pixel the sum and sum of squares of its samples,
/// each from the pixel's own SampleStream (deterministic for a seed, any thread count).
/// Diffuse surfaces visible (directly or through glass) take point, spot and directional
/// caustics from `caustic_irradiance` (per global texel, as CausticReference::irradiance_all
/// gives), so they appear at texel resolution.
class ReferenceFrame {
  public:
    ReferenceFrame(const ReferenceScene& scene, ReferenceCamera camera,
                   ReferenceFrameSettings settings);

    void run_pass(JobSystem& jobs, std::span<const glm::dvec3> caustic_irradiance = {});
    /// The size of the passes to come.
    void set_samples_per_pass(std::uint32_t samples) { settings_.samples_per_pass = samples; }

    [[nodiscard]] std::uint32_t passes() const { return passes_; }
    [[nodiscard]] std::uint64_t samples() const { return samples_; }
    [[nodiscard]] const ReferenceCamera& camera() const { return camera_; }
    /// Mean radiance per pixel, W/(m^2 sr), alpha 1.
    [[nodiscard]] Image image() const;
    /// The standard error of each pixel's mean (alpha 1).
    [[nodiscard]] Image standard_error_image() const;
    /// The frame's own expected image relRMSE: sqrt(sum se^2 / sum mean^2) over pixels and
    /// channels (0 for a black frame).
    [[nodiscard]] double relative_standard_error() const;
    [[nodiscard]] const PathCounters& counters() const { return counters_; }

  private:
    const ReferenceScene* scene_;
    ReferenceCamera camera_;
    ReferenceFrameSettings settings_;
    std::vector<glm::dvec3> sum_;
    std::vector<glm::dvec3> sum_squares_;
    std::uint32_t passes_ = 0;
    std::uint64_t samples_ = 0;
    PathCounters counters_;
};

}  // namespace luxel::lighting::reference
