#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/lighting/components.hpp"
#include "luxel/runtime/gl_objects.hpp"
#include "material_textures.hpp"

namespace luxel::renderer {

/// An axis-aligned box; empty when lo > hi.
struct Bounds {
    glm::vec3 lo{1e30f};
    glm::vec3 hi{-1e30f};

    [[nodiscard]] bool empty() const { return lo.x > hi.x; }
    void add(const glm::vec3& p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    void add(const Bounds& other) {
        if (!other.empty()) {
            add(other.lo);
            add(other.hi);
        }
    }
    /// The box around this one transformed by `matrix` (its eight corners).
    [[nodiscard]] Bounds transformed(const glm::mat4& matrix) const;
    /// Whether the box comes within `radius` of `centre`.
    [[nodiscard]] bool touches_sphere(const glm::vec3& centre, float radius) const;
};

/// One mesh primitive inside the mesh's shared buffers.
struct GpuPrimitive {
    GLint base_vertex = 0;
    std::size_t first_index = 0;
    GLsizei index_count = 0;
    int material = -1;
    /// The primitive's triangle area over the largest face of its mesh's box: how many times
    /// over its triangles would cover that box seen face-on (a sheet 1, a closed box or room
    /// about 3, 5,000 coincident triangles 5,000). FillBudget estimates a draw's cost with it.
    float layers = 0.0f;
    /// A transmissive primitive whose triangles close up (scene::is_closed_surface): a view
    /// ray through it crosses two surfaces. Not looked for on other materials (false).
    bool closed = false;
    /// The material's base-colour texture, shared with every primitive using the image; null
    /// when the material has none or the primitive has no TEXCOORD_0 (the factor alone).
    std::shared_ptr<const gl::Texture> base_color;
    /// The material's emissive texture, likewise (null: the emissive factor alone).
    std::shared_ptr<const gl::Texture> emissive;
};

/// Draws one primitive of the mesh whose vertex array is bound.
void draw_primitive(const GpuPrimitive& range);

/// A scene mesh on the GPU: one interleaved vertex buffer and one index buffer for all its
/// primitives. Vertex layout: location 0 position, 1 normal, 2 texcoord0, 3 light-map UV
/// (texcoord1); absent attributes are zero. A mesh skinned in the vertex stage has a second
/// buffer: location 4 JOINTS_0 (unsigned), 5 WEIGHTS_0.
struct GpuMesh {
    /// The scene and, for a posed mesh, the pose: kept alive so the key's address stays unique.
    std::shared_ptr<const scene::Scene> source;
    std::shared_ptr<const scene::Mesh> posed;
    gl::Buffer vertices;
    gl::Buffer skin;  ///< joints and weights; empty unless `skinned`
    bool skinned = false;
    gl::Buffer indices;
    gl::VertexArray vertex_array;
    std::vector<GpuPrimitive> primitives;
    Bounds bounds;  ///< object space
    std::uint64_t last_used = 0;
};

/// GPU buffers per mesh (by address: MeshInstance::geometry(), or a skinned pose's bind mesh):
/// many entities instancing one mesh share one upload. Meshes are immutable (a const Scene's, or a
/// skinned mesh's pose, which a new pose replaces rather than edits), so an entry never needs
/// re-uploading; entries unused for `kEvictAfterFrames` frames are freed (a pose as soon as a frame
/// draws without it), and with them the base-colour textures (MaterialTextures, one per (scene,
/// image)) that no remaining mesh uses.
class MeshCache {
  public:
    /// The mesh of `instance`, uploaded on first use, marked used in `frame`. With
    /// `skin_on_gpu`, a skinned pose (MeshInstance::joint_matrices) gets its scene's bind mesh
    /// with joints and weights, uploaded once for every pose (GpuMesh::skinned); otherwise the
    /// pose itself, uploaded anew each time it changes.
    const GpuMesh& get(const scene::MeshInstance& instance, std::uint64_t frame, bool skin_on_gpu);
    /// The object-space box of what `instance` draws now. A pose's is its own, not its bind
    /// mesh's (which says nothing of where a walking figure's arms are): computed once per
    /// pose, without uploading it, and forgotten as soon as a frame does not use it.
    const Bounds& bounds(const scene::MeshInstance& instance, std::uint64_t frame);
    /// Frees meshes no entity has drawn for a while, and textures no mesh uses any more.
    void evict(std::uint64_t frame);
    /// The 1x1 white texture untextured primitives sample.
    GLuint white_texture() { return textures_.white(); }

    [[nodiscard]] std::size_t size() const { return meshes_.size(); }
    [[nodiscard]] std::uint64_t uploads() const { return uploads_; }

  private:
    static constexpr std::uint64_t kEvictAfterFrames = 120;
    struct PoseBounds {
        std::shared_ptr<const scene::Mesh> posed;  ///< keeps the key's address unique
        Bounds bounds;
        std::uint64_t last_used = 0;
    };
    std::map<const scene::Mesh*, GpuMesh> meshes_;
    std::map<const scene::Mesh*, PoseBounds> pose_bounds_;
    MaterialTextures textures_;
    std::uint64_t uploads_ = 0;
};

}  // namespace luxel::renderer
