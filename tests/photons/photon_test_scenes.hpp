#pragma once

// Small hand-built ray scenes for the photon tests.

#include <glm/glm.hpp>

#include "luxel/lighting/core/ray_scene.hpp"

namespace luxel::testing {

/// An axis-aligned box of half size h centred at `centre`, faces pointing inwards, one surface
/// per face (ids first_surface .. first_surface + 5), all with material `material`.
inline lighting::TriangleMesh inward_box(glm::vec3 centre, float h, std::int32_t first_surface,
                                         std::uint32_t material) {
    lighting::TriangleMesh mesh;
    const glm::vec3 c[8] = {{-h, -h, -h}, {h, -h, -h}, {h, h, -h}, {-h, h, -h},
                            {-h, -h, h},  {h, -h, h},  {h, h, h},  {-h, h, h}};
    // Each face listed counter-clockwise as seen from inside the box.
    const int faces[6][4] = {{0, 1, 2, 3}, {5, 4, 7, 6}, {4, 0, 3, 7},
                             {1, 5, 6, 2}, {4, 5, 1, 0}, {3, 2, 6, 7}};
    for (int f = 0; f < 6; ++f) {
        const auto base = static_cast<std::uint32_t>(mesh.positions.size());
        for (int k = 0; k < 4; ++k) {
            mesh.positions.push_back(centre + c[faces[f][k]]);
        }
        mesh.indices.insert(mesh.indices.end(),
                            {base, base + 1, base + 2, base, base + 2, base + 3});
        mesh.surface_ids.insert(mesh.surface_ids.end(), 2, first_surface + f);
        mesh.material_ids.insert(mesh.material_ids.end(), 2, material);
    }
    return mesh;
}

/// A closed box with outward faces (an obstacle), surface -1, material `material`.
inline lighting::TriangleMesh outward_box(float h, std::uint32_t material) {
    lighting::TriangleMesh mesh = inward_box(glm::vec3(0.0f), h, -1, material);
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
        std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
    }
    for (auto& s : mesh.surface_ids) {
        s = -1;
    }
    return mesh;
}

}  // namespace luxel::testing
