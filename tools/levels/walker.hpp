#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "level_builder.hpp"

namespace luxel::levels {

/// Where a walker stands at `time` seconds: (x, z) on the floor (y = 0). Between two keys at
/// different places it walks in a straight line, facing where it goes; between two keys at the
/// same place it stands (and turns to face its next leg).
struct WalkKey {
    float time = 0.0f;
    glm::vec2 position{0.0f};
};

/// Adds a walking figure, the kind of character every game level has (issue 29): a blocky
/// person 1.72 m tall made of one mesh skinned to five joints (the figure's root on the floor,
/// two hips, two shoulders), and one looping animation "<name> walk" that carries it along
/// `path` (the last key's time is the loop's length, its place the first key's) with legs and
/// arms swinging at a stride a second while it walks. Every vertex follows one joint with
/// weight 1, as low-poly characters are rigged. Returns the skinned mesh node.
int add_walker(LevelBuilder& level, const std::string& name, int material,
               const std::vector<WalkKey>& path);

}  // namespace luxel::levels
