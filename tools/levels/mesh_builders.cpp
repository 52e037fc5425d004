#include "mesh_builders.hpp"

#include <cmath>

#include <glm/gtc/constants.hpp>

namespace luxel::levels {
namespace {

std::uint32_t index_of(int u, int v, int columns) {
    return static_cast<std::uint32_t>(v * (columns + 1) + u);
}

/// Two counter-clockwise triangles for each cell of a (columns x rows) vertex grid.
void add_grid_indices(scene::Primitive& p, std::uint32_t base, int columns, int rows) {
    for (int v = 0; v < rows; ++v) {
        for (int u = 0; u < columns; ++u) {
            const std::uint32_t a = base + index_of(u, v, columns);
            const std::uint32_t b = base + index_of(u + 1, v, columns);
            const std::uint32_t c = base + index_of(u + 1, v + 1, columns);
            const std::uint32_t d = base + index_of(u, v + 1, columns);
            p.indices.insert(p.indices.end(), {a, b, c, a, c, d});
        }
    }
}

}  // namespace

scene::Primitive make_quad(glm::vec3 corner, glm::vec3 edge_u, glm::vec3 edge_v, int segments_u,
                           int segments_v) {
    scene::Primitive p;
    const glm::vec3 normal = glm::normalize(glm::cross(edge_u, edge_v));
    for (int v = 0; v <= segments_v; ++v) {
        for (int u = 0; u <= segments_u; ++u) {
            const float s = static_cast<float>(u) / static_cast<float>(segments_u);
            const float t = static_cast<float>(v) / static_cast<float>(segments_v);
            p.positions.push_back(corner + s * edge_u + t * edge_v);
            p.normals.push_back(normal);
            p.texcoords0.emplace_back(s, t);
        }
    }
    add_grid_indices(p, 0, segments_u, segments_v);
    return p;
}

scene::Primitive make_height_field(float x0, float x1, float z0, float z1, float y, int cells_x,
                                   int cells_z, const std::function<float(float, float)>& height,
                                   const std::function<glm::vec2(float, float)>& slope) {
    scene::Primitive p;
    // Rows run from z1 towards z0 so that (+x, -z) cells wind counter-clockwise seen from +y.
    for (int v = 0; v <= cells_z; ++v) {
        for (int u = 0; u <= cells_x; ++u) {
            const float s = static_cast<float>(u) / static_cast<float>(cells_x);
            const float t = static_cast<float>(v) / static_cast<float>(cells_z);
            const float x = x0 + s * (x1 - x0);
            const float z = z1 + t * (z0 - z1);
            const glm::vec2 gradient = slope(x, z);
            p.positions.emplace_back(x, y + height(x, z), z);
            p.normals.push_back(glm::normalize(glm::vec3(-gradient.x, 1.0f, -gradient.y)));
            p.texcoords0.emplace_back(s, t);
        }
    }
    add_grid_indices(p, 0, cells_x, cells_z);
    return p;
}

scene::Primitive make_box(glm::vec3 size, bool inside) {
    const glm::vec3 h = size * 0.5f;
    scene::Primitive box;
    // Each face: corner, then two edges whose cross product points outward.
    const glm::vec3 corners[6] = {{-h.x, -h.y, h.z},  {h.x, -h.y, -h.z}, {h.x, -h.y, h.z},
                                  {-h.x, -h.y, -h.z}, {-h.x, h.y, h.z},  {-h.x, -h.y, -h.z}};
    const glm::vec3 edges_u[6] = {{size.x, 0, 0}, {-size.x, 0, 0}, {0, 0, -size.z},
                                  {0, 0, size.z}, {size.x, 0, 0},  {size.x, 0, 0}};
    const glm::vec3 edges_v[6] = {{0, size.y, 0}, {0, size.y, 0},  {0, size.y, 0},
                                  {0, size.y, 0}, {0, 0, -size.z}, {0, 0, size.z}};
    for (int f = 0; f < 6; ++f) {
        scene::Primitive face = inside ? make_quad(corners[f] + edges_u[f], -edges_u[f], edges_v[f])
                                       : make_quad(corners[f], edges_u[f], edges_v[f]);
        append(box, face);
    }
    return box;
}

scene::Primitive make_sphere(float radius, int segments, int rings, bool inside) {
    scene::Primitive p;
    for (int ring = 0; ring <= rings; ++ring) {
        const float theta = glm::pi<float>() * static_cast<float>(ring) / static_cast<float>(rings);
        for (int segment = 0; segment <= segments; ++segment) {
            const float phi =
                glm::two_pi<float>() * static_cast<float>(segment) / static_cast<float>(segments);
            const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta),
                              -std::sin(theta) * std::sin(phi));
            p.positions.push_back(radius * n);
            p.normals.push_back(inside ? -n : n);
            p.texcoords0.emplace_back(static_cast<float>(segment) / static_cast<float>(segments),
                                      static_cast<float>(ring) / static_cast<float>(rings));
        }
    }
    for (int ring = 0; ring < rings; ++ring) {
        for (int segment = 0; segment < segments; ++segment) {
            const auto a = index_of(segment, ring, segments);
            const auto b = index_of(segment, ring + 1, segments);
            const auto c = index_of(segment + 1, ring + 1, segments);
            const auto d = index_of(segment + 1, ring, segments);
            // The pole rows would give zero-area triangles: emit only the non-degenerate one.
            if (ring != 0) {
                inside ? p.indices.insert(p.indices.end(), {a, d, b})
                       : p.indices.insert(p.indices.end(), {a, b, d});
            }
            if (ring != rings - 1) {
                inside ? p.indices.insert(p.indices.end(), {b, d, c})
                       : p.indices.insert(p.indices.end(), {b, c, d});
            }
        }
    }
    return p;
}

scene::Primitive make_open_cylinder(float radius, float height, int segments) {
    scene::Primitive p;
    for (int row = 0; row <= 1; ++row) {
        for (int segment = 0; segment <= segments; ++segment) {
            const float phi =
                glm::two_pi<float>() * static_cast<float>(segment) / static_cast<float>(segments);
            const glm::vec3 n(std::cos(phi), 0.0f, -std::sin(phi));
            p.positions.push_back(radius * n +
                                  glm::vec3(0.0f, height * static_cast<float>(row), 0.0f));
            p.normals.push_back(n);
            p.texcoords0.emplace_back(static_cast<float>(segment) / static_cast<float>(segments),
                                      static_cast<float>(row));
        }
    }
    add_grid_indices(p, 0, segments, 1);
    return p;
}

void append(scene::Primitive& into, const scene::Primitive& more) {
    const auto base = static_cast<std::uint32_t>(into.positions.size());
    into.positions.insert(into.positions.end(), more.positions.begin(), more.positions.end());
    into.normals.insert(into.normals.end(), more.normals.begin(), more.normals.end());
    into.texcoords0.insert(into.texcoords0.end(), more.texcoords0.begin(), more.texcoords0.end());
    into.texcoords1.insert(into.texcoords1.end(), more.texcoords1.begin(), more.texcoords1.end());
    for (std::uint32_t index : more.indices) {
        into.indices.push_back(base + index);
    }
}

}  // namespace luxel::levels
