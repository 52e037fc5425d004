// Skins (glTF 3.7.3): joints, inverse bind matrices, JOINTS_0/WEIGHTS_0 read and checked; a
// skinned mesh placed by its joints alone; linear blend skinning of positions and normals; the
// writer keeping all of it; and every malformed skin refused with its reason.

#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "gltf_test_files.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/scene/gltf.hpp"
#include "luxel/scene/skin.hpp"

namespace {

using luxel::testing::bytes_of;
using luxel::testing::GltfBuilder;
using nlohmann::json;

constexpr int kFloat = 5126;
constexpr int kUnsignedByte = 5121;
constexpr int kUnsignedShort = 5123;

/// A triangle skinned to two joints: vertex 0 to joint 0 alone, vertex 1 to joint 1 alone,
/// vertex 2 half and half (given as 0.5/0.3, which the loader normalises to 0.625/0.375).
/// Node 0 holds mesh and skin and is moved 5 m along z, which glTF says to ignore; nodes 1 and
/// 2 are the joints, at x = 0 and x = 2. Inverse bind matrices are identity for joint 0 and a
/// move of -2 along x for joint 1, so the bind pose is where the vertices are written.
GltfBuilder skinned_triangle() {
    GltfBuilder file;
    const std::vector<float> positions = {0, 0, 0, 2, 0, 0, 1, 1, 0};
    const std::vector<std::uint8_t> joints = {0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0};
    const std::vector<float> weights = {1, 0, 0, 0, 1, 0, 0, 0, 0.5f, 0.3f, 0, 0};
    std::vector<float> inverse_bind(32, 0.0f);
    for (int k = 0; k < 4; ++k) {
        inverse_bind[static_cast<std::size_t>(k * 5)] = 1.0f;
        inverse_bind[static_cast<std::size_t>(16 + k * 5)] = 1.0f;
    }
    inverse_bind[16 + 12] = -2.0f;  // column 3, row 0 of the second matrix
    json primitive;
    primitive["attributes"]["POSITION"] =
        file.add_accessor(file.add_view(positions), kFloat, 3, "VEC3");
    primitive["attributes"]["JOINTS_0"] =
        file.add_accessor(file.add_view(joints), kUnsignedByte, 3, "VEC4");
    primitive["attributes"]["WEIGHTS_0"] =
        file.add_accessor(file.add_view(weights), kFloat, 3, "VEC4");
    file.document["meshes"].push_back({{"primitives", {primitive}}});
    file.document["nodes"] = {
        {{"name", "figure"}, {"mesh", 0}, {"skin", 0}, {"translation", {0, 0, 5}}},
        {{"name", "joint a"}},
        {{"name", "joint b"}, {"translation", {2, 0, 0}}},
    };
    file.document["skins"] = {
        {{"joints", {1, 2}},
         {"inverseBindMatrices",
          file.add_accessor(file.add_view(inverse_bind), kFloat, 2, "MAT4")}}};
    file.document["scenes"] = {{{"nodes", {0, 1, 2}}}};
    file.document["scene"] = 0;
    return file;
}

luxel::scene::Scene load(const GltfBuilder& file) {
    return luxel::scene::load_gltf_from_memory(bytes_of(file.text()), "skinned.gltf");
}

std::string load_error(const GltfBuilder& file) {
    try {
        (void)load(file);
    } catch (const luxel::Error& e) {
        return e.what();
    }
    return "(loaded)";
}

void expect_near(const glm::vec3& a, const glm::vec3& b, float tolerance = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

TEST(Skins, AreLoadedWithWeightsSummingToOne) {
    const luxel::scene::Scene scene = load(skinned_triangle());
    ASSERT_EQ(scene.skins.size(), 1u);
    EXPECT_EQ(scene.skins[0].joints, (std::vector<int>{1, 2}));
    ASSERT_EQ(scene.skins[0].inverse_bind_matrices.size(), 2u);
    EXPECT_EQ(scene.skins[0].inverse_bind_matrices[1][3][0], -2.0f);
    EXPECT_EQ(scene.nodes[0].skin, 0);
    const luxel::scene::Primitive& primitive = scene.meshes[0].primitives[0];
    ASSERT_EQ(primitive.joints.size(), 3u);
    EXPECT_EQ(primitive.joints[1], glm::u16vec4(1, 0, 0, 0));
    EXPECT_NEAR(primitive.weights[2].x, 0.625f, 1e-6f);
    EXPECT_NEAR(primitive.weights[2].y, 0.375f, 1e-6f);
    // A skinned node moves with its joints: never light-mapped as static geometry.
    EXPECT_TRUE(scene.is_dynamic(0));
    EXPECT_FALSE(scene.is_dynamic(1));
}

TEST(Skins, PlaceTheMeshByItsJointsAloneNotByItsNode) {
    const luxel::scene::Scene scene = load(skinned_triangle());
    std::vector<glm::mat4> world = scene.world_matrices();
    const auto joints = luxel::scene::joint_matrices(scene.skins[0], world);
    // In the bind pose every vertex stays where the file wrote it: node 0's 5 m along z is
    // ignored, as glTF says.
    const luxel::scene::Mesh rest = luxel::scene::posed_mesh(scene.meshes[0], joints);
    expect_near(rest.primitives[0].positions[0], {0, 0, 0});
    expect_near(rest.primitives[0].positions[1], {2, 0, 0});
    expect_near(rest.primitives[0].positions[2], {1, 1, 0});

    // Joint b lifted 1 m: vertex 1 follows all the way, vertex 2 by its weight 0.375.
    world[2] = glm::translate(glm::mat4(1.0f), glm::vec3(2, 1, 0));
    const luxel::scene::Mesh lifted = luxel::scene::posed_mesh(
        scene.meshes[0], luxel::scene::joint_matrices(scene.skins[0], world));
    expect_near(lifted.primitives[0].positions[0], {0, 0, 0});
    expect_near(lifted.primitives[0].positions[1], {2, 1, 0});
    expect_near(lifted.primitives[0].positions[2], {1, 1.375f, 0});
    // Everything but positions and normals as bound.
    EXPECT_EQ(lifted.primitives[0].indices, scene.meshes[0].primitives[0].indices);
    EXPECT_EQ(lifted.primitives[0].joints, scene.meshes[0].primitives[0].joints);
}

TEST(Skins, NormalsFollowTheInverseTransposeAndNeverVanish) {
    luxel::scene::Primitive bind;
    bind.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const glm::vec3 diagonal = glm::normalize(glm::vec3(1, 1, 0));
    bind.normals = {diagonal, diagonal, diagonal};
    bind.joints.assign(3, glm::u16vec4(0));
    bind.weights.assign(3, glm::vec4(1, 0, 0, 0));
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;

    // Stretched 4x along x: a surface normal (1,1) leans towards y, (1/4, 1) normalised, not
    // towards x as a plain matrix product would lean it.
    const std::vector<glm::mat4> stretched = {glm::scale(glm::mat4(1.0f), glm::vec3(4, 1, 1))};
    luxel::scene::skin_primitive(bind, stretched, positions, normals);
    expect_near(positions[1], {4, 0, 0});
    expect_near(normals[0], glm::normalize(glm::vec3(0.25f, 1, 0)));

    // Mirrored in x: the normal mirrors with the surface and keeps unit length.
    const std::vector<glm::mat4> mirrored = {glm::scale(glm::mat4(1.0f), glm::vec3(-1, 1, 1))};
    luxel::scene::skin_primitive(bind, mirrored, positions, normals);
    expect_near(normals[0], glm::normalize(glm::vec3(-1, 1, 0)));

    // A joint scaled to nothing collapses the vertices; the normals keep their bind direction
    // instead of becoming zero or NaN.
    const std::vector<glm::mat4> collapsed = {glm::scale(glm::mat4(1.0f), glm::vec3(0.0f))};
    luxel::scene::skin_primitive(bind, collapsed, positions, normals);
    expect_near(positions[2], {0, 0, 0});
    expect_near(normals[2], diagonal);
}

TEST(Skins, SurviveARoundTripThroughTheWriter) {
    const luxel::scene::Scene scene = load(skinned_triangle());
    for (const auto container :
         {luxel::scene::GltfContainer::Binary, luxel::scene::GltfContainer::EmbeddedText}) {
        const luxel::scene::Scene again = luxel::scene::load_gltf_from_memory(
            luxel::scene::save_gltf_to_memory(scene, container), "again.glb");
        ASSERT_EQ(again.skins.size(), 1u);
        EXPECT_EQ(again.skins[0].joints, scene.skins[0].joints);
        EXPECT_EQ(again.skins[0].inverse_bind_matrices, scene.skins[0].inverse_bind_matrices);
        EXPECT_EQ(again.nodes[0].skin, 0);
        EXPECT_EQ(again.meshes[0].primitives[0].joints, scene.meshes[0].primitives[0].joints);
        EXPECT_EQ(again.meshes[0].primitives[0].weights, scene.meshes[0].primitives[0].weights);
    }
}

struct HostileSkin {
    const char* name;
    std::function<void(GltfBuilder&)> mutate;
    const char* reason;
};

TEST(Skins, MalformedSkinsAreRefusedWithTheirReason) {
    const auto attributes = [](GltfBuilder& file) -> json& {
        return file.document["meshes"][0]["primitives"][0]["attributes"];
    };
    const std::vector<HostileSkin> cases = {
        {"a second set of joints",
         [&](GltfBuilder& f) {
             attributes(f)["JOINTS_1"] = attributes(f)["JOINTS_0"];
             attributes(f)["WEIGHTS_1"] = attributes(f)["WEIGHTS_0"];
         },
         "more than four joints per vertex"},
        {"weights without joints", [&](GltfBuilder& f) { attributes(f).erase("JOINTS_0"); },
         "WEIGHTS_0 without JOINTS_0"},
        {"joints as floats",
         [&](GltfBuilder& f) {
             const std::vector<float> joints(12, 0.0f);
             attributes(f)["JOINTS_0"] = f.add_accessor(f.add_view(joints), kFloat, 3, "VEC4");
         },
         "components are not allowed here"},
        {"a vertex naming a joint the skin lacks",
         [&](GltfBuilder& f) {
             const std::vector<std::uint16_t> joints = {0, 0, 0, 0, 7, 0, 0, 0, 0, 1, 0, 0};
             attributes(f)["JOINTS_0"] =
                 f.add_accessor(f.add_view(joints), kUnsignedShort, 3, "VEC4");
         },
         "names joint 7, but skin 0 has 2"},
        {"weights summing to zero",
         [&](GltfBuilder& f) {
             const std::vector<float> weights = {1, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0};
             attributes(f)["WEIGHTS_0"] = f.add_accessor(f.add_view(weights), kFloat, 3, "VEC4");
         },
         "WEIGHTS_0 of vertex 1 are negative or do not have a finite sum above 0"},
        {"a negative weight",
         [&](GltfBuilder& f) {
             const std::vector<float> weights = {1, 0, 0, 0, 2, -1, 0, 0, 0, 1, 0, 0};
             attributes(f)["WEIGHTS_0"] = f.add_accessor(f.add_view(weights), kFloat, 3, "VEC4");
         },
         "are negative or do not have"},
        {"a joint out of range", [](GltfBuilder& f) { f.document["skins"][0]["joints"][1] = 9; },
         "joint 9 out of range"},
        {"a joint twice", [](GltfBuilder& f) { f.document["skins"][0]["joints"][1] = 1; },
         "lists node 1 twice"},
        {"no joints", [](GltfBuilder& f) { f.document["skins"][0]["joints"] = json::array(); },
         "has no joints"},
        {"fewer matrices than joints",
         [](GltfBuilder& f) {
             f.document["skins"][0]["joints"] = {1, 2, 0};
         },
         "2 matrices for 3 joints"},
        {"matrices of the wrong type",
         [](GltfBuilder& f) {
             const std::vector<float> values(8, 0.0f);
             f.document["skins"][0]["inverseBindMatrices"] =
                 f.add_accessor(f.add_view(values), kFloat, 2, "VEC4");
         },
         "expected MAT4"},
        {"a huge inverse bind matrix",
         [](GltfBuilder& f) {
             std::vector<float> values(32, 0.0f);
             for (int k = 0; k < 4; ++k) {
                 values[static_cast<std::size_t>(k * 5)] = 1e30f;
                 values[static_cast<std::size_t>(16 + k * 5)] = 1.0f;
             }
             f.document["skins"][0]["inverseBindMatrices"] =
                 f.add_accessor(f.add_view(values), kFloat, 2, "MAT4");
         },
         "inverse bind matrix 0 scales by more than 1e6"},
        {"a skin out of range", [](GltfBuilder& f) { f.document["nodes"][0]["skin"] = 3; },
         "skin 3 out of range"},
        {"a skin without a mesh", [](GltfBuilder& f) { f.document["nodes"][1]["skin"] = 0; },
         "has a skin but no mesh"},
        {"a skinned mesh without joints",
         [&](GltfBuilder& f) {
             attributes(f).erase("JOINTS_0");
             attributes(f).erase("WEIGHTS_0");
         },
         "has no JOINTS_0 and WEIGHTS_0"},
        {"a skeleton out of range", [](GltfBuilder& f) { f.document["skins"][0]["skeleton"] = 40; },
         "skeleton 40 out of range"},
    };
    for (const HostileSkin& hostile : cases) {
        GltfBuilder file = skinned_triangle();
        hostile.mutate(file);
        const std::string message = load_error(file);
        EXPECT_NE(message.find("skinned.gltf"), std::string::npos)
            << hostile.name << ": " << message;
        EXPECT_NE(message.find(hostile.reason), std::string::npos)
            << hostile.name << ": " << message;
    }
}

TEST(Skins, ValidateRefusesWhatTheLoaderWouldNeverMake) {
    const luxel::scene::Scene good = load(skinned_triangle());
    const auto invalid = [&](const std::function<void(luxel::scene::Scene&)>& change) {
        luxel::scene::Scene scene = good;
        change(scene);
        EXPECT_THROW(scene.validate(), luxel::Error);
    };
    invalid([](auto& s) { s.skins[0].inverse_bind_matrices.pop_back(); });
    invalid([](auto& s) { s.skins[0].inverse_bind_matrices[0][1][1] = NAN; });
    invalid([](auto& s) { s.skins[0].inverse_bind_matrices[0][3][2] = 2e6f; });
    invalid([](auto& s) { s.meshes[0].primitives[0].weights[0] = glm::vec4(0.5f, 0, 0, 0); });
    invalid([](auto& s) { s.meshes[0].primitives[0].joints.pop_back(); });
    invalid([](auto& s) { s.meshes[0].primitives[0].joints[0].w = 2; });
    invalid([](auto& s) { s.nodes[0].skin = 1; });
    EXPECT_NO_THROW(good.validate());
}

}  // namespace
