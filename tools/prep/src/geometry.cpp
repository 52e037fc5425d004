#include "luxel/prep/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>

#include <OpenMesh/Core/System/omstream.hh>

#include "luxel/runtime/error.hpp"

namespace luxel::prep {
namespace {

/// A cell of the welding grid.
struct CellKey {
    std::int64_t x, y, z;
    friend auto operator<=>(const CellKey&, const CellKey&) = default;
};

std::int64_t cell_of(double coordinate) {
    return static_cast<std::int64_t>(std::floor(coordinate));
}

/// Merges points closer than `tolerance`: each point maps to the first earlier point within
/// the tolerance that is not itself merged into another, or to itself. Points are sorted by
/// grid cell, so a point's own cell is at hand; cells are 32 tolerances wide, so only the few
/// points within a tolerance of a cell border need to look into a neighbouring cell (by
/// binary search in the sorted list, which needs no allocation per cell).
std::vector<int> weld(const std::vector<glm::dvec3>& points, double tolerance) {
    const double cell = 32.0 * tolerance;
    struct Entry {
        CellKey key;
        int index;
    };
    std::vector<Entry> sorted(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        const glm::dvec3 c = points[i] / cell;
        sorted[i] = {{cell_of(c.x), cell_of(c.y), cell_of(c.z)}, static_cast<int>(i)};
    }
    std::sort(sorted.begin(), sorted.end(), [](const Entry& a, const Entry& b) {
        return a.key < b.key || (a.key == b.key && a.index < b.index);
    });
    std::vector<std::size_t> position(points.size());
    for (std::size_t at = 0; at < sorted.size(); ++at) {
        position[static_cast<std::size_t>(sorted[at].index)] = at;
    }
    std::vector<int> representative(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        const glm::dvec3& p = points[i];
        int best = static_cast<int>(i);
        auto consider = [&](int j) {
            const glm::dvec3 d = points[static_cast<std::size_t>(j)] - p;
            if (j < best && representative[static_cast<std::size_t>(j)] == j &&
                glm::dot(d, d) <= tolerance * tolerance) {
                best = j;
            }
        };
        // The point's own cell: the earlier points in it sit just before it in the list.
        const CellKey own = sorted[position[i]].key;
        for (std::size_t at = position[i]; at > 0 && sorted[at - 1].key == own; --at) {
            consider(sorted[at - 1].index);
        }
        // Neighbouring cells, only where the tolerance reaches across a cell border.
        const glm::dvec3 low = (p - tolerance) / cell;
        const glm::dvec3 high = (p + tolerance) / cell;
        for (auto x = cell_of(low.x); x <= cell_of(high.x); ++x) {
            for (auto y = cell_of(low.y); y <= cell_of(high.y); ++y) {
                for (auto z = cell_of(low.z); z <= cell_of(high.z); ++z) {
                    const CellKey key{x, y, z};
                    if (key == own) {
                        continue;
                    }
                    auto it = std::lower_bound(
                        sorted.begin(), sorted.end(), key,
                        [](const Entry& e, const CellKey& k) { return e.key < k; });
                    // Within a cell, entries are in index order: only earlier points count.
                    for (; it != sorted.end() && it->key == key && it->index < best; ++it) {
                        consider(it->index);
                    }
                }
            }
        }
        representative[i] = best;
    }
    return representative;
}

bool is_lightmapped(const scene::Primitive& primitive,
                    const std::vector<scene::Material>& materials, bool lightmap_specular) {
    if (primitive.indices.empty() || lightmap_specular || primitive.material < 0) {
        return !primitive.indices.empty();
    }
    return !materials.at(static_cast<std::size_t>(primitive.material)).is_specular();
}

/// OpenMesh's add_face refuses a face that would make a vertex or an edge non-manifold. These
/// are its own two conditions, checked up front so the face can be attached through vertex
/// copies instead: returns, per corner, whether that corner must be a fresh copy.
std::array<bool, 3> corners_to_copy(const HalfEdgeMesh& mesh,
                                    const std::array<HalfEdgeMesh::VertexHandle, 3>& v) {
    std::array<bool, 3> copy{false, false, false};
    for (int i = 0; i < 3; ++i) {
        // A vertex whose fan is closed (no boundary half-edge) cannot take another face.
        copy[static_cast<std::size_t>(i)] = !mesh.is_boundary(v[static_cast<std::size_t>(i)]);
    }
    for (int i = 0; i < 3; ++i) {
        const auto a = v[static_cast<std::size_t>(i)];
        const auto b = v[static_cast<std::size_t>((i + 1) % 3)];
        const auto existing = mesh.find_halfedge(a, b);
        // The directed edge already has a face: a third face on the edge, or a neighbour with
        // the opposite winding.
        if (existing.is_valid() && !mesh.is_boundary(existing)) {
            copy[static_cast<std::size_t>(i)] = true;
            copy[static_cast<std::size_t>((i + 1) % 3)] = true;
        }
    }
    return copy;
}

}  // namespace

glm::dvec3 NodeGeometry::position(int vertex) const {
    const auto& p = mesh.point(HalfEdgeMesh::VertexHandle(vertex));
    return {p[0], p[1], p[2]};
}

void silence_openmesh() {
    static std::once_flag once;
    std::call_once(once, [] { omerr().disable(); });
}

NodeGeometry build_geometry(const scene::Mesh& source,
                            const std::vector<scene::Material>& materials, const glm::dmat4& world,
                            bool lightmap_specular) {
    NodeGeometry geometry;
    geometry.world = world;
    geometry.primitive_lightmapped.resize(source.primitives.size());

    // World positions of every corner's vertex, and the size of what is welded.
    glm::dvec3 low(std::numeric_limits<double>::max());
    glm::dvec3 high(std::numeric_limits<double>::lowest());
    std::size_t referenced_vertices = 0;
    std::vector<std::vector<glm::dvec3>> world_positions(source.primitives.size());
    std::vector<std::vector<bool>> used(source.primitives.size());
    for (std::size_t p = 0; p < source.primitives.size(); ++p) {
        const scene::Primitive& primitive = source.primitives[p];
        const bool lightmapped = is_lightmapped(primitive, materials, lightmap_specular);
        geometry.primitive_lightmapped[p] = lightmapped;
        if (!lightmapped) {
            continue;
        }
        used[p].assign(primitive.positions.size(), false);
        for (const std::uint32_t index : primitive.indices) {
            used[p][index] = true;
        }
        world_positions[p].resize(primitive.positions.size());
        for (std::size_t v = 0; v < primitive.positions.size(); ++v) {
            const glm::dvec3 w =
                glm::dvec3(world * glm::dvec4(glm::dvec3(primitive.positions[v]), 1.0));
            world_positions[p][v] = w;
            if (used[p][v]) {
                low = glm::min(low, w);
                high = glm::max(high, w);
                ++referenced_vertices;
            } else {
                ++geometry.counts.isolated_vertices;
            }
        }
    }
    if (referenced_vertices == 0) {
        return geometry;
    }
    // Every referenced corner position, primitive by primitive, welded in one go.
    std::vector<glm::dvec3> points;
    points.reserve(referenced_vertices);
    std::vector<std::vector<int>> point_of(source.primitives.size());
    for (std::size_t p = 0; p < source.primitives.size(); ++p) {
        if (!geometry.primitive_lightmapped[p]) {
            continue;
        }
        point_of[p].assign(world_positions[p].size(), -1);
        for (std::size_t v = 0; v < world_positions[p].size(); ++v) {
            if (used[p][v]) {
                point_of[p][v] = static_cast<int>(points.size());
                points.push_back(world_positions[p][v]);
            }
        }
    }
    const double size = glm::length(high - low);
    const std::vector<int> representative = weld(points, std::max(size * 1e-6, 1e-9));

    // Welded point -> half-edge mesh vertex, created when a face first uses it.
    std::vector<int> mesh_vertex(points.size(), -1);
    auto vertex_for = [&](int point) {
        int& v = mesh_vertex[static_cast<std::size_t>(point)];
        if (v < 0) {
            const glm::dvec3& p = points[static_cast<std::size_t>(point)];
            v = geometry.mesh.add_vertex(HalfEdgeMesh::Point(p.x, p.y, p.z)).idx();
        }
        return HalfEdgeMesh::VertexHandle(v);
    };

    HalfEdgeMesh& mesh = geometry.mesh;
    for (std::size_t p = 0; p < source.primitives.size(); ++p) {
        if (!geometry.primitive_lightmapped[p]) {
            continue;
        }
        const scene::Primitive& primitive = source.primitives[p];
        for (std::size_t t = 0; t + 2 < primitive.indices.size(); t += 3) {
            Face face;
            std::array<int, 3> corner_points{};
            for (std::size_t c = 0; c < 3; ++c) {
                const std::uint32_t index = primitive.indices[t + c];
                face.source[c] = {static_cast<int>(p), index};
                corner_points[c] = representative[static_cast<std::size_t>(point_of[p][index])];
            }
            if (corner_points[0] == corner_points[1] || corner_points[1] == corner_points[2] ||
                corner_points[0] == corner_points[2]) {
                ++geometry.counts.degenerate_faces;
                continue;
            }
            const glm::dvec3 a = points[static_cast<std::size_t>(corner_points[0])];
            const glm::dvec3 b = points[static_cast<std::size_t>(corner_points[1])];
            const glm::dvec3 c = points[static_cast<std::size_t>(corner_points[2])];
            const glm::dvec3 cross = glm::cross(b - a, c - a);
            const double twice_area = glm::length(cross);
            const double longest =
                std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
            // Collinear corners (relative to the triangle's own size): no area to light, and
            // no normal to compare across edges.
            if (!(twice_area > 1e-10 * longest * longest)) {
                ++geometry.counts.degenerate_faces;
                continue;
            }
            face.normal = cross / twice_area;
            face.area = 0.5 * twice_area;
            face.material = primitive.material;

            std::array<HalfEdgeMesh::VertexHandle, 3> v{vertex_for(corner_points[0]),
                                                        vertex_for(corner_points[1]),
                                                        vertex_for(corner_points[2])};
            const std::array<bool, 3> copy = corners_to_copy(mesh, v);
            const bool repaired = copy[0] || copy[1] || copy[2];
            // add_vertex may grow the point array, so the point is copied before the call.
            auto copy_of = [&mesh](HalfEdgeMesh::VertexHandle original) {
                const HalfEdgeMesh::Point point = mesh.point(original);
                return mesh.add_vertex(point);
            };
            for (std::size_t i = 0; i < 3; ++i) {
                if (copy[i]) {
                    v[i] = copy_of(v[i]);
                }
            }
            auto handle = mesh.add_face(v[0], v[1], v[2]);
            if (!handle.is_valid()) {
                // OpenMesh could not link the new face into the fans around its corners:
                // attach it through copies of all three, as a triangle of its own.
                for (auto& corner : v) {
                    corner = copy_of(corner);
                }
                handle = mesh.add_face(v[0], v[1], v[2]);
                ++geometry.counts.non_manifold_faces;
            } else if (repaired) {
                ++geometry.counts.non_manifold_faces;
            }
            if (!handle.is_valid() ||
                static_cast<std::size_t>(handle.idx()) != geometry.faces.size()) {
                throw Error("mesh '" + source.name +
                            "': OpenMesh rejected a triangle of three fresh vertices");
            }
            for (std::size_t i = 0; i < 3; ++i) {
                face.vertices[i] = v[i].idx();
            }
            if (primitive.normals.empty()) {
                ++geometry.counts.faces_without_normals;
            }
            geometry.faces.push_back(face);
        }
    }

    // Neighbours across each edge, read off the half-edge structure.
    for (std::size_t f = 0; f < geometry.faces.size(); ++f) {
        Face& face = geometry.faces[f];
        for (std::size_t i = 0; i < 3; ++i) {
            const auto h =
                mesh.find_halfedge(HalfEdgeMesh::VertexHandle(face.vertices[i]),
                                   HalfEdgeMesh::VertexHandle(face.vertices[(i + 1) % 3]));
            const auto across = mesh.opposite_face_handle(h);
            face.neighbours[i] = across.is_valid() ? across.idx() : -1;
        }
    }
    geometry.counts.faces = geometry.faces.size();
    return geometry;
}

}  // namespace luxel::prep
