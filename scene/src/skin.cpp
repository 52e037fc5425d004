#include "luxel/scene/skin.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "luxel/scene/scene.hpp"
#include "scene_checks.hpp"

namespace luxel::scene {
namespace {

/// How far a vertex's weights may sum from 1 in a valid scene: the loader normalises them, so
/// only float rounding remains (four terms).
constexpr float kWeightSumTolerance = 1e-4f;

}  // namespace

bool detail::inverse_bind_within_bounds(const glm::mat4& matrix) {
    // The bounds a node's world transform has (scene_transforms.cpp): a joint's world matrix
    // times this one then scales by at most 1e12 and moves by at most about 1e12 m, far
    // from float's overflow for any vertex a level holds.
    constexpr float kMaxScale = 1e6f;
    constexpr float kMaxReach = 1e6f;
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) {
            if (!std::isfinite(matrix[c][r])) {
                return false;
            }
        }
    }
    for (int c = 0; c < 3; ++c) {
        if (!(glm::length(glm::vec3(matrix[c])) <= kMaxScale)) {
            return false;
        }
    }
    return glm::length(glm::vec3(matrix[3])) <= kMaxReach;
}

namespace {

glm::mat4 blended_matrix(const glm::u16vec4& joints, const glm::vec4& weights,
                         std::span<const glm::mat4> matrices) {
    glm::mat4 blended(0.0f);
    for (int k = 0; k < 4; ++k) {
        // Scene::validate holds every joint index below the skin's joint count; a zero weight
        // may still name any of them.
        if (weights[k] != 0.0f && joints[k] < matrices.size()) {
            blended += weights[k] * matrices[joints[k]];
        }
    }
    return blended;
}

}  // namespace

std::vector<glm::mat4> joint_matrices(const Skin& skin, std::span<const glm::mat4> node_world) {
    std::vector<glm::mat4> matrices(skin.joints.size(), glm::mat4(1.0f));
    for (std::size_t j = 0; j < skin.joints.size(); ++j) {
        const int node = skin.joints[j];
        const glm::mat4 world = detail::in_range(node, node_world.size())
                                    ? node_world[static_cast<std::size_t>(node)]
                                    : glm::mat4(1.0f);
        matrices[j] =
            j < skin.inverse_bind_matrices.size() ? world * skin.inverse_bind_matrices[j] : world;
    }
    return matrices;
}

void skin_primitive(const Primitive& bind, std::span<const glm::mat4> joint_matrices,
                    std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals) {
    const std::size_t count = bind.positions.size();
    positions.resize(count);
    const bool with_normals = bind.normals.size() == count;
    normals.resize(with_normals ? count : 0);
    const bool skinned = bind.joints.size() == count && bind.weights.size() == count;
    for (std::size_t v = 0; v < count; ++v) {
        const glm::mat4 m = skinned
                                ? blended_matrix(bind.joints[v], bind.weights[v], joint_matrices)
                                : glm::mat4(1.0f);
        positions[v] = glm::vec3(m * glm::vec4(bind.positions[v], 1.0f));
        if (!with_normals) {
            continue;
        }
        // The inverse transpose up to scale is the cofactor matrix; its sign follows the
        // determinant's, so a mirroring pose keeps normals facing out.
        const glm::mat3 linear(m);
        const float det = glm::determinant(linear);
        glm::vec3 normal = bind.normals[v];
        if (std::isfinite(det) && std::abs(det) > 1e-30f) {
            const glm::mat3 cofactor = glm::transpose(glm::inverse(linear)) * det;
            const glm::vec3 n = (det < 0.0f ? -1.0f : 1.0f) * (cofactor * bind.normals[v]);
            const float length = glm::length(n);
            if (std::isfinite(length) && length > 1e-30f) {
                normal = n / length;
            }
        }
        normals[v] = normal;
    }
}

Mesh posed_mesh(const Mesh& bind, std::span<const glm::mat4> joint_matrices) {
    Mesh posed = bind;
    for (std::size_t p = 0; p < posed.primitives.size(); ++p) {
        Primitive& primitive = posed.primitives[p];
        skin_primitive(bind.primitives[p], joint_matrices, primitive.positions, primitive.normals);
    }
    return posed;
}

