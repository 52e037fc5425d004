#pragma once

// Small hand-built scenes for closed-form checks: axis-aligned quads with light-map UVs.

#include <vector>

#include <glm/glm.hpp>

#include "luxel/lighting/core/reference/reference_scene.hpp"

namespace luxel::testing {

/// A quad at height y spanning [-half, half] in x and z, facing +y (up) or -y (down), with
/// light-map UVs (x, z) -> ((x + half) / 2 half, (z + half) / 2 half).
inline lighting::TriangleMesh horizontal_quad(float y, float half, bool up, std::int32_t surface,
                                              std::uint32_t material) {
    lighting::TriangleMesh mesh;
    mesh.positions = {{-half, y, -half}, {half, y, -half}, {half, y, half}, {-half, y, half}};
    mesh.lightmap_uvs = {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}};
    const glm::vec3 normal(0.0f, up ? 1.0f : -1.0f, 0.0f);
    mesh.normals.assign(4, normal);
    // (0, 3, 2) winds toward +y: cross(p3 - p0, p2 - p0) = (0, +, 0).
    mesh.indices = up ? std::vector<std::uint32_t>{0, 3, 2, 0, 2, 1}
                      : std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3};
    mesh.surface_ids.assign(2, surface);
    mesh.material_ids.assign(2, material);
    return mesh;
}

/// The world triangles of a mesh (an area light's emitting triangles).
inline std::vector<glm::vec3> triangles_of(const lighting::TriangleMesh& mesh) {
    std::vector<glm::vec3> triangles;
    for (std::uint32_t index : mesh.indices) {
        triangles.push_back(mesh.positions[index]);
    }
    return triangles;
}

/// The texels of horizontal_quad(y, half, up, ...) at `size` texels per edge: centres.
inline lighting::reference::ReferenceSurface quad_texels(std::uint32_t surface, float y, float half,
                                                         bool up, int size) {
    lighting::reference::ReferenceSurface out;
    out.surface = surface;
    out.page_size = size;
    for (int ty = 0; ty < size; ++ty) {
        for (int tx = 0; tx < size; ++tx) {
            lighting::reference::ReferenceTexel texel;
            texel.x = tx;
            texel.y = ty;
            const float u = (static_cast<float>(tx) + 0.5f) / static_cast<float>(size);
            const float v = (static_cast<float>(ty) + 0.5f) / static_cast<float>(size);
            texel.position = {(2.0f * u - 1.0f) * half, y, (2.0f * v - 1.0f) * half};
            texel.normal = {0.0f, up ? 1.0f : -1.0f, 0.0f};
            texel.geometric = texel.normal;
            out.texels.push_back(texel);
        }
    }
    return out;
}

}  // namespace luxel::testing
