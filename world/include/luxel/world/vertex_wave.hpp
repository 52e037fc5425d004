#pragma once

#include <memory>
#include <optional>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "luxel/ecs/registry.hpp"
#include "luxel/scene/scene.hpp"

namespace luxel::world {

/// A travelling sine wave over a mesh, from a node's `extras.luxel.wave` (docs/LEVELS.md): each
/// vertex p moves along its normal by
///     h(p, t) = amplitude * sin(2 pi (d . (p.x, p.z) - speed * t) / wavelength)
/// with d the unit direction, p in the node's own space, t in seconds: the water of the source's
/// wave-plane scene (S. Larsen 2006, caustics from moving water). Metres and seconds.
struct WaveParameters {
    float amplitude = 0.02f;          ///< m; the loader refuses one larger than the wavelength
    float wavelength = 0.5f;          ///< m, > 0
    float speed = 0.4f;               ///< m/s along `direction`; 0 stands still
    glm::vec2 direction{1.0f, 0.0f};  ///< (x, z), unit length
};

/// The wave a node's extras.luxel ask for (keys left out take WaveParameters' defaults), or
/// nullopt when they have no `wave`. The loader has checked the types and ranges; a value
/// that slipped past (a zero direction) falls back to the default rather than to NaN.
[[nodiscard]] std::optional<WaveParameters> read_wave(const nlohmann::json& luxel_extras);

/// `rest` with every vertex moved along its normal by the wave at `time` seconds, and normals
/// tilted by the wave's slope (exact for a flat surface, the tangent-plane approximation on a
/// curved one). A primitive without normals moves along +y and gains normals.
[[nodiscard]] scene::Mesh waved_mesh(const scene::Mesh& rest, const WaveParameters& wave,
                                     double time);

/// The component: `mesh` of `source` in the node's rest shape, waved by `wave`. `time` runs
/// with update_waves and wraps at the wave's period, so precision does not decay.
struct VertexWave {
    std::shared_ptr<const scene::Scene> source;
    int mesh = -1;
    WaveParameters wave;
    double time = 0.0;
    bool playing = true;
    /// The time the entity's MeshInstance was last shaped at; a step that lands on the same
    /// time shapes nothing.
    std::optional<double> shaped_at;
};

/// Advances every playing VertexWave by dt seconds and gives its entity the waved shape
/// (set_mesh_shape: the ray scene refits, the renderer uploads). dt = 0 shapes a wave that
/// has not been shaped yet, so the first frame shows time 0. Run it with the other game
/// systems, before the lighting and the renderer read the frame. Returns how many meshes it
/// shaped.
std::size_t update_waves(ecs::Registry& registry, double dt_seconds);

}  // namespace luxel::world
