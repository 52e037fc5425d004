#pragma once

// Helpers for the luxel-prep suites: small scenes built in code, one call to prepare, and an
// independent check of a prepared file's light-map pages (rasterized here with polygon
// clipping, not with luxel-prep's own rasterizer).

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "luxel/prep/prep.hpp"
#include "luxel/scene/scene.hpp"

namespace luxel::testing {

/// The repository's built-in levels (assets/levels/<name>.glb, written by luxel-make-levels).
[[nodiscard]] std::vector<std::string> built_in_level_names();
/// The levels made by Blender (tests/levels/blender/<name>.glb, from <name>.py beside it). Both
/// kinds are prepared into assets/levels/prepared/ by scripts/prepare-levels.sh.
[[nodiscard]] std::vector<std::string> blender_level_names();
[[nodiscard]] std::filesystem::path level_file(const std::string& name);
[[nodiscard]] std::filesystem::path prepared_level_file(const std::string& name);

/// A diffuse white material.
[[nodiscard]] scene::Material diffuse_material(const std::string& name = "diffuse");

/// A scene with one node holding `primitive` with a diffuse material.
[[nodiscard]] scene::Scene single_mesh_scene(scene::Primitive primitive,
                                             const std::string& name = "mesh");

/// Appends a mesh of one primitive (its material kept) and a root node drawing it at
/// `translation`; returns the node's index.
int add_mesh_node(scene::Scene& scene, const std::string& name, scene::Primitive primitive,
                  const glm::vec3& translation);

/// prepare() on a fresh job system of `threads` threads.
[[nodiscard]] prep::PrepResult run_prep(const scene::Scene& scene,
                                        const prep::PrepOptions& options = {}, int threads = 2);

/// What check_light_map_pages found, for messages and further assertions.
struct PageCheck {
    std::size_t surfaces = 0;
    std::size_t charts = 0;
    std::size_t triangles = 0;
    std::int64_t texels = 0;
    std::int64_t page_texels = 0;
    double stretch_min = 1e300;
    double stretch_max = 0.0;
    std::vector<std::string> failures;  ///< the first few problems found
};

/// Checks a prepared scene as the runtime sees it: every surface primitive has TEXCOORD_1 and
/// its triangles lie in exactly one of its charts' rectangles; each chart's texels (luxel-prep's
/// conservative rule, from the stored float UVs) cover every texel its triangles overlap by
/// independent clipping; the texel counts match the table; the charts, grown by their padding,
/// stay inside their page and never claim a texel twice; and every triangle's area stretch is
/// within 1/max_stretch..max_stretch.
[[nodiscard]] PageCheck check_light_map_pages(const scene::Scene& prepared, int padding,
                                              double max_stretch = 1.5);

}  // namespace luxel::testing
