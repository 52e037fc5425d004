// Meshes: attributes, indices and primitive modes, turned into checked triangle lists.

#include <cmath>
#include <numeric>
#include <optional>

#include <tiny_gltf.h>

#include "gltf_internal.hpp"

namespace luxel::scene::gltf_detail {
namespace {

/// The attribute's accessor index (unchecked), or nothing when the primitive has none.
std::optional<int> attribute(const tinygltf::Primitive& primitive, const char* name) {
    const auto found = primitive.attributes.find(name);
    return found == primitive.attributes.end() ? std::nullopt : std::optional(found->second);
}

template <typename Vec>
std::vector<Vec> as_vectors(const std::vector<float>& flat) {
    constexpr auto n = static_cast<std::size_t>(Vec::length());
    std::vector<Vec> out(flat.size() / n);
    for (std::size_t i = 0; i < out.size(); ++i) {
        for (std::size_t c = 0; c < n; ++c) {
            out[i][static_cast<typename Vec::length_type>(c)] = flat[i * n + c];
        }
    }
    return out;
}

/// Triangles the primitive's mode makes from `count` vertices or indices.
std::uint64_t triangles_for(int mode, std::uint64_t count) {
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        return count / 3;
    }
    return count >= 3 ? count - 2 : 0;  // strips and fans
}

/// Rewrites strips and fans as triangle lists with the winding the glTF specification gives
/// (3.7.2.1): strip triangle i is (i, i+1+i%2, i+2-i%2), fan triangle i is (i+1, i+2, 0).
std::vector<std::uint32_t> as_triangle_list(int mode, std::vector<std::uint32_t> indices) {
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        indices.resize(indices.size() / 3 * 3);
        return indices;
    }
    std::vector<std::uint32_t> list;
    if (indices.size() < 3) {
        return list;
    }
    list.reserve((indices.size() - 2) * 3);
    for (std::size_t i = 0; i + 2 < indices.size(); ++i) {
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            list.push_back(indices[i]);
            list.push_back(indices[i + 1 + i % 2]);
            list.push_back(indices[i + 2 - i % 2]);
        } else {
            list.push_back(indices[i + 1]);
            list.push_back(indices[i + 2]);
            list.push_back(indices[0]);
        }
    }
    return list;
}

/// Drops triangles that repeat a vertex or have zero area; returns how many went.
std::size_t drop_degenerate(std::vector<std::uint32_t>& indices,
                            const std::vector<glm::vec3>& positions) {
    std::size_t kept = 0;
    for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
        const std::uint32_t a = indices[t];
        const std::uint32_t b = indices[t + 1];
        const std::uint32_t c = indices[t + 2];
        if (a == b || b == c || a == c) {
            continue;
        }
        const glm::vec3 normal =
            glm::cross(positions[b] - positions[a], positions[c] - positions[a]);
        if (!(glm::dot(normal, normal) > 0.0f)) {
            continue;
        }
        indices[kept++] = a;
        indices[kept++] = b;
        indices[kept++] = c;
    }
    const std::size_t dropped = indices.size() / 3 - kept / 3;
    indices.resize(kept);
    return dropped;
}

class PrimitiveImporter {
  public:
    PrimitiveImporter(ImportContext& context, const std::string& where)
        : context_(context), where_(where) {}

    /// The converted primitive, or nothing when it is skipped (with a warning).
    std::optional<Primitive> import(const tinygltf::Primitive& source) {
        const int mode = source.mode == -1 ? TINYGLTF_MODE_TRIANGLES : source.mode;
        if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
            mode != TINYGLTF_MODE_TRIANGLE_FAN) {
            context_.warn(where_ + ": mode " + std::to_string(mode) + " is not triangles; skipped");
            ++context_.scene().report.primitives_skipped;
            return std::nullopt;
        }
        const std::optional<int> position_accessor = attribute(source, "POSITION");
        if (!position_accessor) {
            context_.warn(where_ + ": has no POSITION attribute; skipped");
            ++context_.scene().report.primitives_skipped;
            return std::nullopt;
        }
        if (source.material < -1 ||
            source.material >= static_cast<int>(context_.scene().materials.size())) {
            context_.fail(where_ + ": material " + std::to_string(source.material) +
                          " out of range");
        }

        // Count first, read later: the triangle limit is enforced before any data is copied.
        const std::uint64_t vertex_count =
            accessor_count(context_, *position_accessor, "POSITION of " + where_);
        const std::uint64_t element_count =
            source.indices >= 0 ? accessor_count(context_, source.indices, "indices of " + where_)
                                : vertex_count;
        context_.count_triangles(triangles_for(mode, element_count), where_);

        Primitive primitive;
        primitive.material = source.material;
        primitive.positions = as_vectors<glm::vec3>(
            read_floats(context_, *position_accessor, 3, false, "POSITION of " + where_));
        primitive.normals = read_optional<glm::vec3>(source, "NORMAL", false, vertex_count);
        primitive.texcoords0 = read_optional<glm::vec2>(source, "TEXCOORD_0", true, vertex_count);
        primitive.texcoords1 = read_optional<glm::vec2>(source, "TEXCOORD_1", true, vertex_count);
        normalise_normals(primitive);
        read_skinning(source, vertex_count, primitive);

