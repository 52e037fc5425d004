#pragma once

// Scenes for the gather tests and benchmark: a closed box of 12 triangles and a prepared
// level (cornell*.glb) mirrored into a RayScene by PhotonWorld, each with a RadianceAtlas.

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/ecs/registry.hpp"
#include "luxel/ecs/transform_system.hpp"
#include "luxel/lighting/core/gather.hpp"
#include "luxel/lighting/core/photon_world.hpp"
#include "luxel/lighting/core/radiance_atlas.hpp"
#include "luxel/lighting/core/ray_scene.hpp"
#include "luxel/runtime/gl_context.hpp"
#include "luxel/world/scene_instance.hpp"

namespace luxel::test {

/// A headless GL 4.5 context (EGL: llvmpipe on the surfaceless platform without a GPU).
[[nodiscard]] std::unique_ptr<GlContext> make_gl_context();

/// The 12 triangles of the box [lo, hi], two per face, winding towards the inside when
/// `inward` (outside otherwise). Face f (-x, +x, -y, +y, -z, +z) is surface first_surface + f;
/// light-map UVs span each face's page corner to corner.
[[nodiscard]] lighting::TriangleMesh box_mesh(const glm::vec3& lo, const glm::vec3& hi, bool inward,
                                              std::int32_t first_surface = 0);

/// `surfaces` surfaces, each on its own page of `page_size`^2 texels holding `radiance`.
[[nodiscard]] lighting::RadianceAtlas constant_atlas(std::size_t surfaces,
                                                     const glm::vec3& radiance, int page_size = 4);

/// A smooth, everywhere positive radiance of a page texel (x, y), different per channel.
[[nodiscard]] glm::vec3 synthetic_radiance(int x, int y);

/// A level from assets/levels/<name>.glb, instantiated (animations stopped), its transforms
/// resolved and mirrored into a PhotonWorld's RayScene; the atlas has one page per light-map
/// page of the level, filled with synthetic_radiance, and every surface luxel-prep laid out
/// points at its page (other surfaces have none).
struct GatherLevel {
    ecs::Registry registry;
    world::SceneInstance instance;
    ecs::TransformSystem transforms{registry};
    std::unique_ptr<lighting::PhotonWorld> world;
    lighting::RadianceAtlas atlas;

    explicit GatherLevel(const std::string& name);
    [[nodiscard]] const lighting::RayScene& scene() const { return world->ray_scene(); }
    /// `count` texel centres on front faces seen from the middle of the level's bounds: rays
    /// in Fibonacci-sphere directions, each hit moved `lift` off the surface along its
    /// geometric normal, which becomes the texel normal.
    [[nodiscard]] std::vector<lighting::GatherTexel> texels(std::size_t count,
                                                            float lift = 2e-3f) const;
};

[[nodiscard]] std::filesystem::path level_path(const std::string& name);

}  // namespace luxel::test
