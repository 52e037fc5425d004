#pragma once

// The prepared Cornell box with one thing taken away (its light, its camera, or luxel-prep's
// light-map layout): the levels a user brings from another tool that lack it, for the tests of
// what luxel says about them (scene/level_check.hpp) and what the lighting does with them.

#include <filesystem>
#include <string>

#include "luxel/scene/gltf.hpp"
#include "luxel/scene/scene.hpp"
#include "test_paths.hpp"

namespace luxel::testing {

[[nodiscard]] inline scene::Scene prepared_cornell() {
    return scene::load_gltf(luxel::testing::source_dir() / "assets" / "levels" / "prepared" /
                            "cornell.glb");
}

/// No punctual light, and no material emits.
[[nodiscard]] inline scene::Scene without_light(scene::Scene level) {
    for (scene::Node& node : level.nodes) {
        node.light = -1;
    }
    level.lights.clear();
    for (scene::Material& material : level.materials) {
        material.emissive = glm::vec3(0.0f);
    }
    return level;
}

[[nodiscard]] inline scene::Scene without_camera(scene::Scene level) {
    for (scene::Node& node : level.nodes) {
        node.camera = -1;
    }
    level.cameras.clear();
    return level;
}

/// As exported by another tool: no light-map layout, no TEXCOORD_1.
[[nodiscard]] inline scene::Scene unprepared(scene::Scene level) {
    for (scene::Node& node : level.nodes) {
        node.flags.raw.erase("lightmap");
    }
    for (scene::Mesh& mesh : level.meshes) {
        for (scene::Primitive& primitive : mesh.primitives) {
            primitive.texcoords1.clear();
        }
    }
    return level;
}

/// Saves `level` as `file` and loads it back, so that it names the file as a loaded level does.
[[nodiscard]] inline scene::Scene saved_as(const scene::Scene& level,
                                           const std::filesystem::path& file) {
    scene::save_gltf(level, file);
    return scene::load_gltf(file);
}

}  // namespace luxel::testing
