#include "mesh_cache.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>

#include "luxel/scene/volume.hpp"

namespace luxel::renderer {
namespace {

struct Vertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec2 texcoord0;
    glm::vec2 lightmap_uv;
};
static_assert(sizeof(Vertex) == 40);

struct SkinVertex {
    glm::u16vec4 joints;
    glm::vec4 weights;
};
static_assert(sizeof(SkinVertex) == 24);

/// Whether the vertex stage can skin `mesh`: some primitive has joints and weights.
bool has_skin(const scene::Mesh& mesh) {
    return std::any_of(mesh.primitives.begin(), mesh.primitives.end(),
                       [](const scene::Primitive& p) {
                           return !p.joints.empty() && p.joints.size() == p.positions.size() &&
                                  p.weights.size() == p.positions.size();
                       });
}

Bounds bounds_of(const scene::Mesh& mesh) {
    Bounds bounds;
    for (const scene::Primitive& primitive : mesh.primitives) {
        for (const glm::vec3& p : primitive.positions) {
            bounds.add(p);
        }
    }
    return bounds;
}

/// The second vertex buffer of a mesh skinned on the GPU, bound at binding 1.
void upload_skin(const scene::Mesh& mesh, GpuMesh& gpu) {
    std::vector<SkinVertex> skin;
    for (const scene::Primitive& primitive : mesh.primitives) {
        const std::size_t count = primitive.positions.size();
        const bool skinned = primitive.joints.size() == count && primitive.weights.size() == count;
        // Scene::validate refuses a skinned mesh with a primitive without joints; zeros would
        // only keep the buffer's vertices in step (such a vertex collapses and draws nothing).
        for (std::size_t i = 0; i < count; ++i) {
            skin.push_back(skinned ? SkinVertex{primitive.joints[i], primitive.weights[i]}
                                   : SkinVertex{glm::u16vec4(0), glm::vec4(0.0f)});
        }
    }
    gpu.skin = gl::Buffer::create(std::max<std::size_t>(skin.size(), 1) * sizeof(SkinVertex),
                                  skin.empty() ? nullptr : skin.data(), 0);
    gpu.skinned = true;
    const GLuint vao = gpu.vertex_array.id();
    glVertexArrayVertexBuffer(vao, 1, gpu.skin.id(), 0, sizeof(SkinVertex));
    glEnableVertexArrayAttrib(vao, 4);
    glVertexArrayAttribIFormat(vao, 4, 4, GL_UNSIGNED_SHORT, offsetof(SkinVertex, joints));
    glVertexArrayAttribBinding(vao, 4, 1);
    glEnableVertexArrayAttrib(vao, 5);
    glVertexArrayAttribFormat(vao, 5, 4, GL_FLOAT, GL_FALSE, offsetof(SkinVertex, weights));
    glVertexArrayAttribBinding(vao, 5, 1);
    gl::check_error("MeshCache skin upload");
}

/// The texture a primitive samples for a material's image slot (`image_of` picks it), or null:
/// none without a textured material or without TEXCOORD_0 to sample it with.
template <class ImageOf>
std::shared_ptr<const gl::Texture> texture_of(const std::shared_ptr<const scene::Scene>& source,
                                              const scene::Primitive& primitive,
                                              MaterialTextures& textures, ImageOf image_of) {
    if (primitive.material < 0 ||
        static_cast<std::size_t>(primitive.material) >= source->materials.size() ||
        primitive.texcoords0.size() != primitive.positions.size() || primitive.positions.empty()) {
        return nullptr;
    }
    const int image = image_of(source->materials[static_cast<std::size_t>(primitive.material)]);
    if (image < 0) {
        return nullptr;
    }
    return textures.get(source, image);
}

/// Sum of the primitive's triangle areas (object space, m^2).
double triangle_area(const scene::Primitive& primitive) {
    double area = 0.0;
    const std::size_t count = primitive.positions.size();
    for (std::size_t t = 0; t + 2 < primitive.indices.size(); t += 3) {
        const std::uint32_t a = primitive.indices[t];
        const std::uint32_t b = primitive.indices[t + 1];
        const std::uint32_t c = primitive.indices[t + 2];
        if (a >= count || b >= count || c >= count) {
            continue;  // validated at load; never trusted for an index
        }
        const glm::dvec3 pa(primitive.positions[a]);
        area += 0.5 * glm::length(glm::cross(glm::dvec3(primitive.positions[b]) - pa,
                                             glm::dvec3(primitive.positions[c]) - pa));
    }
    return area;
}

/// GpuPrimitive::layers for every primitive, once the mesh's box is known.
void set_layers(const scene::Mesh& mesh, GpuMesh& gpu) {
    const glm::dvec3 extent = gpu.bounds.empty()
                                  ? glm::dvec3(0.0)
                                  : glm::dvec3(gpu.bounds.hi) - glm::dvec3(gpu.bounds.lo);
    const double face = std::max({extent.x * extent.y, extent.y * extent.z, extent.z * extent.x});
    for (std::size_t p = 0; p < gpu.primitives.size(); ++p) {
        const double area = triangle_area(mesh.primitives[p]);
        // A box with no face (a line, a point) holds only slivers: count each triangle once.
        const double layers =
            face > 1e-12 ? area / face : static_cast<double>(mesh.primitives[p].indices.size() / 3);
        gpu.primitives[p].layers = static_cast<float>(std::min(layers, 1e30));
    }
}

GpuMesh upload(const std::shared_ptr<const scene::Scene>& source, const scene::Mesh& mesh,
               MaterialTextures& textures) {
    std::vector<Vertex> vertices;
    std::vector<std::uint32_t> indices;
    GpuMesh gpu;
    gpu.source = source;
    for (const scene::Primitive& primitive : mesh.primitives) {
        GpuPrimitive range;
        range.base_vertex = static_cast<GLint>(vertices.size());
        range.first_index = indices.size();
        range.index_count = static_cast<GLsizei>(primitive.indices.size());
        range.material = primitive.material;
        const auto material = static_cast<std::size_t>(primitive.material);
        range.closed = primitive.material >= 0 && material < source->materials.size() &&
                       source->materials[material].transmission > 0.0f &&
                       scene::is_closed_surface(primitive);
        range.base_color = texture_of(source, primitive, textures,
                                      [](const scene::Material& m) { return m.base_color_image; });
        range.emissive = texture_of(source, primitive, textures,
                                    [](const scene::Material& m) { return m.emissive_image; });
        const std::size_t count = primitive.positions.size();
        const bool normals = primitive.normals.size() == count;
        const bool uv0 = primitive.texcoords0.size() == count;
        const bool uv1 = primitive.texcoords1.size() == count;
        for (std::size_t i = 0; i < count; ++i) {
            vertices.push_back({primitive.positions[i],
                                normals ? primitive.normals[i] : glm::vec3(0.0f),
                                uv0 ? primitive.texcoords0[i] : glm::vec2(0.0f),
                                uv1 ? primitive.texcoords1[i] : glm::vec2(0.0f)});
        }
        indices.insert(indices.end(), primitive.indices.begin(), primitive.indices.end());
        gpu.primitives.push_back(range);
    }
    gpu.bounds = bounds_of(mesh);
    set_layers(mesh, gpu);
    // Buffers need at least one byte; an empty mesh draws nothing.
    gpu.vertices = gl::Buffer::create(std::max<std::size_t>(vertices.size(), 1) * sizeof(Vertex),
                                      vertices.empty() ? nullptr : vertices.data(), 0);
    gpu.indices =
        gl::Buffer::create(std::max<std::size_t>(indices.size(), 1) * sizeof(std::uint32_t),
                           indices.empty() ? nullptr : indices.data(), 0);
    gpu.vertex_array = gl::VertexArray::create();
    const GLuint vao = gpu.vertex_array.id();
    glVertexArrayVertexBuffer(vao, 0, gpu.vertices.id(), 0, sizeof(Vertex));
    glVertexArrayElementBuffer(vao, gpu.indices.id());
    const std::array<std::pair<GLint, std::size_t>, 4> attributes = {{
        {3, offsetof(Vertex, position)},
        {3, offsetof(Vertex, normal)},
        {2, offsetof(Vertex, texcoord0)},
        {2, offsetof(Vertex, lightmap_uv)},
    }};
    for (GLuint location = 0; location < attributes.size(); ++location) {
        glEnableVertexArrayAttrib(vao, location);
        glVertexArrayAttribFormat(vao, location, attributes[location].first, GL_FLOAT, GL_FALSE,
                                  static_cast<GLuint>(attributes[location].second));
        glVertexArrayAttribBinding(vao, location, 0);
    }
    gl::check_error("MeshCache upload");
    return gpu;
}

}  // namespace

