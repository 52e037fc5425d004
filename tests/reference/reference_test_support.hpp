#pragma once

// Loading a prepared level into a ReferenceScene, as luxel-ref does.

#include <filesystem>
#include <memory>
#include <string>

#include "luxel/ecs/transform_system.hpp"
#include "luxel/lighting/core/illumination_maps.hpp"
#include "luxel/lighting/core/photon_world.hpp"
#include "luxel/lighting/reference/reference_scene.hpp"
#include "luxel/scene/gltf.hpp"
#include "luxel/world/scene_instance.hpp"
#include "test_paths.hpp"

namespace luxel::testing {

inline std::filesystem::path prepared_level(const std::string& name) {
    return luxel::testing::source_dir() / "assets" / "levels" / "prepared" / (name + ".glb");
}

/// A level instantiated (no animation), its PhotonWorld and IlluminationMaps synced, and the
/// reference's view of it.
struct ReferenceLevel {
    ecs::Registry registry;
    world::SceneInstance instance;
    std::unique_ptr<lighting::PhotonWorld> world;
    std::unique_ptr<lighting::IlluminationMaps> maps;
    std::unique_ptr<lighting::reference::ReferenceScene> scene;

    explicit ReferenceLevel(const std::string& name) {
        auto source = std::make_shared<scene::Scene>(scene::load_gltf(prepared_level(name)));
        world::InstantiateOptions options;
        options.play_animations = false;
        instance = world::instantiate(registry, source, options);
        ecs::TransformSystem transforms(registry);
        transforms.update();
        lighting::PhotonWorldSettings settings;
        settings.caustics.photons_per_pair = 0;  // the reference traces its own
        world = std::make_unique<lighting::PhotonWorld>(registry, settings);
        world->sync();
        maps = std::make_unique<lighting::IlluminationMaps>(registry, *world);
        maps->sync();
        scene = std::make_unique<lighting::reference::ReferenceScene>(
            lighting::reference::ReferenceScene::from_world(*world, *maps));
    }
};

}  // namespace luxel::testing
