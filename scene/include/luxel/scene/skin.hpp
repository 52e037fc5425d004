#pragma once

#include <span>
#include <string>
#include <vector>

#include <glm/ext/vector_uint4_sized.hpp>
#include <glm/glm.hpp>

/// Skins: glTF's skeletal deformation (specification 3.7.3). A skinned mesh's vertices are
/// placed by its joints alone: vertex v with joints j0..j3 and weights w0..w3 lands at
/// sum_k w_k * world(j_k) * inverse_bind(j_k) * v, in world space, whatever the transform of the
/// node that holds the mesh (linear blend skinning).
namespace luxel::scene {

struct Primitive;
struct Mesh;

struct Skin {
    std::string name;
    /// The nodes that deform the mesh, distinct; JOINTS_0 values index this list.
    std::vector<int> joints;
    /// One per joint: from the mesh's bind-pose space into the joint's own space (identity when
    /// the file gives none, as glTF says).
    std::vector<glm::mat4> inverse_bind_matrices;
    /// The skeleton's root node, or -1. glTF gives it as a hint only; skinning never reads it.
    int skeleton = -1;
};

/// The matrix each joint applies to a vertex bound to it alone: world(joint) * inverse_bind.
/// `node_world` holds every node's local-to-world matrix in the current pose.
[[nodiscard]] std::vector<glm::mat4> joint_matrices(const Skin& skin,
                                                    std::span<const glm::mat4> node_world);

/// Linear blend skinning of one primitive (with joints and weights) into world space:
/// positions, and normals (when the primitive has them) through the inverse transpose of each
/// vertex's blended matrix. A vertex whose blended matrix has no inverse (joints scaled to
/// zero) keeps its bind-pose normal direction, so no normal is ever zero or NaN.
void skin_primitive(const Primitive& bind, std::span<const glm::mat4> joint_matrices,
                    std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals);

/// A copy of `bind` in the pose `joint_matrices` give, every position and normal in world
/// space; indices, texture coordinates, materials, joints and weights as they were.
[[nodiscard]] Mesh posed_mesh(const Mesh& bind, std::span<const glm::mat4> joint_matrices);

}  // namespace luxel::scene
