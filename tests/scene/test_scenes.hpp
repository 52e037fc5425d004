#pragma once

// Small scenes built in code that between them use every feature the glTF loader and writer
// handle. The round-trip, mutation and fuzzing tests start from them.

#include <cstdint>
#include <string>
#include <vector>

#include "luxel/scene/scene.hpp"

namespace luxel::testing {

/// A 2x2 PNG (encoded bytes), for textures.
[[nodiscard]] std::vector<std::uint8_t> tiny_png();

/// A box room with a textured cube, a glass sphere, a mirror, an emissive panel, a door on a
/// dynamic pivot, point/spot/directional lights (one switched off), three cameras, and two
/// animations using LINEAR, STEP and CUBICSPLINE on translation, rotation and scale.
[[nodiscard]] scene::Scene box_room();

/// One triangle, no material, no scene name: everything left at its default.
[[nodiscard]] scene::Scene single_triangle();

/// A grid of `cells` x `cells` quads (more than 65535 vertices once cells >= 256, which makes
/// the writer use 32-bit indices), with both texture coordinate sets.
[[nodiscard]] scene::Scene grid(int cells);

/// The scenes the mutation test and the fuzzing seeds start from, with a name each.
struct NamedScene {
    std::string name;
    scene::Scene scene;
};
[[nodiscard]] std::vector<NamedScene> mutation_seed_scenes();

}  // namespace luxel::testing
