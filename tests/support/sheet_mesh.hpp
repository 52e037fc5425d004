#pragma once

// A flat sheet of side x side vertices in the xz plane, for the tests and benchmarks of meshes
// that deform (skinning, vertex waves).

#include <cstdint>

#include <glm/glm.hpp>

#include "luxel/scene/scene.hpp"

namespace luxel::testing {

/// `side` x `side` vertices from `origin` across `size` metres in x and z, every normal
/// `normal`, two triangles per cell wound so the face normal is +y. Vertex (x, z) is index
/// z * side + x.
inline scene::Primitive sheet_primitive(int side, glm::vec3 origin, float size,
                                        glm::vec3 normal = {0.0f, 1.0f, 0.0f}) {
    scene::Primitive primitive;
    const float step = side > 1 ? size / static_cast<float>(side - 1) : 0.0f;
    for (int z = 0; z < side; ++z) {
        for (int x = 0; x < side; ++x) {
            primitive.positions.push_back(origin + glm::vec3(step * static_cast<float>(x), 0.0f,
                                                             step * static_cast<float>(z)));
            primitive.normals.push_back(normal);
        }
    }
    const auto stride = static_cast<std::uint32_t>(side);
    for (int z = 0; z + 1 < side; ++z) {
        for (int x = 0; x + 1 < side; ++x) {
            const auto i = static_cast<std::uint32_t>(z * side + x);
            primitive.indices.insert(primitive.indices.end(),
                                     {i, i + stride, i + 1, i + 1, i + stride, i + stride + 1});
        }
    }
    return primitive;
}

}  // namespace luxel::testing
