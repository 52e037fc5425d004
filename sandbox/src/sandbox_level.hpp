#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/ecs/registry.hpp"
#include "luxel/scene/scene.hpp"
#include "luxel/world/scene_instance.hpp"

/// The game side of the sandbox: which level to load, the game systems that move things the
/// way a game would (besides glTF animations), and the scripted camera of headless runs.
namespace luxel::sandbox {

/// The built-in levels a user may name (assets/levels/prepared/<name>.glb).
[[nodiscard]] const std::vector<std::string>& level_names();

/// A level name resolves to its prepared file under the asset directory (the current
/// directory's assets/ first, then the source tree's); anything else is taken as a path.
/// Throws luxel::Error naming the level and the places looked in when nothing is found.
[[nodiscard]] std::filesystem::path resolve_level(const std::string& name_or_path);

/// Moves a node up from its rest position by height * |sin(pi t / period)|: a ball bouncing on
/// the floor. Levels ask for it with extras.luxel.bounce (docs/LEVELS.md).
struct Bounce {
    glm::vec3 rest{0.0f};
    float height = 1.0f;
    float period = 1.0f;
};

/// Finds the nodes of `instance` that carry extras.luxel.bounce and gives their entities a
/// Bounce; returns how many.
std::size_t add_bounces(ecs::Registry& registry, const world::SceneInstance& instance,
                        const scene::Scene& scene);
/// The bounce system: sets each Bounce entity's Transform for game time `seconds`.
void update_bounces(ecs::Registry& registry, double seconds);

/// Where the camera is and what it looks at.
struct CameraPose {
    glm::vec3 eye{0.0f};
    glm::vec3 target{0.0f, 0.0f, -1.0f};
    float vertical_fov = 1.0f;  ///< radians
};

/// A looping camera path through keyframes, linearly interpolated (eye and target).
class CameraPath {
  public:
    struct Key {
        double time = 0.0;
        glm::vec3 eye{0.0f};
        glm::vec3 target{0.0f};
    };
    CameraPath(std::vector<Key> keys, float vertical_fov);
    [[nodiscard]] CameraPose at(double seconds) const;
    [[nodiscard]] double duration() const { return keys_.back().time; }

  private:
    std::vector<Key> keys_;
    float vertical_fov_;
};

/// The scripted camera of a level: a walk through the sandbox level's rooms; for other levels
/// a slow sway around the level's own camera (or a default view when it has none).
[[nodiscard]] CameraPath camera_path_for(const std::string& level_name, const scene::Scene& scene);

}  // namespace luxel::sandbox
