#include "luxel/world/mesh_shape.hpp"

#include <cmath>
#include <string>

#include "luxel/runtime/error.hpp"
#include "luxel/scene/components.hpp"

namespace luxel::world {
namespace {

std::string name_of(const ecs::Registry& registry, ecs::Entity entity) {
    const auto* name = registry.try_get<scene::Name>(entity);
    return name != nullptr && !name->value.empty() ? "'" + name->value + "'"
                                                   : "entity " + std::to_string(entity.index());
}

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// Why `shape` cannot stand for `mesh`, or an empty string.
std::string mismatch(const scene::Mesh& mesh, const scene::Mesh& shape) {
    if (shape.primitives.size() != mesh.primitives.size()) {
        return "a shape of " + std::to_string(shape.primitives.size()) +
               " primitives for a mesh of " + std::to_string(mesh.primitives.size());
    }
    for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
        const scene::Primitive& a = mesh.primitives[p];
        const scene::Primitive& b = shape.primitives[p];
        if (b.positions.size() != a.positions.size() ||
            (!b.normals.empty() && b.normals.size() != b.positions.size())) {
            return "primitive " + std::to_string(p) + "'s shape has " +
                   std::to_string(b.positions.size()) + " vertices, its mesh " +
                   std::to_string(a.positions.size());
        }
        // The ray scene keeps the first shape's triangles and moves only their vertices: other
        // indices would draw triangles the photons never meet.
        if (b.indices != a.indices) {
            return "primitive " + std::to_string(p) + "'s shape has other triangles than its mesh";
        }
        for (const glm::vec3& v : b.positions) {
            if (!finite(v)) {
                return "primitive " + std::to_string(p) +
                       "'s shape has a position that is not "
                       "finite";
            }
        }
        for (const glm::vec3& n : b.normals) {
            if (!finite(n)) {
                return "primitive " + std::to_string(p) +
                       "'s shape has a normal that is not "
                       "finite";
            }
        }
    }
    return {};
}

}  // namespace

void set_mesh_shape(ecs::Registry& registry, ecs::Entity entity,
                    std::shared_ptr<const scene::Mesh> shape) {
    const auto* instance =
        registry.valid(entity) ? registry.try_get<scene::MeshInstance>(entity) : nullptr;
    if (instance == nullptr || shape == nullptr) {
        throw Error("set_mesh_shape: " + name_of(registry, entity) +
                    (instance == nullptr ? " has no mesh" : " was given no shape"));
    }
    const scene::Mesh& mesh = instance->source->meshes.at(static_cast<std::size_t>(instance->mesh));
    if (const std::string why = mismatch(mesh, *shape); !why.empty()) {
        throw Error("set_mesh_shape: " + name_of(registry, entity) + ": " + why);
    }
    const std::shared_ptr<const scene::Scene> source = instance->source;
    const int index = instance->mesh;
    if (!registry.has<scene::Dynamic>(entity)) {
        registry.emplace<scene::Dynamic>(entity);
    }
    // Replaced, not patched: the shared pointer is new, so the renderer's cache (keyed by the
    // mesh it draws) and the ray scene both see a different shape.
    registry.replace<scene::MeshInstance>(entity, source, index, std::move(shape));
}

}  // namespace luxel::world
