#include "gather_geometry.hpp"

#include <algorithm>
#include <cstddef>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

#include "gather/gather_interface.h"

namespace luxel::lighting {
namespace {

struct GatherVertex {
    glm::vec3 position;
    glm::vec2 lightmap_uv;
    std::int32_t surface;
};
static_assert(sizeof(GatherVertex) == 24);

GatherGeometry::Object upload(const TriangleMesh& mesh,
                              const std::vector<TraceMaterial>* materials) {
    std::vector<GatherVertex> vertices;
    std::vector<std::uint32_t> indices;
    vertices.reserve(mesh.positions.size());
    indices.reserve(mesh.indices.size());
    // (source vertex, surface) -> output vertex: the duplication of shared vertices.
    std::unordered_map<std::uint64_t, std::uint32_t> remap;
    remap.reserve(mesh.positions.size());
    const bool has_uvs = mesh.lightmap_uvs.size() == mesh.positions.size();
    const std::size_t triangles = mesh.triangle_count();
    for (std::size_t t = 0; t < triangles; ++t) {
        const bool specular = materials != nullptr && t < mesh.material_ids.size() &&
                              mesh.material_ids[t] < materials->size() &&
                              (*materials)[mesh.material_ids[t]].scattering != Scattering::Diffuse;
        const std::int32_t surface = specular                      ? GATHER_SPECULAR_SURFACE
                                     : t < mesh.surface_ids.size() ? mesh.surface_ids[t]
                                                                   : -1;
        for (std::size_t corner = 0; corner < 3; ++corner) {
            const std::uint32_t source = mesh.indices[3 * t + corner];
            const std::uint64_t key =
                (static_cast<std::uint64_t>(source) << 32) | static_cast<std::uint32_t>(surface);
            const auto [found, inserted] =
                remap.try_emplace(key, static_cast<std::uint32_t>(vertices.size()));
            if (inserted) {
                vertices.push_back({mesh.positions[source],
                                    has_uvs ? mesh.lightmap_uvs[source] : glm::vec2(0.0f),
                                    surface});
            }
            indices.push_back(found->second);
        }
    }

    GatherGeometry::Object object;
    object.index_count = static_cast<GLsizei>(indices.size());
    object.vertices =
        gl::Buffer::create(std::max<std::size_t>(vertices.size(), 1) * sizeof(GatherVertex),
                           vertices.empty() ? nullptr : vertices.data(), 0);
    object.indices =
        gl::Buffer::create(std::max<std::size_t>(indices.size(), 1) * sizeof(std::uint32_t),
                           indices.empty() ? nullptr : indices.data(), 0);
    object.vertex_array = gl::VertexArray::create();
    const GLuint vao = object.vertex_array.id();
    glVertexArrayVertexBuffer(vao, 0, object.vertices.id(), 0, sizeof(GatherVertex));
    glVertexArrayElementBuffer(vao, object.indices.id());
    glEnableVertexArrayAttrib(vao, 0);
    glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE,
                              static_cast<GLuint>(offsetof(GatherVertex, position)));
    glVertexArrayAttribBinding(vao, 0, 0);
    glEnableVertexArrayAttrib(vao, 1);
    glVertexArrayAttribFormat(vao, 1, 2, GL_FLOAT, GL_FALSE,
                              static_cast<GLuint>(offsetof(GatherVertex, lightmap_uv)));
    glVertexArrayAttribBinding(vao, 1, 0);
    glEnableVertexArrayAttrib(vao, 2);
    glVertexArrayAttribIFormat(vao, 2, 1, GL_INT,
                               static_cast<GLuint>(offsetof(GatherVertex, surface)));
    glVertexArrayAttribBinding(vao, 2, 0);
    gl::check_error("GatherGeometry upload");
    return object;
}

}  // namespace

void GatherGeometry::sync(const RayScene& scene, const std::vector<TraceMaterial>* materials) {
    const std::vector<ObjectId> ids = scene.objects();
    std::erase_if(objects_, [&](const auto& entry) {
        return !std::binary_search(ids.begin(), ids.end(), entry.first);
    });
    for (ObjectId id : ids) {
        const auto found = objects_.find(id);
        if (found == objects_.end() || found->second.deformations != scene.deformations(id)) {
            Object object = upload(scene.mesh(id), materials);
            object.deformations = scene.deformations(id);
            objects_.insert_or_assign(id, std::move(object));
            ++uploads_;
        }
    }
}

}  // namespace luxel::lighting
