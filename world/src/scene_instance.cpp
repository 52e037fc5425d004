#include "luxel/world/scene_instance.hpp"

#include <optional>
#include <string>

#include "luxel/ecs/hierarchy.hpp"
#include "luxel/ecs/transform.hpp"
#include "luxel/lighting/components.hpp"
#include "luxel/lighting/sky_portal.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/scene/lightmap_layout.hpp"
#include "luxel/scene/portal.hpp"
#include "luxel/scene/skin.hpp"
#include "luxel/world/animation_system.hpp"
#include "luxel/world/skinning.hpp"
#include "luxel/world/sky.hpp"
#include "luxel/world/vertex_wave.hpp"

namespace luxel::world {
namespace {

void add_light(ecs::Registry& registry, ecs::Entity entity, const scene::Light& light,
               const scene::NodeFlags& flags) {
    const bool enabled = flags.light_enabled;
    switch (light.type) {
        case scene::LightType::Point:
            registry.emplace<lighting::PointLight>(entity, light.radiant_power(), light.range,
                                                   enabled, flags.light_radius);
            break;
        case scene::LightType::Spot:
            registry.emplace<lighting::SpotLight>(entity, light.radiant_power(),
                                                  light.inner_cone_angle, light.outer_cone_angle,
                                                  light.range, enabled, flags.light_radius);
            break;
        case scene::LightType::Directional:
            registry.emplace<lighting::DirectionalLight>(entity, light.irradiance(), enabled);
            break;
    }
}

/// extras.luxel.switch = {"period": P, "on": T, "phase": S}; absent or malformed fields keep
/// LightSwitch's defaults, and a non-positive period disables switching.
void add_switch_if_any(ecs::Registry& registry, ecs::Entity entity, const nlohmann::json& raw) {
    const auto found = raw.find("switch");
    if (found == raw.end() || !found->is_object()) {
        return;
    }
    LightSwitch light_switch;
    auto number = [&](const char* key, double fallback) {
        const auto value = found->find(key);
        return value != found->end() && value->is_number() ? value->get<double>() : fallback;
    };
    light_switch.period = number("period", light_switch.period);
    light_switch.on = number("on", light_switch.on);
    light_switch.phase = number("phase", light_switch.phase);
    if (light_switch.period > 0.0) {
        registry.emplace<LightSwitch>(entity, light_switch);
    }
}

/// A portal's triangles, in its node's space: every triangle of every primitive of its mesh.
void add_portal(ecs::Registry& registry, ecs::Entity entity, const scene::Scene& source,
                const scene::Node& node) {
    lighting::SkyPortal portal;
    for (const auto& primitive : source.meshes.at(static_cast<std::size_t>(node.mesh)).primitives) {
        // The loader checked every index against the positions.
        for (std::size_t i = 0; i < primitive.triangle_count() * 3; ++i) {
            portal.triangles.push_back(primitive.positions[primitive.indices[i]]);
        }
    }
    registry.emplace<lighting::SkyPortal>(entity, std::move(portal));
}

/// Whether any primitive of `mesh` has an emissive material.
bool is_emissive(const scene::Scene& source, const scene::Mesh& mesh) {
    for (const auto& primitive : mesh.primitives) {
        if (primitive.material >= 0 &&
            source.materials.at(static_cast<std::size_t>(primitive.material)).is_emissive()) {
            return true;
        }
    }
    return false;
}

void add_mesh(ecs::Registry& registry, ecs::Entity entity,
              const std::shared_ptr<const scene::Scene>& source, const scene::Node& node) {
    const scene::Mesh& mesh = source->meshes.at(static_cast<std::size_t>(node.mesh));
    if (const std::optional<WaveParameters> wave = read_wave(node.flags.raw)) {
        // Shaped at time 0 from the start, so the first frame and the warm-up see the wave's
        // starting shape, and the ray scene makes it an object whose later shapes refit in place.
        registry.emplace<scene::MeshInstance>(
            entity, source, node.mesh,
            std::make_shared<const scene::Mesh>(waved_mesh(mesh, *wave, 0.0)));
        registry.emplace<VertexWave>(entity, VertexWave{source, node.mesh, *wave, 0.0, true, 0.0});
    } else {
        registry.emplace<scene::MeshInstance>(entity, source, node.mesh);
    }
    const scene::Material* specular = nullptr;
    for (const auto& primitive : mesh.primitives) {
        if (primitive.material < 0) {
            continue;
        }
        const scene::Material& material =
            source->materials.at(static_cast<std::size_t>(primitive.material));
        if (specular == nullptr && material.is_specular()) {
            specular = &material;
        }
    }
    if (is_emissive(*source, mesh)) {
        registry.emplace<lighting::AreaLight>(entity);
    }
    if (specular != nullptr) {
        registry.emplace<lighting::CausticGenerator>(entity, specular->ior, specular->transmission,
                                                     glm::vec3(specular->base_color));
    }
    // luxel-prep's layout says which primitive is which surface; without it the UVs are not a
    // light-map parameterisation we can trust.
    std::optional<scene::LightmapLayout> layout;
    try {
        layout = scene::read_lightmap_layout(node.flags.raw);
    } catch (const Error& e) {
        throw Error(source->in_file("node '" + node.name + "': " + e.what()));
    }
    if (!layout) {
        return;
    }
    for (const auto& surface : layout->surfaces) {
        if (static_cast<std::size_t>(surface.primitive) >= mesh.primitives.size() ||
            mesh.primitives[static_cast<std::size_t>(surface.primitive)].texcoords1.empty()) {
            throw Error(source->in_file("node '" + node.name + "': light-map surface " +
                                        std::to_string(surface.id) + " names primitive " +
                                        std::to_string(surface.primitive) +
                                        ", which has no TEXCOORD_1"));
        }
    }
    registry.emplace<lighting::LightmappedSurface>(entity, std::move(*layout));
}

/// The entity that draws node `index`'s skinned mesh, posed as the scene's nodes stand.
ecs::Entity add_skinned_mesh(ecs::Registry& registry,
                             const std::shared_ptr<const scene::Scene>& source, std::size_t index,
                             const std::vector<ecs::Entity>& nodes,
                             const std::vector<glm::mat4>& rest_world) {
    const scene::Node& node = source->nodes[index];
    const scene::Skin& skin = source->skins.at(static_cast<std::size_t>(node.skin));
    const ecs::Entity entity = registry.create();
    registry.emplace<ecs::Transform>(entity);
    registry.emplace<scene::Name>(entity, node.name);
    registry.emplace<scene::SceneNode>(entity, static_cast<int>(index));
    registry.emplace<scene::Dynamic>(entity);
    SkinnedMesh skinned;
    skinned.source = source;
    skinned.skin = node.skin;
    skinned.mesh = node.mesh;
    for (const int joint : skin.joints) {
        skinned.joints.push_back(nodes.at(static_cast<std::size_t>(joint)));
    }
    skinned.posed_with = scene::joint_matrices(skin, rest_world);
    const scene::Mesh& bind = source->meshes.at(static_cast<std::size_t>(node.mesh));
    registry.emplace<scene::MeshInstance>(
        entity, source, node.mesh,
        std::make_shared<const scene::Mesh>(scene::posed_mesh(bind, skinned.posed_with)),
        std::make_shared<const std::vector<glm::mat4>>(skinned.posed_with));
    registry.emplace<SkinnedMesh>(entity, std::move(skinned));
    if (is_emissive(*source, bind)) {
        registry.emplace<lighting::AreaLight>(entity);
    }
    return entity;
}

}  // namespace

ecs::Entity SceneInstance::find(const std::string& node_name) const {
    if (source) {
        for (std::size_t i = 0; i < source->nodes.size() && i < nodes.size(); ++i) {
            if (source->nodes[i].name == node_name) {
                return nodes[i];
            }
        }
    }
    return ecs::null_entity;
}

SceneInstance instantiate(ecs::Registry& registry, std::shared_ptr<const scene::Scene> scene,
                          const InstantiateOptions& options) {
    SceneInstance instance;
    instance.source = scene;
    instance.nodes.reserve(scene->nodes.size());
    for (std::size_t i = 0; i < scene->nodes.size(); ++i) {
        const scene::Node& node = scene->nodes[i];
        const ecs::Entity entity = registry.create();
        instance.nodes.push_back(entity);
        registry.emplace<ecs::Transform>(entity, node.translation, node.rotation, node.scale);
        registry.emplace<scene::Name>(entity, node.name);
        registry.emplace<scene::SceneNode>(entity, static_cast<int>(i));
        if (node.mesh >= 0 && scene::is_portal(node)) {
            add_portal(registry, entity, *scene, node);
        } else if (node.mesh >= 0 && node.skin < 0) {  // skinned meshes: below
            add_mesh(registry, entity, scene, node);
        }
        if (node.light >= 0) {
            add_light(registry, entity, scene->lights.at(static_cast<std::size_t>(node.light)),
                      node.flags);
            add_switch_if_any(registry, entity, node.flags.raw);
        }
        if (node.camera >= 0) {
            registry.emplace<scene::CameraComponent>(
                entity, scene->cameras.at(static_cast<std::size_t>(node.camera)));
        }
        if (scene->is_dynamic(static_cast<int>(i))) {
            registry.emplace<scene::Dynamic>(entity);
        }
    }
    // Links after every entity exists: a node may name a parent that comes later in the list.
    for (std::size_t i = 0; i < scene->nodes.size(); ++i) {
        const int parent = scene->nodes[i].parent;
        if (parent >= 0) {
            ecs::set_parent(registry, instance.nodes[i],
                            instance.nodes.at(static_cast<std::size_t>(parent)));
        }
    }
    // Skinned meshes after every node's entity exists: their joints may be any nodes. (A
    // portal with a skin stays a portal: its opening does not deform.)
    const std::vector<glm::mat4> rest_world =
        scene->skins.empty() ? std::vector<glm::mat4>{} : scene->world_matrices();
    for (std::size_t i = 0; i < scene->nodes.size(); ++i) {
        const scene::Node& node = scene->nodes[i];
        if (node.mesh >= 0 && node.skin >= 0 && !scene::is_portal(node)) {
            instance.skinned.push_back(
                add_skinned_mesh(registry, scene, i, instance.nodes, rest_world));
        }
    }
    for (std::size_t a = 0; a < scene->animations.size(); ++a) {
        const scene::Animation& animation = scene->animations[a];
        AnimationPlayer player;
        player.source = scene;
        player.animation = static_cast<int>(a);
        player.playing = options.play_animations;
        for (const auto& channel : animation.channels) {
            player.targets.push_back(channel.node >= 0 && static_cast<std::size_t>(channel.node) <
                                                              instance.nodes.size()
                                         ? instance.nodes[static_cast<std::size_t>(channel.node)]
                                         : ecs::null_entity);
        }
        const ecs::Entity entity = registry.create();
        registry.emplace<scene::Name>(entity, "animation: " + animation.name);
        registry.emplace<AnimationPlayer>(entity, std::move(player));
        instance.animations.push_back(entity);
    }
    const int sun = sun_node(*scene);
    instance.sky =
        add_sky(registry, *scene, options.sky.value_or(scene->sky),
                sun >= 0 ? instance.nodes[static_cast<std::size_t>(sun)] : ecs::null_entity);
    return instance;
}

}  // namespace luxel::world
