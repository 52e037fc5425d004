#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "luxel/scene/scene.hpp"

namespace luxel::levels {

/// Small conveniences for assembling a scene::Scene in code: every add_* returns the index of
/// what it added, so levels read as a list of things placed in the world.
class LevelBuilder {
  public:
    explicit LevelBuilder(std::string name);

    int add_diffuse(const std::string& name, glm::vec3 albedo);
    int add_material(scene::Material material);
    int add_mesh(const std::string& name, scene::Primitive primitive, int material);
    /// A node under `parent` (-1: a root) at the given placement.
    int add_node(const std::string& name, int parent = -1, glm::vec3 translation = glm::vec3(0.0f),
                 glm::quat rotation = glm::quat(1, 0, 0, 0), glm::vec3 scale = glm::vec3(1.0f));
    int add_mesh_node(const std::string& name, scene::Primitive primitive, int material,
                      int parent = -1, glm::vec3 translation = glm::vec3(0.0f));
    /// A light node; lights shine down their node's -z axis (glTF), so `rotation` aims spots.
    int add_light(scene::Light light, glm::vec3 position,
                  glm::quat rotation = glm::quat(1, 0, 0, 0), int parent = -1);
    /// A perspective camera at `eye` looking at `target` (+y up).
    int add_camera(const std::string& name, glm::vec3 eye, glm::vec3 target, float yfov_radians);

    /// A skin (glTF 3.7.3) over `joints` (node indices), bound where the joints stand now: each
    /// inverse bind matrix is the inverse of its joint's world matrix in the nodes' own TRS.
    int add_skin(const std::string& name, std::vector<int> joints);
    /// A root node drawing `primitive` (with joints and weights) deformed by skin `skin`; as
    /// glTF says, its own transform is ignored, so it has none.
    int add_skinned_mesh_node(const std::string& name, scene::Primitive primitive, int material,
                              int skin);

    /// Animates one property of a node through keyframes (times in seconds).
    void animate(const std::string& animation_name, int node, scene::AnimatedProperty property,
                 scene::Interpolation interpolation, std::vector<float> times,
                 std::vector<glm::vec4> values);

    [[nodiscard]] scene::Node& node(int index) {
        return scene_.nodes.at(static_cast<std::size_t>(index));
    }
    /// The level's sky (scene extras, docs/LEVELS.md "Sky"); none unless set.
    [[nodiscard]] scene::SkySpec& sky() { return scene_.sky; }
    [[nodiscard]] scene::Scene finish();

  private:
    scene::Scene scene_;
};

[[nodiscard]] inline glm::vec4 as_key(const glm::vec3& v) {
    return glm::vec4(v, 0.0f);
}
[[nodiscard]] inline glm::vec4 as_key(const glm::quat& q) {
    return {q.x, q.y, q.z, q.w};
}

}  // namespace luxel::levels