namespace detail {

void validate_skins(const Scene& scene) {
    for (std::size_t s = 0; s < scene.skins.size(); ++s) {
        const Skin& skin = scene.skins[s];
        const std::string where = "skin " + std::to_string(s) + quoted_name(skin.name);
        if (skin.joints.empty()) {
            invalid(where + ": has no joints");
        }
        std::vector<int> sorted = skin.joints;
        std::sort(sorted.begin(), sorted.end());
        if (!in_range(sorted.front(), scene.nodes.size()) ||
            !in_range(sorted.back(), scene.nodes.size())) {
            invalid(where + ": a joint is out of range (" + std::to_string(scene.nodes.size()) +
                    " nodes)");
        }
        if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) {
            invalid(where + ": lists a joint twice");
        }
        if (skin.inverse_bind_matrices.size() != skin.joints.size()) {
            invalid(where + ": " + std::to_string(skin.inverse_bind_matrices.size()) +
                    " inverse bind matrices for " + std::to_string(skin.joints.size()) + " joints");
        }
        for (const glm::mat4& matrix : skin.inverse_bind_matrices) {
            if (!detail::inverse_bind_within_bounds(matrix)) {
                invalid(where +
                        ": an inverse bind matrix is not finite, or scales by more than "
                        "1e6 or moves by more than 1e6 m");
            }
        }
        if (skin.skeleton != -1 && !in_range(skin.skeleton, scene.nodes.size())) {
            invalid(where + ": skeleton " + std::to_string(skin.skeleton) + " out of range");
        }
    }
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        for (std::size_t p = 0; p < scene.meshes[m].primitives.size(); ++p) {
            const Primitive& primitive = scene.meshes[m].primitives[p];
            const std::string where = "mesh " + std::to_string(m) +
                                      quoted_name(scene.meshes[m].name) + " primitive " +
                                      std::to_string(p);
            const std::size_t vertices = primitive.positions.size();
            if (primitive.joints.size() != primitive.weights.size() ||
                (!primitive.joints.empty() && primitive.joints.size() != vertices)) {
                invalid(where + ": joints and weights must both be absent or one per vertex");
            }
            for (const glm::vec4& w : primitive.weights) {
                const float sum = w.x + w.y + w.z + w.w;
                if (!(w.x >= 0.0f && w.y >= 0.0f && w.z >= 0.0f && w.w >= 0.0f) ||
                    !(std::abs(sum - 1.0f) <= kWeightSumTolerance)) {
                    invalid(where + ": joint weights must be at least 0 and sum to 1");
                }
            }
        }
    }
    for (std::size_t i = 0; i < scene.nodes.size(); ++i) {
        const Node& node = scene.nodes[i];
        if (node.skin == -1) {
            continue;
        }
        const std::string where = "node " + std::to_string(i) + quoted_name(node.name);
        if (!in_range(node.skin, scene.skins.size())) {
            invalid(where + ": skin " + std::to_string(node.skin) + " out of range");
        }
        if (!in_range(node.mesh, scene.meshes.size())) {
            invalid(where + ": has a skin but no mesh");
        }
        const std::size_t joints = scene.skins[static_cast<std::size_t>(node.skin)].joints.size();
        for (const Primitive& primitive :
             scene.meshes[static_cast<std::size_t>(node.mesh)].primitives) {
            if (primitive.joints.empty()) {
                invalid(where + ": its skin deforms mesh " + std::to_string(node.mesh) +
                        ", whose primitives need JOINTS_0 and WEIGHTS_0");
            }
            for (const glm::u16vec4& j : primitive.joints) {
                if (std::max({j.x, j.y, j.z, j.w}) >= joints) {
                    invalid(where + ": a vertex names joint " +
                            std::to_string(std::max({j.x, j.y, j.z, j.w})) + " of a skin with " +
                            std::to_string(joints) + " joints");
                }
            }
        }
    }
}

}  // namespace detail
}  // namespace luxel::scene