void draw_primitive(const GpuPrimitive& range) {
    glDrawElementsBaseVertex(GL_TRIANGLES, range.index_count, GL_UNSIGNED_INT,
                             reinterpret_cast<const void*>(static_cast<std::uintptr_t>(
                                 range.first_index * sizeof(std::uint32_t))),
                             range.base_vertex);
}

Bounds Bounds::transformed(const glm::mat4& matrix) const {
    Bounds out;
    if (empty()) {
        return out;
    }
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p((corner & 1) != 0 ? hi.x : lo.x, (corner & 2) != 0 ? hi.y : lo.y,
                          (corner & 4) != 0 ? hi.z : lo.z);
        out.add(glm::vec3(matrix * glm::vec4(p, 1.0f)));
    }
    return out;
}

bool Bounds::touches_sphere(const glm::vec3& centre, float radius) const {
    if (empty()) {
        return false;
    }
    const glm::vec3 nearest = glm::clamp(centre, lo, hi);
    const glm::vec3 d = nearest - centre;
    return glm::dot(d, d) <= radius * radius;
}

const GpuMesh& MeshCache::get(const scene::MeshInstance& instance, std::uint64_t frame,
                              bool skin_on_gpu) {
    const scene::Mesh* bind =
        skin_on_gpu && instance.joint_matrices
            ? &instance.source->meshes.at(static_cast<std::size_t>(instance.mesh))
            : nullptr;
    if (bind != nullptr && !has_skin(*bind)) {
        bind = nullptr;  // joint matrices without joints to apply them to: draw the pose
    }
    const scene::Mesh* key = bind != nullptr ? bind : &instance.geometry();
    auto found = meshes_.find(key);
    if (found == meshes_.end()) {
        GpuMesh gpu = upload(instance.source, *key, textures_);
        gpu.posed = bind != nullptr ? nullptr : instance.posed;
        found = meshes_.emplace(key, std::move(gpu)).first;
        ++uploads_;
    }
    // Also when an unskinned node drew the same mesh first (glTF lets a node without a skin
    // instance a mesh with joints).
    if (bind != nullptr && !found->second.skinned) {
        upload_skin(*bind, found->second);
    }
    found->second.last_used = frame;
    return found->second;
}

const Bounds& MeshCache::bounds(const scene::MeshInstance& instance, std::uint64_t frame) {
    if (!instance.posed) {
        return get(instance, frame, false).bounds;
    }
    auto found = pose_bounds_.find(instance.posed.get());
    if (found == pose_bounds_.end()) {
        found = pose_bounds_
                    .emplace(instance.posed.get(),
                             PoseBounds{instance.posed, bounds_of(*instance.posed), frame})
                    .first;
    }
    found->second.last_used = frame;
    return found->second.bounds;
}

void MeshCache::evict(std::uint64_t frame) {
    std::erase_if(meshes_, [&](const auto& entry) {
        // A pose the frame did not draw has been replaced by a newer one: its buffers would
        // otherwise pile up, one set per frame the figure moved.
        const std::uint64_t keep = entry.second.posed ? 0 : kEvictAfterFrames;
        return entry.second.last_used + keep < frame;
    });
    std::erase_if(pose_bounds_, [&](const auto& entry) { return entry.second.last_used < frame; });
    textures_.evict();
}

}  // namespace luxel::renderer
