#pragma once

// Hand-built specular objects for the caustic tests.

#include <cmath>

#include <glm/glm.hpp>

#include "luxel/lighting/core/light_source.hpp"
#include "luxel/lighting/core/ray_scene.hpp"

namespace luxel::testing {

/// A parallelogram from `origin` spanned by u and v, facing cross(u, v), one surface.
inline lighting::TriangleMesh quad_mesh(glm::vec3 origin, glm::vec3 u, glm::vec3 v,
                                        std::int32_t surface, std::uint32_t material) {
    lighting::TriangleMesh mesh;
    const glm::vec3 normal = glm::normalize(glm::cross(u, v));
    mesh.positions = {origin, origin + u, origin + u + v, origin + v};
    mesh.normals = {normal, normal, normal, normal};
    mesh.indices = {0, 1, 2, 0, 2, 3};
    mesh.surface_ids = {surface, surface};
    mesh.material_ids = {material, material};
    return mesh;
}

/// Orders every triangle of a closed convex mesh so that it faces away from `inside`.
inline void face_outwards(lighting::TriangleMesh& mesh, glm::vec3 inside) {
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const glm::vec3& a = mesh.positions[mesh.indices[t]];
        const glm::vec3& b = mesh.positions[mesh.indices[t + 1]];
        const glm::vec3& c = mesh.positions[mesh.indices[t + 2]];
        if (glm::dot(glm::cross(b - a, c - a), (a + b + c) / 3.0f - inside) < 0.0f) {
            std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
        }
    }
}

/// A UV sphere with smooth (analytic) normals, facing outwards, surface -1.
inline lighting::TriangleMesh sphere_mesh(glm::vec3 centre, float radius, int segments, int rings,
                                          std::uint32_t material) {
    constexpr float pi = 3.14159265358979f;
    lighting::TriangleMesh mesh;
    for (int ring = 0; ring <= rings; ++ring) {
        const float theta = pi * static_cast<float>(ring) / static_cast<float>(rings);
        for (int segment = 0; segment <= segments; ++segment) {
            const float phi =
                2.0f * pi * static_cast<float>(segment) / static_cast<float>(segments);
            const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta),
                              std::sin(theta) * std::sin(phi));
            mesh.positions.push_back(centre + radius * n);
            mesh.normals.push_back(n);
        }
    }
    auto index = [&](int segment, int ring) {
        return static_cast<std::uint32_t>(ring * (segments + 1) + segment);
    };
    for (int ring = 0; ring < rings; ++ring) {
        for (int segment = 0; segment < segments; ++segment) {
            const std::uint32_t a = index(segment, ring);
            const std::uint32_t b = index(segment, ring + 1);
            const std::uint32_t c = index(segment + 1, ring + 1);
            const std::uint32_t d = index(segment + 1, ring);
            if (ring != 0) {
                mesh.indices.insert(mesh.indices.end(), {a, b, d});
            }
            if (ring != rings - 1) {
                mesh.indices.insert(mesh.indices.end(), {b, c, d});
            }
        }
    }
    face_outwards(mesh, centre);
    mesh.surface_ids.assign(mesh.triangle_count(), -1);
    mesh.material_ids.assign(mesh.triangle_count(), material);
    return mesh;
}

/// A closed right prism: the triangle (0,1) (1,1) (1,0) in xy (a horizontal top face, a
/// vertical face at x = 1 and the 45-degree hypotenuse below) extruded over z in [-0.5, 0.5].
/// Flat faces (no vertex normals), surface -1.
inline lighting::TriangleMesh right_prism_mesh(std::uint32_t material) {
    lighting::TriangleMesh mesh;
    const glm::vec2 corners[3] = {{0.0f, 1.0f}, {1.0f, 1.0f}, {1.0f, 0.0f}};
    for (float z : {-0.5f, 0.5f}) {
        for (const glm::vec2& c : corners) {
            mesh.positions.push_back({c.x, c.y, z});
        }
    }
    mesh.indices = {0, 1, 2, 3, 4, 5};  // the two end caps
    for (std::uint32_t edge = 0; edge < 3; ++edge) {
        const std::uint32_t next = (edge + 1) % 3;
        mesh.indices.insert(mesh.indices.end(), {edge, next, next + 3, edge, next + 3, edge + 3});
    }
    face_outwards(mesh, glm::vec3(2.0f / 3.0f, 2.0f / 3.0f, 0.0f));
    mesh.surface_ids.assign(mesh.triangle_count(), -1);
    mesh.material_ids.assign(mesh.triangle_count(), material);
    return mesh;
}

/// The sphere around a mesh's bounding box, as PhotonWorld aims caustic photons.
inline lighting::BoundingSphere bounding_sphere(const lighting::TriangleMesh& mesh) {
    glm::vec3 lo(1e30f);
    glm::vec3 hi(-1e30f);
    for (const glm::vec3& p : mesh.positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    const glm::vec3 centre = 0.5f * (lo + hi);
    float radius = 0.0f;
    for (const glm::vec3& p : mesh.positions) {
        radius = std::max(radius, glm::length(p - centre));
    }
    return {centre, radius};
}

}  // namespace luxel::testing
