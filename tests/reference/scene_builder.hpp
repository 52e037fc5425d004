#pragma once

// Small hand-built scenes for closed-form checks: axis-aligned quads with light-map UVs.

#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/constants.hpp>

#include "luxel/lighting/reference/reference_scene.hpp"

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

/// A rectangle centred at `centre`, spanning [-half_u, half_u] along the unit vector `u` and
/// [-half_v, half_v] along the unit vector `v` (u perpendicular to v), whose front faces
/// `normal` (+-cross(u, v)). Light-map UV (s, t) is the point centre + (2s - 1) half_u u +
/// (2t - 1) half_v v, so the light map's texels are squares of the rectangle.
struct Rectangle {
    glm::vec3 centre{0.0f};
    glm::vec3 u{1.0f, 0.0f, 0.0f};
    glm::vec3 v{0.0f, 0.0f, 1.0f};
    float half_u = 1.0f;
    float half_v = 1.0f;
    glm::vec3 normal{0.0f, -1.0f, 0.0f};

    /// The world point of light-map UV (s, t).
    [[nodiscard]] glm::dvec3 point(double s, double t) const {
        return glm::dvec3(centre) + (2.0 * s - 1.0) * static_cast<double>(half_u) * glm::dvec3(u) +
               (2.0 * t - 1.0) * static_cast<double>(half_v) * glm::dvec3(v);
    }

    /// Two triangles wound so their geometric normal is `normal`.
    [[nodiscard]] lighting::TriangleMesh mesh(std::int32_t surface, std::uint32_t material) const {
        lighting::TriangleMesh out;
        const std::vector<glm::vec2> uvs{{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}};
        for (const glm::vec2& uv : uvs) {
            out.positions.push_back(glm::vec3(point(uv.x, uv.y)));
        }
        out.lightmap_uvs = uvs;
        out.normals.assign(4, normal);
        // cross(p1 - p0, p2 - p0) = 4 half_u half_v cross(u, v): (0, 1, 2) winds toward it.
        const bool along = glm::dot(glm::cross(u, v), normal) > 0.0f;
        out.indices = along ? std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}
                            : std::vector<std::uint32_t>{0, 2, 1, 0, 3, 2};
        out.surface_ids.assign(2, surface);
        out.material_ids.assign(2, material);
        return out;
    }

    /// The centre of light-map texel (tx, ty) at `size` texels per edge.
    [[nodiscard]] lighting::reference::ReferenceTexel texel(int tx, int ty, int size) const {
        lighting::reference::ReferenceTexel out;
        out.x = tx;
        out.y = ty;
        const double s = (static_cast<double>(tx) + 0.5) / static_cast<double>(size);
        const double t = (static_cast<double>(ty) + 0.5) / static_cast<double>(size);
        out.position = glm::vec3(point(s, t));
        out.normal = normal;
        out.geometric = normal;
        return out;
    }

    /// Every texel of the rectangle's light map at `size` texels per edge.
    [[nodiscard]] lighting::reference::ReferenceSurface texels(std::uint32_t surface,
                                                               int size) const {
        lighting::reference::ReferenceSurface out;
        out.surface = surface;
        out.page_size = size;
        for (int ty = 0; ty < size; ++ty) {
            for (int tx = 0; tx < size; ++tx) {
                out.texels.push_back(texel(tx, ty, size));
            }
        }
        return out;
    }
};

/// A UV sphere: `rings` bands of latitude (pole to pole along y) and `segments` of longitude,
/// every vertex on the sphere, smooth (radial) normals, outward winding, no light map. The
/// quads between two latitudes are planar, so the mesh is the convex hull of its vertices.
inline lighting::TriangleMesh uv_sphere(const glm::vec3& centre, float radius, int rings,
                                        int segments, std::uint32_t material) {
    lighting::TriangleMesh mesh;
    const double pi = glm::pi<double>();
    const auto vertex = [&](int ring, int segment) {
        return static_cast<std::uint32_t>(ring * (segments + 1) + segment);
    };
    for (int ring = 0; ring <= rings; ++ring) {
        const double theta = pi * static_cast<double>(ring) / static_cast<double>(rings);
        for (int segment = 0; segment <= segments; ++segment) {
            const double phi =
                2.0 * pi * static_cast<double>(segment % segments) / static_cast<double>(segments);
            const glm::dvec3 n(std::sin(theta) * std::cos(phi), std::cos(theta),
                               std::sin(theta) * std::sin(phi));
            mesh.positions.push_back(centre + radius * glm::vec3(n));
            mesh.normals.push_back(glm::vec3(n));
        }
    }
    for (int ring = 0; ring < rings; ++ring) {
        for (int segment = 0; segment < segments; ++segment) {
            // a (ring, segment), b one ring down, c down and along, d along: cross(d - a,
            // b - a) points outward. The pole rows keep only their non-degenerate triangle.
            const std::uint32_t a = vertex(ring, segment);
            const std::uint32_t b = vertex(ring + 1, segment);
            const std::uint32_t c = vertex(ring + 1, segment + 1);
            const std::uint32_t d = vertex(ring, segment + 1);
            if (ring + 1 < rings) {
                mesh.indices.insert(mesh.indices.end(), {a, c, b});
            }
            if (ring > 0) {
                mesh.indices.insert(mesh.indices.end(), {a, d, c});
            }
        }
    }
    mesh.surface_ids.assign(mesh.triangle_count(), -1);
    mesh.material_ids.assign(mesh.triangle_count(), material);
    return mesh;
}

}  // namespace luxel::testing
