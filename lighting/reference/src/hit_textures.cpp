#include "luxel/lighting/reference/hit_textures.hpp"

#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>

#include "luxel/runtime/error.hpp"
#include "luxel/runtime/log.hpp"
#include "luxel/scene/components.hpp"
#include "luxel/scene/image_decode.hpp"

namespace luxel::lighting::reference {

std::shared_ptr<const HitTextures> HitTextures::from_world(const PhotonWorld& world) {
    auto result = std::make_shared<HitTextures>();
    // (scene, material) -> texture slot; (scene, image) -> decoded image (or null: failed).
    std::map<std::pair<const scene::Scene*, int>, std::int32_t> material_slots;
    std::map<std::pair<const scene::Scene*, int>, const scene::LinearImage*> decoded;
    const auto texture_of = [&](const scene::Scene& source, int material) -> std::int32_t {
        const auto key = std::make_pair(&source, material);
        if (const auto found = material_slots.find(key); found != material_slots.end()) {
            return found->second;
        }
        std::int32_t slot = -1;
        if (material >= 0 && static_cast<std::size_t>(material) < source.materials.size()) {
            const scene::Material& m = source.materials[static_cast<std::size_t>(material)];
            const int image = m.base_color_image;
            if (image >= 0 && static_cast<std::size_t>(image) < source.images.size()) {
                const auto image_key = std::make_pair(&source, image);
                auto found = decoded.find(image_key);
                if (found == decoded.end()) {
                    const scene::LinearImage* linear = nullptr;
                    try {
                        result->images_.push_back(
                            std::make_unique<scene::LinearImage>(scene::decode_image(
                                source.images[static_cast<std::size_t>(image)], image)));
                        linear = result->images_.back().get();
                    } catch (const Error& error) {
                        log::warn("luxel-ref: ", error.what(),
                                  "; its material keeps the texture's mean colour in the "
                                  "reference's paths");
                    }
                    found = decoded.emplace(image_key, linear).first;
                }
                if (found->second != nullptr) {
                    slot = static_cast<std::int32_t>(result->textures_.size());
                    result->textures_.push_back(
                        {found->second,
                         glm::clamp(glm::vec3(m.base_color), glm::vec3(0.0f), glm::vec3(1.0f))});
                }
            }
        }
        material_slots.emplace(key, slot);
        return slot;
    };

    const ecs::Registry& registry = world.registry();
    for (const auto& [entity, object] : world.mesh_objects()) {
        const auto* instance = registry.try_get<scene::MeshInstance>(entity);
        if (instance == nullptr || instance->source == nullptr) {
            continue;
        }
        const scene::Mesh& mesh = instance->geometry();
        Object textured;
        bool any = false;
        for (const scene::Primitive& primitive : mesh.primitives) {
            const std::int32_t slot = texture_of(*instance->source, primitive.material);
            any = any || slot >= 0;
            // The ray scene's vertices are the primitives' concatenated (PhotonGeometry).
            if (primitive.texcoords0.size() == primitive.positions.size()) {
                textured.texcoords.insert(textured.texcoords.end(), primitive.texcoords0.begin(),
                                          primitive.texcoords0.end());
            } else {
                textured.texcoords.resize(textured.texcoords.size() + primitive.positions.size(),
                                          glm::vec2(0.0f));
            }
            textured.textures.insert(textured.textures.end(), primitive.triangle_count(), slot);
        }
        if (!any) {
            continue;
        }
        textured.mesh = &world.ray_scene().mesh(object);
        if (textured.mesh->positions.size() != textured.texcoords.size() ||
            textured.mesh->triangle_count() != textured.textures.size()) {
            continue;  // not the layout PhotonGeometry mirrored: leave it to the mean
        }
        result->objects_.emplace(object, std::move(textured));
    }
    if (result->objects_.empty()) {
        return nullptr;
    }
    return result;
}

std::optional<glm::vec3> HitTextures::albedo(const RayHit& hit) const {
    const auto found = objects_.find(hit.object);
    if (found == objects_.end()) {
        return std::nullopt;
    }
    const Object& object = found->second;
    if (hit.triangle >= object.textures.size()) {
        return std::nullopt;
    }
    const std::int32_t slot = object.textures[hit.triangle];
    if (slot < 0) {
        return std::nullopt;
    }
    const auto& indices = object.mesh->indices;
    const std::uint32_t i0 = indices[3 * static_cast<std::size_t>(hit.triangle)];
    const std::uint32_t i1 = indices[3 * static_cast<std::size_t>(hit.triangle) + 1];
    const std::uint32_t i2 = indices[3 * static_cast<std::size_t>(hit.triangle) + 2];
    const float u = hit.barycentric.x;
    const float v = hit.barycentric.y;
    const glm::vec2 uv =
        (1.0f - u - v) * object.texcoords[i0] + u * object.texcoords[i1] + v * object.texcoords[i2];
    const Texture& texture = textures_[static_cast<std::size_t>(slot)];
    return texture.factor * texture.image->bilinear(uv);
}

}  // namespace luxel::lighting::reference
