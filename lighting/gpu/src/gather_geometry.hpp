#pragma once

#include <cstdint>
#include <map>

#include <vector>

#include "luxel/lighting/core/photon_tracer.hpp"
#include "luxel/lighting/core/ray_scene.hpp"
#include "luxel/runtime/gl_objects.hpp"

namespace luxel::lighting {

/// The RayScene's triangles on the GPU, one vertex array per object, in the object's own space
/// (static objects: world space, as RayScene stores them). Each vertex carries its light-map
/// UV and the surface id of the triangles using it; a vertex shared by triangles of different
/// surfaces is duplicated so the id can be a flat per-vertex attribute. A triangle whose material
/// is a mirror or glass carries GATHER_SPECULAR_SURFACE instead (with a material table).
///
/// Vertex layout: location 0 position (vec3), 1 light-map UV (vec2), 2 surface id (int).
class GatherGeometry {
  public:
    struct Object {
        gl::Buffer vertices;
        gl::Buffer indices;
        gl::VertexArray vertex_array;
        GLsizei index_count = 0;
        std::uint64_t deformations = 0;  ///< RayScene::deformations when uploaded
    };

    /// Uploads objects the scene has and this does not, uploads again those deformed since
    /// (a skinned mesh's pose), and frees those the scene no longer has. RayScene never reuses
    /// an object id and changes an object's mesh only through deform, which it counts.
    /// `materials` (may be null) is the table the meshes' material ids index.
    void sync(const RayScene& scene, const std::vector<TraceMaterial>* materials);
    /// Drops everything; the next sync uploads every object again.
    void clear() { objects_.clear(); }

    [[nodiscard]] const std::map<ObjectId, Object>& objects() const { return objects_; }
    /// Objects uploaded since construction (for tests of the refresh logic).
    [[nodiscard]] std::uint64_t uploads() const { return uploads_; }

  private:
    std::map<ObjectId, Object> objects_;
    std::uint64_t uploads_ = 0;
};

}  // namespace luxel::lighting
