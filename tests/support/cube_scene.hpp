#pragma once

// A closed cube as a one-mesh scene, for tests that add an object to a level at run time.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/scene/scene.hpp"

namespace luxel::testing {

/// The closed box [lo, hi], faces outward (counter-clockwise seen from outside): four corners
/// per face appended to `positions`, two triangles per face to `indices`.
inline void append_box(const glm::vec3& lo, const glm::vec3& hi, std::vector<glm::vec3>& positions,
                       std::vector<std::uint32_t>& indices) {
    const glm::vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z},
                            {lo.x, hi.y, lo.z}, {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z},
                            {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
    const int faces[6][4] = {{3, 2, 1, 0}, {4, 5, 6, 7}, {0, 4, 7, 3},
                             {1, 2, 6, 5}, {0, 1, 5, 4}, {3, 7, 6, 2}};
    for (const auto& face : faces) {
        const auto base = static_cast<std::uint32_t>(positions.size());
        for (int k = 0; k < 4; ++k) {
            positions.push_back(c[face[k]]);
        }
        indices.insert(indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
}

/// An axis-aligned cube of edge 2 * half centred at the origin, faces outward (counter-
/// clockwise seen from outside), made of `material`.
inline std::shared_ptr<const scene::Scene> cube_scene(float half, const scene::Material& material,
                                                      const std::string& name = "cube") {
    auto s = std::make_shared<scene::Scene>();
    s->materials.push_back(material);
    scene::Primitive p;
    append_box(glm::vec3(-half), glm::vec3(half), p.positions, p.indices);
    p.material = 0;
    s->meshes.push_back({name, {p}});
    return s;
}

/// A plain diffuse material of albedo `grey`.
inline scene::Material diffuse_material(float grey) {
    scene::Material material;
    material.metallic = 0.0f;
    material.base_color = glm::vec4(grey, grey, grey, 1.0f);
    return material;
}

}  // namespace luxel::testing
