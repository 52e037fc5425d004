// The engine-side scene: transforms, the dynamic rule, material classes, and validate().

#include <numbers>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "luxel/runtime/error.hpp"
#include "luxel/scene/scene.hpp"
#include "test_scenes.hpp"

namespace {

using luxel::scene::Scene;

/// root -> child -> grandchild, plus a second root.
Scene chain() {
    Scene scene;
    scene.nodes.resize(4);
    scene.nodes[0].children = {1};
    scene.nodes[1].parent = 0;
    scene.nodes[1].children = {2};
    scene.nodes[2].parent = 1;
    scene.roots = {0, 3};
    scene.nodes[0].translation = {1, 0, 0};
    scene.nodes[1].rotation = glm::angleAxis(std::numbers::pi_v<float> / 2.0f, glm::vec3(0, 0, 1));
    scene.nodes[2].translation = {2, 0, 0};
    scene.nodes[2].scale = {3, 3, 3};
    return scene;
}

void expect_invalid(const Scene& scene, const std::string& problem) {
    try {
        scene.validate();
        FAIL() << "validate() accepted a scene with: " << problem;
    } catch (const luxel::Error& e) {
        EXPECT_NE(std::string(e.what()).find(problem), std::string::npos) << e.what();
    }
}

TEST(Scene, LocalMatrixIsTranslateRotateScale) {
    luxel::scene::Node node;
    node.translation = {1, 2, 3};
    node.rotation = glm::angleAxis(std::numbers::pi_v<float> / 2.0f, glm::vec3(0, 1, 0));
    node.scale = {2, 2, 2};
    const glm::vec4 p = node.local_matrix() * glm::vec4(1, 0, 0, 1);
    // Scale to (2,0,0), rotate about y to (0,0,-2), translate.
    EXPECT_NEAR(p.x, 1.0f, 1e-6f);
    EXPECT_NEAR(p.y, 2.0f, 1e-6f);
    EXPECT_NEAR(p.z, 1.0f, 1e-6f);
}

TEST(Scene, WorldMatricesComposeParents) {
    const Scene scene = chain();
    const std::vector<glm::mat4> world = scene.world_matrices();
    ASSERT_EQ(world.size(), 4u);
    // The grandchild's origin: (2,0,0) rotated 90 degrees about z to (0,2,0), plus (1,0,0).
    const glm::vec4 origin = world[2] * glm::vec4(0, 0, 0, 1);
    EXPECT_NEAR(origin.x, 1.0f, 1e-6f);
    EXPECT_NEAR(origin.y, 2.0f, 1e-6f);
    EXPECT_EQ(world[3], glm::mat4(1.0f));
    Scene cyclic = chain();
    cyclic.nodes[0].parent = 2;
    EXPECT_THROW((void)cyclic.world_matrices(), luxel::Error);
}

TEST(Scene, DynamicFollowsAnimationsFlagsAndAncestors) {
    Scene scene = chain();
    EXPECT_FALSE(scene.is_dynamic(2));
    luxel::scene::Animation animation;
    animation.samplers.push_back({{0.0f, 1.0f}, {glm::vec4(0.0f), glm::vec4(1.0f)}, {}});
    animation.channels.push_back({1, luxel::scene::AnimatedProperty::Translation, 0});
    scene.animations.push_back(animation);
    EXPECT_FALSE(scene.is_dynamic(0));
    EXPECT_TRUE(scene.is_dynamic(1));
    EXPECT_TRUE(scene.is_dynamic(2));  // moved by its animated parent
    scene.nodes[2].flags.dynamic = false;
    EXPECT_FALSE(scene.is_dynamic(2));  // an explicit flag wins
    scene.nodes[3].flags.dynamic = true;
    EXPECT_TRUE(scene.is_dynamic(3));
    scene.animations.clear();
    scene.nodes[0].flags.dynamic = true;
    EXPECT_TRUE(scene.is_dynamic(1));  // a game-moved ancestor moves its children
    EXPECT_FALSE(scene.is_dynamic(-1));
    EXPECT_FALSE(scene.is_dynamic(99));
}

TEST(Scene, MaterialClasses) {
    luxel::scene::Material material;
    EXPECT_FALSE(material.is_emissive());
    EXPECT_FALSE(material.is_specular());  // glTF default: metallic 1, roughness 1
    material.emissive = {0.0f, 0.5f, 0.0f};
    material.emissive_strength = 4.0f;
    EXPECT_TRUE(material.is_emissive());
    EXPECT_EQ(material.emitted_radiance(), glm::vec3(0.0f, 2.0f, 0.0f));
    material.roughness = 0.05f;
    EXPECT_TRUE(material.is_specular());  // a mirror
    material.metallic = 0.5f;
    EXPECT_FALSE(material.is_specular());
    material.transmission = 0.3f;
    EXPECT_TRUE(material.is_specular());  // glass
}

TEST(Scene, ValidateAcceptsTheTestScenes) {
    EXPECT_NO_THROW(luxel::testing::box_room().validate());
    EXPECT_NO_THROW(luxel::testing::single_triangle().validate());
    EXPECT_NO_THROW(chain().validate());
    EXPECT_EQ(luxel::testing::grid(4).triangle_count(), 32u);
}

TEST(Scene, ValidateNamesEachBrokenInvariant) {
    Scene scene = chain();
    scene.nodes[1].parent = 3;
    expect_invalid(scene, "names another parent");
    scene = chain();
    scene.nodes[0].parent = 2;
    scene.nodes[2].children = {0};
    scene.roots = {3};
    expect_invalid(scene, "cycle");
    scene = chain();
    scene.roots.push_back(1);
    expect_invalid(scene, "root 1");
    scene = chain();
    scene.nodes[0].mesh = 0;
    expect_invalid(scene, "mesh 0 out of range");
    scene = chain();
    scene.nodes[0].rotation = glm::quat(0.0f, 0.0f, 0.0f, 0.0f);
    expect_invalid(scene, "zero quaternion");

    scene = luxel::testing::single_triangle();
    scene.meshes[0].primitives[0].positions[1].x = std::numeric_limits<float>::quiet_NaN();
    expect_invalid(scene, "not finite");
    scene = luxel::testing::single_triangle();
    scene.meshes[0].primitives[0].normals = {glm::vec3(0, 0, 1)};
    expect_invalid(scene, "do not match");
    scene = luxel::testing::single_triangle();
    scene.meshes[0].primitives[0].indices.push_back(0);
    expect_invalid(scene, "not a multiple of 3");

    scene = luxel::testing::box_room();
    scene.materials[0].base_color.r = 1.5f;
    expect_invalid(scene, "must be in [0, 1]");
    scene = luxel::testing::box_room();
    scene.images[0].mime_type = "image/jpeg";  // PNG bytes
    expect_invalid(scene, "PNG or JPEG");
    scene = luxel::testing::box_room();
    scene.lights[1].inner_cone_angle = 1.0f;
    expect_invalid(scene, "cone angles");
    scene = luxel::testing::box_room();
    scene.cameras[2].zfar.reset();  // orthographic needs a far plane
    expect_invalid(scene, "projection");
    scene = luxel::testing::box_room();
    scene.animations[0].samplers[0].times[1] = 0.0f;
    expect_invalid(scene, "increase strictly");
    scene = luxel::testing::box_room();
    scene.animations[0].samplers[1].values.pop_back();
    expect_invalid(scene, "values for");
    scene = luxel::testing::box_room();
    scene.animations[0].channels.push_back(scene.animations[0].channels[0]);
    expect_invalid(scene, "another channel");
}

}  // namespace