        std::vector<std::uint32_t> indices;
        if (source.indices >= 0) {
            indices = read_indices(context_, source.indices, "indices of " + where_);
        } else {
            indices.resize(primitive.positions.size());
            std::iota(indices.begin(), indices.end(), 0u);
        }
        if (mode == TINYGLTF_MODE_TRIANGLES && indices.size() % 3 != 0) {
            context_.warn(where_ + ": " + std::to_string(indices.size()) +
                          " indices are not a multiple of 3; the last " +
                          std::to_string(indices.size() % 3) + " ignored");
        }
        for (std::size_t k = 0; k < indices.size(); ++k) {
            if (indices[k] >= primitive.positions.size()) {
                context_.fail(where_ + ": index " + std::to_string(k) + " is " +
                              std::to_string(indices[k]) + ", out of range for " +
                              std::to_string(primitive.positions.size()) + " vertices");
            }
        }
        primitive.indices = as_triangle_list(mode, std::move(indices));
        context_.scene().report.degenerate_triangles_dropped +=
            drop_degenerate(primitive.indices, primitive.positions);
        if (primitive.indices.empty()) {
            context_.warn(where_ + ": no triangles left after dropping degenerate ones; skipped");
            return std::nullopt;
        }
        return primitive;
    }

  private:
    template <typename Vec>
    std::vector<Vec> read_optional(const tinygltf::Primitive& source, const char* name,
                                   bool allow_normalized, std::uint64_t vertex_count) {
        const std::optional<int> accessor = attribute(source, name);
        if (!accessor) {
            return {};
        }
        const std::string usage = std::string(name) + " of " + where_;
        const std::uint64_t count = accessor_count(context_, *accessor, usage);
        if (count != vertex_count) {
            context_.fail(where_ + ": " + name + " has " + std::to_string(count) +
                          " elements but POSITION has " + std::to_string(vertex_count));
        }
        return as_vectors<Vec>(
            read_floats(context_, *accessor, Vec::length(), allow_normalized, usage));
    }

    /// JOINTS_0 and WEIGHTS_0, both or neither, the weights normalised to sum to 1. A second
    /// set (more than four joints per vertex) is refused rather than dropped: without it the
    /// mesh would deform visibly wrong, and every exporter can limit influences to four.
    void read_skinning(const tinygltf::Primitive& source, std::uint64_t vertex_count,
                       Primitive& primitive) {
        if (attribute(source, "JOINTS_1") || attribute(source, "WEIGHTS_1")) {
            context_.fail(where_ +
                          ": has JOINTS_1/WEIGHTS_1, more than four joints per vertex; luxel "
                          "reads four (export with at most four bone influences per vertex)");
        }
        const std::optional<int> joints = attribute(source, "JOINTS_0");
        const std::optional<int> weights = attribute(source, "WEIGHTS_0");
        if (!joints && !weights) {
            return;
        }
        if (!joints || !weights) {
            context_.fail(where_ + ": has " +
                          (joints ? "JOINTS_0 without WEIGHTS_0" : "WEIGHTS_0 without JOINTS_0"));
        }
        const std::string joints_usage = "JOINTS_0 of " + where_;
        if (accessor_count(context_, *joints, joints_usage) != vertex_count) {
            context_.fail(where_ + ": JOINTS_0 and POSITION have different counts");
        }
        primitive.weights = read_optional<glm::vec4>(source, "WEIGHTS_0", true, vertex_count);
        primitive.joints = read_joints(context_, *joints, joints_usage);
        for (std::size_t v = 0; v < primitive.weights.size(); ++v) {
            glm::vec4& w = primitive.weights[v];
            const float sum = w.x + w.y + w.z + w.w;
            if (!(w.x >= 0.0f && w.y >= 0.0f && w.z >= 0.0f && w.w >= 0.0f) || !(sum > 0.0f) ||
                !std::isfinite(sum)) {
                context_.fail(where_ + ": WEIGHTS_0 of vertex " + std::to_string(v) +
                              " are negative or do not have a finite sum above 0");
            }
            // glTF asks for weights that sum to 1, but quantised ones (8 or 16 bits) miss it by
            // up to a few units in the last place and hand-made files by more; a sum other than
            // 1 would pull the vertex towards the joints' origin or push it away.
            w /= sum;
        }
    }

    void normalise_normals(Primitive& primitive) {
        for (glm::vec3& normal : primitive.normals) {
            const float length = std::sqrt(glm::dot(normal, normal));
            if (!(length > 1e-12f)) {
                // A zero normal has no direction to restore; dropping the attribute lets the
                // renderer derive normals from the faces instead of shading with garbage.
                context_.warn(where_ + ": a normal has zero length; normals ignored");
                primitive.normals.clear();
                return;
            }
            normal /= length;
        }
    }

    ImportContext& context_;
    const std::string& where_;
};

}  // namespace

void import_meshes(ImportContext& context) {
    const tinygltf::Model& model = context.model();
    Scene& scene = context.scene();
    scene.meshes.reserve(model.meshes.size());
    for (std::size_t m = 0; m < model.meshes.size(); ++m) {
        const tinygltf::Mesh& source = model.meshes[m];
        Mesh mesh;
        mesh.name = source.name;
        for (std::size_t p = 0; p < source.primitives.size(); ++p) {
            const std::string where =
                label("mesh", m, source.name) + " primitive " + std::to_string(p);
            PrimitiveImporter importer(context, where);
            if (std::optional<Primitive> primitive = importer.import(source.primitives[p])) {
                mesh.primitives.push_back(std::move(*primitive));
            }
        }
        scene.meshes.push_back(std::move(mesh));
    }
}

}  // namespace luxel::scene::gltf_detail
