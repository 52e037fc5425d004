// Linear blend skinning in the vertex stage (docs/METHOD.md §8.7): a skinned mesh is uploaded
// once in its bind pose with JOINTS_0 and WEIGHTS_0, and each frame's joint matrices (a joint's
// world matrix times its inverse bind matrix) come in one storage buffer for all skinned meshes
// (renderer/src/joint_palette.hpp). The same sums as the CPU's scene::skin_primitive, which the
// ray scene traces, so the frame draws what the photons meet.

layout(location = 4) in uvec4 a_joints;
layout(location = 5) in vec4 a_weights;

layout(std430, binding = 20) readonly buffer JointMatrices {
    mat4 joint_matrices[];
};

// Index of this mesh's first joint matrix; -1: the mesh is not skinned (locations 4 and 5 are
// then not read). u_joint_count: its skin's joints; an index beyond them counts for nothing,
// as on the CPU.
uniform int u_first_joint = -1;
uniform int u_joint_count = 0;

bool skinned() {
    return u_first_joint >= 0;
}

mat4 skin_matrix() {
    mat4 m = mat4(0.0);
    for (int k = 0; k < 4; ++k) {
        // A zero weight may name any joint of the skin.
        if (a_weights[k] != 0.0 && int(a_joints[k]) < u_joint_count) {
            m += a_weights[k] * joint_matrices[u_first_joint + int(a_joints[k])];
        }
    }
    return m;
}

// The normal through the blended matrix: its cofactor matrix (the inverse transpose up to
// scale), signed by the determinant so a mirroring pose keeps normals facing out. A matrix
// without an inverse (joints scaled to nothing) leaves the bind normal, as the CPU does.
vec3 skin_normal(mat4 m, vec3 normal) {
    mat3 linear = mat3(m);
    float det = determinant(linear);
    if (!(abs(det) > 1e-30)) {
        return normal;
    }
    vec3 n = sign(det) * (transpose(inverse(linear)) * det) * normal;
    float len = length(n);
    return len > 1e-30 ? n / len : normal;
}
