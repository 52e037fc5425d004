#include "level_builder.hpp"

#include <glm/gtc/matrix_transform.hpp>

namespace luxel::levels {

LevelBuilder::LevelBuilder(std::string name) {
    scene_.name = std::move(name);
}

int LevelBuilder::add_diffuse(const std::string& name, glm::vec3 albedo) {
    scene::Material material;
    material.name = name;
    material.base_color = glm::vec4(albedo, 1.0f);
    material.metallic = 0.0f;
    material.roughness = 1.0f;
    return add_material(material);
}

int LevelBuilder::add_material(scene::Material material) {
    scene_.materials.push_back(std::move(material));
    return static_cast<int>(scene_.materials.size()) - 1;
}

int LevelBuilder::add_mesh(const std::string& name, scene::Primitive primitive, int material) {
    primitive.material = material;
    scene::Mesh mesh;
    mesh.name = name;
    mesh.primitives.push_back(std::move(primitive));
    scene_.meshes.push_back(std::move(mesh));
    return static_cast<int>(scene_.meshes.size()) - 1;
}

int LevelBuilder::add_node(const std::string& name, int parent, glm::vec3 translation,
                           glm::quat rotation, glm::vec3 scale) {
    scene::Node node;
    node.name = name;
    node.parent = parent;
    node.translation = translation;
    node.rotation = rotation;
    node.scale = scale;
    scene_.nodes.push_back(std::move(node));
    const int index = static_cast<int>(scene_.nodes.size()) - 1;
    if (parent >= 0) {
        scene_.nodes.at(static_cast<std::size_t>(parent)).children.push_back(index);
    } else {
        scene_.roots.push_back(index);
    }
    return index;
}

int LevelBuilder::add_mesh_node(const std::string& name, scene::Primitive primitive, int material,
                                int parent, glm::vec3 translation) {
    const int mesh = add_mesh(name, std::move(primitive), material);
    const int index = add_node(name, parent, translation);
    node(index).mesh = mesh;
    return index;
}

int LevelBuilder::add_light(scene::Light light, glm::vec3 position, glm::quat rotation,
                            int parent) {
    const std::string name = light.name;
    scene_.lights.push_back(std::move(light));
    const int index = add_node(name, parent, position, rotation);
    node(index).light = static_cast<int>(scene_.lights.size()) - 1;
    return index;
}

int LevelBuilder::add_camera(const std::string& name, glm::vec3 eye, glm::vec3 target,
                             float yfov_radians) {
    scene::Camera camera;
    camera.name = name;
    camera.yfov = yfov_radians;
    camera.znear = 0.05f;
    camera.zfar = 100.0f;
    scene_.cameras.push_back(camera);
    // glTF cameras look down their node's -z: the node's rotation is the inverse view rotation.
    const glm::mat4 view = glm::lookAt(eye, target, glm::vec3(0.0f, 1.0f, 0.0f));
    const glm::quat rotation = glm::quat_cast(glm::inverse(glm::mat3(view)));
    const int index = add_node(name, -1, eye, glm::normalize(rotation));
    node(index).camera = static_cast<int>(scene_.cameras.size()) - 1;
    return index;
}

int LevelBuilder::add_skin(const std::string& name, std::vector<int> joints) {
    const std::vector<glm::mat4> world = scene_.world_matrices();
    scene::Skin skin;
    skin.name = name;
    for (const int joint : joints) {
        skin.inverse_bind_matrices.push_back(
            glm::inverse(world.at(static_cast<std::size_t>(joint))));
    }
    skin.joints = std::move(joints);
    scene_.skins.push_back(std::move(skin));
    return static_cast<int>(scene_.skins.size()) - 1;
}

int LevelBuilder::add_skinned_mesh_node(const std::string& name, scene::Primitive primitive,
                                        int material, int skin) {
    const int index = add_mesh_node(name, std::move(primitive), material);
    node(index).skin = skin;
    return index;
}

void LevelBuilder::animate(const std::string& animation_name, int node_index,
                           scene::AnimatedProperty property, scene::Interpolation interpolation,
                           std::vector<float> times, std::vector<glm::vec4> values) {
    scene::Animation* animation = nullptr;
    for (auto& existing : scene_.animations) {
        if (existing.name == animation_name) {
            animation = &existing;
        }
    }
    if (animation == nullptr) {
        scene_.animations.emplace_back();
        animation = &scene_.animations.back();
        animation->name = animation_name;
    }
    animation->samplers.push_back({std::move(times), std::move(values), interpolation});
    animation->channels.push_back(
        {node_index, property, static_cast<int>(animation->samplers.size()) - 1});
}

scene::Scene LevelBuilder::finish() {
    scene_.validate();
    return std::move(scene_);
}

}  // namespace luxel::levels
