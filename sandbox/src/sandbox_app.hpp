#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "luxel/ecs/registry.hpp"
#include "luxel/ecs/transform_system.hpp"
#include "luxel/lighting/core/lighting_system.hpp"
#include "luxel/lighting/gpu/caustic_pass.hpp"
#include "luxel/prep/auto_prep.hpp"
#include "luxel/renderer/frame_renderer.hpp"
#include "luxel/runtime/jobs.hpp"
#include "luxel/runtime/shader_library.hpp"
#include "luxel/scene/gltf.hpp"
#include "luxel/world/scene_instance.hpp"
#include "run_report.hpp"
#include "sandbox_level.hpp"

namespace luxel::sandbox {

struct AppSettings {
    std::string level = "sandbox";
    int width = 640;
    int height = 360;
    double budget_ms = 4.0;
    int threads = 0;
    /// Wall-time limit of the lighting warm-up at load (0: none, start dark).
    double warm_up_ms = 20'000.0;
    scene::LoadOptions load_limits;     ///< --limit
    std::optional<scene::SkySpec> sky;  ///< --sky: instead of the level's
    prep::AutoPrepSettings auto_prep;   ///< --no-auto-prep, --prep-cache
    bool anti_aliasing = true;          ///< --aa: smooth the frame's geometric edges
    bool soft_shadows = true;           ///< --soft-shadows: penumbrae of lights with a radius
    bool bicubic_light_maps = false;    ///< --lightmap-filter bicubic
    bool sky_edges = true;              ///< --sky-edges: sky coverage at silhouettes
};

/// The game: a level in an ECS registry, the game systems that move it, the lighting system and
/// the renderer. One frame is what a game's loop does:
///     animations, light switches, bounce system -> TransformSystem -> LightingSystem::update
///     -> render (FrameRenderer, and the caustic pass when the FeaturePlan has caustics).
/// There is no lighting logic here: the sandbox only drives luxel the way a game would.
/// Needs a current GL 4.5 context.
class SandboxApp {
  public:
    SandboxApp(const AppSettings& settings, JobSystem& jobs, const ShaderLibrary& shaders);

    /// What one frame measured.
    struct FrameResult {
        double lighting_ms = 0.0;
        RunReport::Frame report;
    };
    /// Advances the game by `dt` seconds to `time` and renders from `camera`. With `frozen`,
    /// nothing moves (the lighting still converges).
    FrameResult frame(double time, double dt, const renderer::FrameCamera& camera, bool frozen);

    [[nodiscard]] renderer::FrameRenderer& renderer() { return *renderer_; }
    [[nodiscard]] const lighting::LightingSystem& lighting() const { return *lighting_; }
    [[nodiscard]] const scene::Scene& scene() const { return *scene_; }
    [[nodiscard]] const std::string& level_name() const { return level_name_; }
    [[nodiscard]] const std::filesystem::path& level_file() const { return level_file_; }
    [[nodiscard]] const CameraPath& camera_path() const { return path_; }
    [[nodiscard]] double budget_ms() const { return budget_ms_; }
    [[nodiscard]] double warm_up_ms() const { return warm_up_ms_; }
    void set_budget_ms(double budget) { budget_ms_ = budget; }

  private:
    std::string level_name_;
    std::filesystem::path level_file_;
    std::shared_ptr<const scene::Scene> scene_;
    ecs::Registry registry_;
    world::SceneInstance instance_;
    ecs::TransformSystem transforms_{registry_};
    std::unique_ptr<lighting::LightingSystem> lighting_;
    std::unique_ptr<renderer::FrameRenderer> renderer_;
    const ShaderLibrary* shaders_;
    CameraPath path_;
    double budget_ms_;
    double warm_up_ms_ = 0.0;
    int width_;
    int height_;
};

/// The name the level goes by in reports: a built-in level's name, or a file's stem.
[[nodiscard]] std::string level_display_name(const std::string& name_or_path);

}  // namespace luxel::sandbox
