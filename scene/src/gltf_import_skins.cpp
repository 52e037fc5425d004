// Skins: joints, inverse bind matrices, and the skinned nodes' meshes checked against them.

#include <algorithm>
#include <set>

#include <tiny_gltf.h>

#include "scene_checks.hpp"

#include "gltf_internal.hpp"

namespace luxel::scene::gltf_detail {
namespace {

Skin import_skin(const ImportContext& context, const tinygltf::Skin& source,
                 const std::string& where) {
    const std::size_t nodes = context.scene().nodes.size();
    Skin skin;
    skin.name = source.name;
    if (source.joints.empty()) {
        context.fail(where + ": has no joints");
    }
    std::set<int> seen;
    for (const int joint : source.joints) {
        if (joint < 0 || static_cast<std::size_t>(joint) >= nodes) {
            context.fail(where + ": joint " + std::to_string(joint) + " out of range (" +
                         std::to_string(nodes) + " nodes)");
        }
        if (!seen.insert(joint).second) {
            context.fail(where + ": lists node " + std::to_string(joint) + " twice");
        }
    }
    skin.joints = source.joints;
    if (source.skeleton < -1 ||
        (source.skeleton >= 0 && static_cast<std::size_t>(source.skeleton) >= nodes)) {
        context.fail(where + ": skeleton " + std::to_string(source.skeleton) + " out of range");
    }
    skin.skeleton = source.skeleton;
    if (source.inverseBindMatrices < 0) {
        skin.inverse_bind_matrices.assign(skin.joints.size(), glm::mat4(1.0f));
        return skin;
    }
    const std::string usage = "inverseBindMatrices of " + where;
    if (accessor_count(context, source.inverseBindMatrices, usage) != skin.joints.size()) {
        context.fail(where + ": " + usage + " has " +
                     std::to_string(accessor_count(context, source.inverseBindMatrices, usage)) +
                     " matrices for " + std::to_string(skin.joints.size()) + " joints");
    }
    const std::vector<float> values =
        read_floats(context, source.inverseBindMatrices, 16, false, usage);
    skin.inverse_bind_matrices.resize(skin.joints.size());
    for (std::size_t j = 0; j < skin.joints.size(); ++j) {
        glm::mat4& matrix = skin.inverse_bind_matrices[j];
        for (int c = 0; c < 4; ++c) {
            for (int r = 0; r < 4; ++r) {
                // glTF stores matrices column by column, as glm does.
                matrix[c][r] = values[j * 16 + static_cast<std::size_t>(c * 4 + r)];
            }
        }
        if (!detail::inverse_bind_within_bounds(matrix)) {
            context.fail(where + ": inverse bind matrix " + std::to_string(j) +
                         " scales by more than 1e6 or moves by more than 1e6 m");
        }
    }
    return skin;
}

}  // namespace

void import_skins(ImportContext& context) {
    const tinygltf::Model& model = context.model();
    Scene& scene = context.scene();
    scene.skins.reserve(model.skins.size());
    for (std::size_t s = 0; s < model.skins.size(); ++s) {
        scene.skins.push_back(
            import_skin(context, model.skins[s], label("skin", s, model.skins[s].name)));
    }
    // Every vertex of a skinned node's mesh must name joints of that node's skin.
    for (std::size_t i = 0; i < scene.nodes.size(); ++i) {
        const Node& node = scene.nodes[i];
        if (node.skin < 0) {
            continue;
        }
        const std::string where = label("node", i, node.name);
        const std::size_t joints = scene.skins[static_cast<std::size_t>(node.skin)].joints.size();
        const Mesh& mesh = scene.meshes[static_cast<std::size_t>(node.mesh)];
        for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
            const Primitive& primitive = mesh.primitives[p];
            if (primitive.joints.empty()) {
                context.fail(where + ": has skin " + std::to_string(node.skin) +
                             ", but primitive " + std::to_string(p) +
                             " of its mesh has no JOINTS_0 and WEIGHTS_0");
            }
            for (std::size_t v = 0; v < primitive.joints.size(); ++v) {
                const glm::u16vec4& j = primitive.joints[v];
                const std::uint16_t largest = std::max({j.x, j.y, j.z, j.w});
                if (largest >= joints) {
                    context.fail(where + ": vertex " + std::to_string(v) + " of primitive " +
                                 std::to_string(p) + " names joint " + std::to_string(largest) +
                                 ", but skin " + std::to_string(node.skin) + " has " +
                                 std::to_string(joints));
                }
            }
        }
    }
}

}  // namespace luxel::scene::gltf_detail
