#pragma once

// A level loaded for the reference: instantiated at an animation time, its geometry and
// lights mirrored by a PhotonWorld, its light-map texels by IlluminationMaps.

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "luxel/ecs/registry.hpp"
#include "luxel/lighting/core/illumination_maps.hpp"
#include "luxel/lighting/core/photon_world.hpp"
#include "luxel/lighting/reference/reference_frame.hpp"
#include "luxel/lighting/reference/reference_scene.hpp"
#include "luxel/prep/auto_prep.hpp"
#include "luxel/scene/gltf.hpp"
#include "luxel/world/scene_instance.hpp"

namespace luxel::ref {

/// A level name resolves to <prepared levels>/NAME.glb ($LUXEL_LEVEL_DIR first, then the
/// source tree's assets/levels/prepared, then ./assets/levels/prepared); anything with a
/// slash or a .glb/.gltf extension is a path. Throws luxel::Error naming what was tried.
[[nodiscard]] std::filesystem::path resolve_level(const std::string& level);

struct LoadedLevel {
    ecs::Registry registry;
    world::SceneInstance instance;
    std::unique_ptr<lighting::PhotonWorld> world;
    std::unique_ptr<lighting::IlluminationMaps> maps;
    std::unique_ptr<lighting::reference::ReferenceScene> scene;
};

/// Throws luxel::Error naming `file` and the reference-bytes limit when the reference's
/// per-texel state for `texels` texels (ReferenceIntegrator::bytes_per_texel() each) is more
/// than `limits` allows. load_level checks it once the maps are laid out, before the
/// reference scene allocates anything per texel.
void check_reference_memory(const std::filesystem::path& file, std::uint64_t texels,
                            const scene::LoadOptions& limits);

/// Loads `file` (prep::load_playable: its warnings, and prepared at load if luxel-prep never
/// did) and poses it at `time` seconds (animations and light switches advanced), under `sky`
/// instead of its own sky when set.
[[nodiscard]] std::unique_ptr<LoadedLevel> load_level(const std::filesystem::path& file,
                                                      double time,
                                                      const std::optional<scene::SkySpec>& sky,
                                                      const prep::PlayableLevel& playable,
                                                      JobSystem& jobs);

/// The level's first camera (node order) for a width x height image, if it has one.
[[nodiscard]] std::optional<lighting::reference::ReferenceCamera> level_camera(
    const LoadedLevel& level, int width, int height);
/// The camera of scene::DefaultView (what luxel-sandbox shows of a level without a camera) for a
/// width x height image.
[[nodiscard]] lighting::reference::ReferenceCamera default_camera(int width, int height);
/// The same for any posed instance of a level (luxel-bench renders the real-time frame and
/// the reference frame from this one camera).
[[nodiscard]] std::optional<lighting::reference::ReferenceCamera> level_camera(
    const ecs::Registry& registry, const world::SceneInstance& instance, int width, int height);

}  // namespace luxel::ref
