#pragma once

// Small scenes for the illumination-map tests: a light-mapped plane fed with photons from a
// known irradiance field, and levels loaded through the ECS.

#include <cmath>
#include <filesystem>
#include <functional>
#include <memory>
#include <random>
#include <string>

#include <glm/glm.hpp>

#include "luxel/ecs/registry.hpp"
#include "luxel/ecs/transform.hpp"
#include "luxel/ecs/transform_system.hpp"
#include "luxel/lighting/components.hpp"
#include "luxel/lighting/core/illumination_maps.hpp"
#include "luxel/lighting/core/lighting_system.hpp"
#include "luxel/lighting/core/photon_world.hpp"
#include "luxel/runtime/jobs.hpp"
#include "luxel/scene/gltf.hpp"
#include "luxel/world/scene_instance.hpp"
#include "test_paths.hpp"

namespace luxel::testing {

/// A side x side metre plane at y = 0 (normal +y) cut into cells x cells squares, light-mapped
/// at texel_size metres per texel on a page_size page, its chart at texel (2, 2).
inline std::shared_ptr<const scene::Scene> lightmapped_plane(float side, int cells,
                                                             float texel_size, int page_size,
                                                             glm::vec3 albedo) {
    auto s = std::make_shared<scene::Scene>();
    scene::Material material;
    material.base_color = glm::vec4(albedo, 1.0f);
    s->materials.push_back(material);
    scene::Primitive p;
    p.material = 0;
    const float texels = side / texel_size;
    for (int j = 0; j <= cells; ++j) {
        for (int i = 0; i <= cells; ++i) {
            const float u = static_cast<float>(i) / static_cast<float>(cells);
            const float v = static_cast<float>(j) / static_cast<float>(cells);
            p.positions.emplace_back(u * side, 0.0f, v * side);
            p.normals.emplace_back(0.0f, 1.0f, 0.0f);
            p.texcoords1.emplace_back((2.0f + u * texels) / static_cast<float>(page_size),
                                      (2.0f + v * texels) / static_cast<float>(page_size));
        }
    }
    const auto row = static_cast<std::uint32_t>(cells + 1);
    for (std::uint32_t j = 0; j < static_cast<std::uint32_t>(cells); ++j) {
        for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(cells); ++i) {
            const std::uint32_t a = j * row + i;
            // Counter-clockwise seen from +y.
            p.indices.insert(p.indices.end(), {a, a + row, a + 1, a + 1, a + row, a + row + 1});
        }
    }
    s->meshes.push_back({"plane", {p}});
    return s;
}

/// A lighting configuration for closed-form checks: `groups` x `per_group` photons, 64 gather
/// rays, and units so large that one unlimited frame does all the map work there is.
inline lighting::LightingConfig closed_form_config(std::uint32_t groups, std::uint32_t per_group) {
    lighting::LightingConfig config;
    config.photons.selective.groups = groups;
    config.photons.selective.per_group = per_group;
    config.gather.rays_per_texel = 64;
    config.texels_per_gather_unit = 1u << 20;
    config.texels_per_aim_unit = 1u << 20;
    return config;
}

/// Frames of 1/30 s with an unlimited budget until the plan says converged (every group
/// probed: per_group frames at least); the frames it took, or max_frames + 1.
inline int converge(ecs::TransformSystem& transforms, lighting::LightingSystem& lighting,
                    double& time, int max_frames = 100) {
    for (int i = 1; i <= max_frames; ++i) {
        time += 1.0 / 30.0;
        transforms.update();
        lighting.update(1e9, time);
        if (lighting.plan().census().converged) {
            return i;
        }
    }
    return max_frames + 1;
}

/// A registry holding one light-mapped plane entity, a PhotonWorld without lights (the test
/// stores photons itself) and the maps over it.
/// The light-map layout of lightmapped_plane(side, ..., texel_size, page_size, ...): one
/// surface whose chart starts at page texel (2, 2).
inline scene::LightmapLayout plane_layout(float side, float texel_size, int page_size) {
    scene::LightmapLayout layout;
    layout.texel_size = texel_size;
    layout.page_size = page_size;
    scene::LightmapSurface surface;
    surface.id = 0;
    surface.primitive = 0;
    surface.page = 0;
    const int texels = static_cast<int>(std::lround(side / texel_size));
    surface.rect = {2, 2, texels, texels};
    surface.charts = {surface.rect};
    surface.area = static_cast<double>(side) * side;
    surface.texels = static_cast<std::int64_t>(texels) * texels;
    layout.surfaces.push_back(surface);
    return layout;
}

struct PlaneWorld {
    ecs::Registry registry;
    ecs::TransformSystem transforms{registry};
    std::unique_ptr<lighting::PhotonWorld> photons;
    std::unique_ptr<lighting::IlluminationMaps> maps;
    ecs::Entity plane;
    int texel_count = 0;

    PlaneWorld(float side, float texel_size, int page_size, glm::vec3 albedo,
               lighting::IlluminationSettings settings = {},
               glm::mat4 transform = glm::mat4(1.0f)) {
        plane = registry.create();
        registry.emplace<scene::MeshInstance>(
            plane, lightmapped_plane(side, 8, texel_size, page_size, albedo), 0);
        registry.emplace<lighting::LightmappedSurface>(plane,
                                                       plane_layout(side, texel_size, page_size));
        ecs::Transform t;
        t.translation = glm::vec3(transform[3]);
        registry.emplace<ecs::Transform>(plane, t);
        transforms.update();
        photons = std::make_unique<lighting::PhotonWorld>(registry);
        photons->sync();
        maps = std::make_unique<lighting::IlluminationMaps>(registry, *photons, settings);
        maps->sync();
    }

    /// Stores photons at `positions` with `powers` on surface 0, as one group's direct hits.
    void store(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& powers) {
        lighting::PhotonMap& map = photons->photon_map();
        const std::uint32_t group = map.add_groups(1);
        lighting::TracedGroup traced;
        traced.starts.push_back(0);
        for (std::size_t i = 0; i < positions.size(); ++i) {
            traced.hops.push_back({positions[i], powers[i], 0, lighting::kNoObject, 0});
            traced.starts.push_back(static_cast<std::uint32_t>(traced.hops.size()));
        }
        map.replace_group(group, traced);
    }
};

/// A prepared level (assets/levels/prepared/<name>.glb) instantiated at rest, its photons
/// traced once: what the level-wide map tests build their maps on.
struct TracedLevel {
    ecs::Registry registry;
    ecs::TransformSystem transforms{registry};
    JobSystem jobs{2};
    std::unique_ptr<lighting::PhotonWorld> photons;

    explicit TracedLevel(const std::string& name) {
        const std::filesystem::path file =
            luxel::testing::source_dir() / "assets" / "levels" / "prepared" / (name + ".glb");
        world::InstantiateOptions options;
        options.play_animations = false;
        world::instantiate(registry, std::make_shared<scene::Scene>(scene::load_gltf(file)),
                           options);
        transforms.update();
        photons = std::make_unique<lighting::PhotonWorld>(registry);
        photons->sync();
        photons->probe(0, jobs);
        photons->retrace_pending(jobs);
    }
};

}  // namespace luxel::testing
