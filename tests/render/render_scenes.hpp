#pragma once

// Scenes and helpers for the frame renderer tests and benchmark: a headless GL context, small
// hand-built scenes (a lit plane, a blocker, light-mapped planes) in an ECS registry driven by
// a real LightingSystem, and read-back of G-buffer textures.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/ecs/registry.hpp"
#include "luxel/ecs/transform_system.hpp"
#include "luxel/lighting/components.hpp"
#include "luxel/lighting/core/lighting_system.hpp"
#include "luxel/renderer/frame_camera.hpp"
#include "luxel/runtime/gl.hpp"
#include "luxel/runtime/gl_context.hpp"
#include "luxel/runtime/jobs.hpp"
#include "luxel/world/scene_instance.hpp"

namespace luxel::test {

/// A headless GL 4.5 context (EGL: llvmpipe on the surfaceless platform without a GPU).
[[nodiscard]] std::unique_ptr<GlContext> make_render_context();

/// A horizontal square of half-width `half` at height `height`, facing +y (or -y), with
/// normals and light-map UVs spanning [0, 1]^2 corner to corner.
[[nodiscard]] scene::Primitive horizontal_square(const glm::vec3& centre, float half,
                                                 bool facing_up = true);

/// A one-mesh scene holding `primitive` with a material of `albedo`. `textured` gives the
/// material a base-colour image index, which makes its IIM hold irradiance.
[[nodiscard]] std::shared_ptr<scene::Scene> single_mesh_scene(scene::Primitive primitive,
                                                              const glm::vec3& albedo,
                                                              bool textured = false);

/// RGBA8 pixels (rows top first) encoded as a PNG in memory with stb_image_write.
[[nodiscard]] std::vector<std::uint8_t> encode_png(int width, int height,
                                                   const std::vector<std::uint8_t>& rgba);

/// A light-map layout of one surface (primitive 0) covering a whole page of `page_size`.
[[nodiscard]] scene::LightmapLayout whole_page_layout(int page_size, double area);

/// A small lighting configuration: few photons, so LightingSystem::update is quick.
[[nodiscard]] lighting::LightingConfig small_lighting_config();

/// An ECS world with transforms and a LightingSystem created on demand (after the entities).
struct RenderWorld {
    ecs::Registry registry;
    ecs::TransformSystem transforms{registry};
    JobSystem jobs{2};
    std::unique_ptr<lighting::LightingSystem> lighting;
    double time = 0.0;

    /// Adds an entity drawing mesh 0 of `scene` at `position`; returns it.
    ecs::Entity add_mesh(std::shared_ptr<const scene::Scene> scene,
                         const glm::vec3& position = glm::vec3(0.0f));
    ecs::Entity add_point_light(const glm::vec3& position, const glm::vec3& power);
    /// Instantiates the prepared level `name` (prepared_level) under `sky`, or the level's own.
    void load_level(const std::string& name, const std::optional<scene::SkySpec>& sky = {});
    /// Resolves transforms and creates the LightingSystem (once).
    void start(const lighting::LightingConfig& config = small_lighting_config());
    /// One frame: transforms, then LightingSystem::update(budget_ms, time += dt).
    void update(double budget_ms = 1e9, double dt = 1.0 / 60.0);
};

/// A prepared level from assets/levels/prepared/<name>.glb.
[[nodiscard]] std::filesystem::path prepared_level(const std::string& name);
/// Every prepared level's name.
[[nodiscard]] std::vector<std::string> prepared_levels();

/// The first camera of the registry's level (its world transform applied), or a default view
/// 4 m in front of the origin.
[[nodiscard]] renderer::FrameCamera level_camera(ecs::Registry& registry, float aspect);

/// Reads a texture's level 0 as RGBA floats, rows bottom first (GL order).
[[nodiscard]] std::vector<glm::vec4> read_texture(GLuint texture, int width, int height);

}  // namespace luxel::test
