#pragma once

#include <functional>
#include <string>
#include <vector>

#include "luxel/scene/scene.hpp"

namespace luxel::levels {

/// One built-in level: its file stem under assets/levels/ and the code that builds it.
struct LevelRecipe {
    std::string name;
    std::string description;
    std::function<scene::Scene()> build;
};

/// Every built-in level, in the order they are written. Deterministic: the same code always
/// produces the same scene, so the committed .glb files can be checked against a rebuild.
[[nodiscard]] std::vector<LevelRecipe> built_in_levels();

/// The Cornell box with its bumpy floor split into floor_cells x floor_cells cells.
[[nodiscard]] scene::Scene make_cornell(const std::string& name, int floor_cells);
[[nodiscard]] scene::Scene make_two_rooms();
[[nodiscard]] scene::Scene make_caustics();
/// The sandbox game level (issue 10): two rooms joined by a corridor, a swinging door, a turning
/// glass sculpture, a bouncing ball (moved by a game system from extras.luxel.bounce), a
/// swinging lamp, a switched light, and a skinned figure walking through both rooms.
[[nodiscard]] scene::Scene make_sandbox();
/// A closed room lit only through one window (a portal in it) by a uniform sky and a low sun
/// (issue 20's built-in sky room).
[[nodiscard]] scene::Scene make_sky_room();
/// A closed sphere seen from inside, uniform albedo and emission (stability checks: the exact
/// radiance inside is L = Le / (1 - albedo)).
[[nodiscard]] scene::Scene make_furnace(float albedo = 0.5f, float emitted_radiance = 1.0f);

}  // namespace luxel::levels
