#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <glm/glm.hpp>

#include "luxel/scene/scene.hpp"

namespace luxel::prep {

/// OpenMesh's triangle mesh with double-precision points: charts are cut and flattened in world
/// space, where a level a kilometre across still needs sub-millimetre precision.
struct HalfEdgeTraits : OpenMesh::DefaultTraitsDouble {};
using HalfEdgeMesh = OpenMesh::TriMesh_ArrayKernelT<HalfEdgeTraits>;

/// Where a face corner came from: a vertex of one primitive of the source mesh.
struct SourceCorner {
    int primitive = -1;
    std::uint32_t vertex = 0;
};

/// One triangle of a node's light-mapped geometry, in world space. Its index is the index of
/// the matching face of NodeGeometry::mesh.
struct Face {
    std::array<int, 3> vertices{};  ///< half-edge mesh vertices, in the source winding
    std::array<SourceCorner, 3> source{};
    /// The face across the edge from corner i to corner i+1; -1 on a boundary.
    std::array<int, 3> neighbours{-1, -1, -1};
    int material = -1;
    glm::dvec3 normal{0.0};  ///< unit geometric normal
    double area = 0.0;       ///< m^2
};

/// What building the half-edge mesh repaired or dropped, for the report.
struct GeometryCounts {
    std::size_t faces = 0;
    /// Zero-area triangles (collinear corners, or corners welded together): dropped.
    std::size_t degenerate_faces = 0;
    /// Faces OpenMesh refuses to attach (a third face on an edge, two fans meeting at a vertex,
    /// an edge used twice in one direction): attached through copies of the offending vertices.
    std::size_t non_manifold_faces = 0;
    /// Vertices no triangle uses: left out of the output.
    std::size_t isolated_vertices = 0;
    /// Faces from primitives without NORMAL: luxel-prep computes normals for them.
    std::size_t faces_without_normals = 0;
};

/// A mesh node's light-mapped triangles as one welded half-edge mesh in world space, with the
/// way back to the source primitives. Primitives of specular materials are not part of it
/// (unless asked for) and pass through unchanged.
struct NodeGeometry {
    HalfEdgeMesh mesh;
    std::vector<Face> faces;
    std::vector<bool> primitive_lightmapped;  ///< per source primitive
    glm::dmat4 world{1.0};
    GeometryCounts counts;

    [[nodiscard]] glm::dvec3 position(int vertex) const;
};

/// Welds the positions of the light-mapped primitives (corners closer than a millionth of the
/// mesh's size are one vertex, so seams that exist only for TEXCOORD_0 or NORMAL do not cut
/// surfaces apart), drops degenerate faces and builds the half-edge mesh.
[[nodiscard]] NodeGeometry build_geometry(const scene::Mesh& mesh,
                                          const std::vector<scene::Material>& materials,
                                          const glm::dmat4& world, bool lightmap_specular);

/// Turns off OpenMesh's error stream: luxel-prep checks and repairs what OpenMesh would
/// complain about, and reports it itself. Called once, before any parallel work.
void silence_openmesh();

}  // namespace luxel::prep
