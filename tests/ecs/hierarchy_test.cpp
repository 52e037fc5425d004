// Transform, the parent/child links and the TransformSystem.

#include <gtest/gtest.h>

#include <type_traits>
#include <vector>

#include <glm/gtc/constants.hpp>

#include "luxel/ecs/hierarchy.hpp"
#include "luxel/ecs/registry.hpp"
#include "luxel/ecs/transform.hpp"
#include "luxel/ecs/transform_system.hpp"
#include "test_components.hpp"

namespace luxel::ecs {
namespace {

using test::sorted;

// The links can only be made by the hierarchy functions.
static_assert(!std::is_constructible_v<Parent, Entity>);
static_assert(!std::is_constructible_v<Parent, Entity, std::uint32_t>);
static_assert(!std::is_copy_constructible_v<Parent> && !std::is_copy_assignable_v<Parent>);
static_assert(!std::is_constructible_v<Children, Entity>);

void expect_matrix_near(const glm::mat4& actual, const glm::mat4& expected,
                        float tolerance = 1e-4f) {
    for (int column = 0; column < 4; ++column) {
        for (int row = 0; row < 4; ++row) {
            EXPECT_NEAR(actual[column][row], expected[column][row], tolerance)
                << "column " << column << " row " << row;
        }
    }
}

glm::vec3 world_position(const Registry& registry, Entity entity) {
    return registry.get<WorldTransform>(entity).position();
}

Transform translated(float x, float y = 0.0f, float z = 0.0f) {
    Transform transform;
    transform.translation = glm::vec3(x, y, z);
    return transform;
}

Entity spawn(Registry& registry, const Transform& transform, Entity parent = null_entity) {
    const Entity entity = registry.create();
    registry.emplace<Transform>(entity, transform);
    if (!parent.is_null()) {
        set_parent(registry, entity, parent);
    }
    return entity;
}

// ---- Transform ----------------------------------------------------------------------------

TEST(Transform, MatrixAppliesScaleThenRotationThenTranslation) {
    Transform transform;
    transform.translation = glm::vec3(10, 0, 0);
    transform.rotation = glm::angleAxis(glm::half_pi<float>(), glm::vec3(0, 0, 1));
    transform.scale = glm::vec3(2, 3, 4);
    const glm::vec4 point = transform.matrix() * glm::vec4(1, 0, 0, 1);
    // (1,0,0) -> scaled (2,0,0) -> rotated 90 deg about z (0,2,0) -> translated (10,2,0).
    EXPECT_NEAR(point.x, 10.0f, 1e-5f);
    EXPECT_NEAR(point.y, 2.0f, 1e-5f);
    EXPECT_NEAR(point.z, 0.0f, 1e-5f);
    EXPECT_EQ(Transform{}.matrix(), glm::mat4(1.0f));
}

TEST(Transform, FromMatrixRecoversATrs) {
    Transform original;
    original.translation = glm::vec3(1, -2, 3);
    original.rotation = glm::normalize(glm::angleAxis(0.7f, glm::normalize(glm::vec3(1, 2, 3))));
    original.scale = glm::vec3(0.5f, 2.0f, 3.0f);
    const Transform recovered = Transform::from_matrix(original.matrix());
    expect_matrix_near(recovered.matrix(), original.matrix());
    EXPECT_NEAR(recovered.scale.y, 2.0f, 1e-5f);

    Transform mirrored = original;
    mirrored.scale.z = -3.0f;
    const Transform recovered_mirror = Transform::from_matrix(mirrored.matrix());
    expect_matrix_near(recovered_mirror.matrix(), mirrored.matrix());
    EXPECT_LT(recovered_mirror.scale.z, 0.0f);
}

TEST(Transform, FromMatrixDropsShearButKeepsAValidRotation) {
    glm::mat4 sheared(1.0f);
    sheared[1][0] = 0.5f;  // y axis leans towards x
    sheared[3] = glm::vec4(4, 5, 6, 1);
    const Transform result = Transform::from_matrix(sheared);
    EXPECT_NEAR(glm::length(result.rotation), 1.0f, 1e-5f);
    EXPECT_EQ(result.translation, glm::vec3(4, 5, 6));
    EXPECT_NEAR(result.scale.x, 1.0f, 1e-5f);
}

// ---- Links --------------------------------------------------------------------------------

TEST(Hierarchy, LinksChildrenInAttachmentOrder) {
    Registry registry;
    const Entity root = registry.create();
    std::vector<Entity> kids;
    for (int i = 0; i < 5; ++i) {
        kids.push_back(registry.create());
        set_parent(registry, kids.back(), root);
    }
    EXPECT_EQ(parent_of(registry, kids[2]), root);
    EXPECT_EQ(parent_of(registry, root), null_entity);
    EXPECT_EQ(registry.get<Children>(root).size(), 5u);
    std::vector<Entity> listed(children_of(registry, root).begin(),
                               children_of(registry, root).end());
    EXPECT_EQ(listed, kids);

    remove_parent(registry, kids[2]);
    remove_parent(registry, kids[0]);
    set_parent(registry, kids[4], kids[4 - 1]);
    const std::vector<Entity> want{kids[1], kids[3]};
    listed.assign(children_of(registry, root).begin(), children_of(registry, root).end());
    EXPECT_EQ(listed, want);
    EXPECT_TRUE(is_ancestor_of(registry, root, kids[4]));
    EXPECT_FALSE(is_ancestor_of(registry, kids[4], root));
    EXPECT_FALSE(is_ancestor_of(registry, kids[0], kids[1]));
    EXPECT_TRUE(children_of(registry, kids[0]).empty());

    remove_parent(registry, kids[1]);
    remove_parent(registry, kids[3]);
    EXPECT_FALSE(registry.has<Children>(root)) << "an empty list is removed";
}

TEST(Hierarchy, CyclesAreRejectedAndChangeNothing) {
    Registry registry;
    const Entity a = registry.create();
    const Entity b = registry.create();
    const Entity c = registry.create();
    set_parent(registry, b, a);
    set_parent(registry, c, b);
    EXPECT_THROW(set_parent(registry, a, a), HierarchyCycleError);
    EXPECT_THROW(set_parent(registry, a, c), HierarchyCycleError);
    EXPECT_THROW(set_parent(registry, b, c), HierarchyCycleError);
    EXPECT_EQ(parent_of(registry, a), null_entity);
    EXPECT_EQ(parent_of(registry, b), a);
    EXPECT_EQ(parent_of(registry, c), b);
    try {
        set_parent(registry, a, c);
    } catch (const HierarchyCycleError& error) {
        EXPECT_NE(std::string(error.what()).find("descendant"), std::string::npos) << error.what();
    }
    set_parent(registry, c, a);  // moving to an ancestor is fine
    EXPECT_EQ(parent_of(registry, c), a);
}

TEST(Hierarchy, StaleHandlesAreRejected) {
    Registry registry;
    const Entity parent = registry.create();
    const Entity child = registry.create();
    const Entity gone = registry.create();
    registry.destroy(gone);
    EXPECT_THROW(set_parent(registry, child, gone), StaleEntityError);
    EXPECT_THROW(set_parent(registry, gone, parent), StaleEntityError);
    EXPECT_THROW(destroy_recursive(registry, gone), StaleEntityError);
    EXPECT_THROW((void)children_of(registry, gone), StaleEntityError);
}

TEST(Hierarchy, DirectRemovalOfLinksKeepsTheListsConsistent) {
    Registry registry;
    const Entity root = spawn(registry, translated(0, 10));
    const Entity first = spawn(registry, translated(1), root);
    const Entity second = spawn(registry, translated(2), root);
    const Entity third = spawn(registry, translated(3), root);

    registry.remove<Parent>(second);  // like remove_parent(KeepLocal)
    std::vector<Entity> listed(children_of(registry, root).begin(),
                               children_of(registry, root).end());
    EXPECT_EQ(listed, (std::vector<Entity>{first, third}));
    EXPECT_EQ(registry.get<Transform>(second).translation, glm::vec3(2, 0, 0));

    registry.remove<Children>(root);  // detaches the rest, keeping their world transforms
    EXPECT_EQ(parent_of(registry, first), null_entity);
    EXPECT_EQ(parent_of(registry, third), null_entity);
    EXPECT_EQ(registry.get<Transform>(third).translation, glm::vec3(3, 10, 0));
}

// ---- TransformSystem ----------------------------------------------------------------------

TEST(TransformSystem, ChildWorldIsParentWorldTimesLocal) {
    Registry registry;
    TransformSystem system(registry);
    Transform parent_local = translated(1);
    parent_local.rotation = glm::angleAxis(glm::half_pi<float>(), glm::vec3(0, 0, 1));
    const Entity parent = spawn(registry, parent_local);
    const Entity child = spawn(registry, translated(1), parent);
    const Entity grandchild = spawn(registry, translated(0, 0, 2), child);
    system.update();
    expect_matrix_near(registry.get<WorldTransform>(parent).matrix, parent_local.matrix());
    const glm::vec3 child_position = world_position(registry, child);
    EXPECT_NEAR(child_position.x, 1.0f, 1e-5f);
    EXPECT_NEAR(child_position.y, 1.0f, 1e-5f);
    expect_matrix_near(registry.get<WorldTransform>(grandchild).matrix,
                       compute_world_matrix(registry, grandchild));
    EXPECT_EQ(registry.get<Parent>(grandchild).depth(), 2u);
}

TEST(TransformSystem, UpdatesOnlyDirtySubtreesAndReportsOnlyWhatMoved) {
    Registry registry;
    TransformSystem system(registry);
    const Entity tree_a = spawn(registry, translated(0));
    const Entity tree_b = spawn(registry, translated(100));
    std::vector<Entity> under_a;
    std::vector<Entity> under_b;
    for (int i = 0; i < 10; ++i) {
        under_a.push_back(spawn(registry, translated(1), i == 0 ? tree_a : under_a.back()));
        under_b.push_back(spawn(registry, translated(1), tree_b));
    }
    system.update();
    EXPECT_EQ(system.last_visit_count(), 22u) << "the first update visits everything";

    Observer<WorldTransform> moved = registry.observe<WorldTransform>();
    system.update();
    EXPECT_EQ(system.last_visit_count(), 0u) << "nothing changed, nothing visited";

    registry.patch<Transform>(tree_a, [](Transform& t) { t.translation.y = 5; });
    system.update();
    EXPECT_EQ(system.last_visit_count(), 11u) << "tree_a and its chain of 10, not tree_b";
    std::vector<Entity> want = under_a;
    want.push_back(tree_a);
    EXPECT_EQ(sorted(std::vector<Entity>(moved.updated().begin(), moved.updated().end())),
              sorted(want));
    EXPECT_NEAR(world_position(registry, under_a.back()).y, 5.0f, 1e-5f);
    EXPECT_NEAR(world_position(registry, under_a.back()).x, 10.0f, 1e-5f);
    moved.clear();

    registry.patch<Transform>(under_b[3], [](Transform&) {});  // same value
    system.update();
    EXPECT_EQ(system.last_visit_count(), 1u);
    EXPECT_TRUE(moved.empty()) << "a world matrix that did not change is not reported";
}

TEST(TransformSystem, ReparentingKeepsLocalOrWorld) {
    Registry registry;
    TransformSystem system(registry);
    const Entity left = spawn(registry, translated(-10));
    const Entity right = spawn(registry, translated(10));
    const Entity child = spawn(registry, translated(1), left);
    const Entity grandchild = spawn(registry, translated(0, 1), child);
    system.update();
    EXPECT_NEAR(world_position(registry, grandchild).x, -9.0f, 1e-5f);

    set_parent(registry, child, right);  // KeepLocal: moves with its new parent
    system.update();
    EXPECT_NEAR(world_position(registry, child).x, 11.0f, 1e-5f);
    EXPECT_NEAR(world_position(registry, grandchild).x, 11.0f, 1e-5f);
    EXPECT_NEAR(world_position(registry, grandchild).y, 1.0f, 1e-5f);
    EXPECT_TRUE(children_of(registry, left).empty());

    set_parent(registry, child, left, ReparentMode::KeepWorld);
    system.update();
    EXPECT_NEAR(world_position(registry, child).x, 11.0f, 1e-4f);
    EXPECT_NEAR(registry.get<Transform>(child).translation.x, 21.0f, 1e-4f);
    EXPECT_EQ(parent_of(registry, child), left);

    remove_parent(registry, child, ReparentMode::KeepWorld);
    system.update();
    EXPECT_NEAR(world_position(registry, child).x, 11.0f, 1e-4f);
    remove_parent(registry, grandchild);  // KeepLocal: now relative to the world
    system.update();
    EXPECT_NEAR(world_position(registry, grandchild).x, 0.0f, 1e-5f);
}

TEST(TransformSystem, DestroyingAParentDetachesChildrenKeepingTheirWorld) {
    Registry registry;
    TransformSystem system(registry);
    Transform parent_local = translated(5, 0, 0);
    parent_local.rotation = glm::angleAxis(0.3f, glm::vec3(0, 1, 0));
    parent_local.scale = glm::vec3(2.0f);
    const Entity grandparent = spawn(registry, translated(0, 0, 7));
    const Entity parent = spawn(registry, parent_local, grandparent);
    const Entity child = spawn(registry, translated(1, 2, 3), parent);
    const Entity grandchild = spawn(registry, translated(0, 1, 0), child);
    const Entity sibling = spawn(registry, translated(-1), parent);
    system.update();
    const glm::mat4 child_world = registry.get<WorldTransform>(child).matrix;
    const glm::mat4 grandchild_world = registry.get<WorldTransform>(grandchild).matrix;

    registry.destroy(parent);
    EXPECT_EQ(parent_of(registry, child), null_entity);
    EXPECT_EQ(parent_of(registry, sibling), null_entity);
    EXPECT_EQ(parent_of(registry, grandchild), child) << "subtrees below stay intact";
    EXPECT_FALSE(registry.has<Children>(grandparent)) << "the parent left its own parent's list";
    system.update();
    expect_matrix_near(registry.get<WorldTransform>(child).matrix, child_world);
    expect_matrix_near(registry.get<WorldTransform>(grandchild).matrix, grandchild_world);
    EXPECT_EQ(registry.get<Parent>(grandchild).depth(), 1u);
}

TEST(TransformSystem, DestroyRecursiveTakesTheWholeSubtreeOnly) {
    Registry registry;
    TransformSystem system(registry);
    const Entity root = spawn(registry, translated(0));
    const Entity doomed = spawn(registry, translated(1), root);
    const Entity kept = spawn(registry, translated(2), root);
    std::vector<Entity> below;
    for (int i = 0; i < 20; ++i) {
        below.push_back(spawn(registry, translated(1), i % 2 == 0 ? doomed : below.back()));
    }
    system.update();
    destroy_recursive(registry, doomed);
    EXPECT_FALSE(registry.valid(doomed));
    for (const Entity entity : below) {
        EXPECT_FALSE(registry.valid(entity));
    }
    EXPECT_TRUE(registry.valid(kept));
    EXPECT_EQ(registry.get<Children>(root).size(), 1u);
    EXPECT_EQ(registry.alive(), 2u);
    EXPECT_EQ(registry.size<WorldTransform>(), 2u);
    system.update();
}

TEST(TransformSystem, AncestorsWithoutTransformCountAsIdentity) {
    Registry registry;
    TransformSystem system(registry);
    const Entity group = registry.create();  // no Transform
    const Entity member = spawn(registry, translated(3));
    set_parent(registry, member, group);
    system.update();
    EXPECT_FALSE(registry.has<WorldTransform>(group));
    EXPECT_NEAR(world_position(registry, member).x, 3.0f, 1e-6f);

    const Entity anchor = spawn(registry, translated(0, 9));
    const Entity attached = spawn(registry, translated(1), anchor);
    system.update();
    EXPECT_NEAR(world_position(registry, attached).y, 9.0f, 1e-6f);
    registry.remove<Transform>(anchor);
    system.update();
    EXPECT_FALSE(registry.has<WorldTransform>(anchor)) << "no Transform, no WorldTransform";
    EXPECT_NEAR(world_position(registry, attached).y, 0.0f, 1e-6f);
}

TEST(TransformSystem, CatchesUpWithAPopulatedRegistryAndChecksItsRegistry) {
    Registry registry;
    const Entity parent = spawn(registry, translated(1));
    const Entity child = spawn(registry, translated(1), parent);
    TransformSystem system(registry);
    system.update(registry);
    EXPECT_NEAR(world_position(registry, child).x, 2.0f, 1e-6f);
    Registry other;
    EXPECT_THROW(system.update(other), EcsError);
}

TEST(TransformSystem, TenThousandDeepChainWithoutRecursion) {
    constexpr int depth = 10000;
    Registry registry;
    TransformSystem system(registry);
    std::vector<Entity> chain;
    for (int i = 0; i < depth; ++i) {
        chain.push_back(spawn(registry, translated(1), i == 0 ? null_entity : chain.back()));
    }
    system.update();
    EXPECT_EQ(world_position(registry, chain.back()).x, static_cast<float>(depth));
    EXPECT_EQ(registry.get<Parent>(chain.back()).depth(), static_cast<std::uint32_t>(depth - 1));
    EXPECT_THROW(set_parent(registry, chain.front(), chain.back()), HierarchyCycleError);

    registry.patch<Transform>(chain.front(), [](Transform& t) { t.translation.x = 2; });
    system.update();
    EXPECT_EQ(system.last_visit_count(), static_cast<std::size_t>(depth));
    EXPECT_EQ(world_position(registry, chain.back()).x, static_cast<float>(depth + 1));
    expect_matrix_near(compute_world_matrix(registry, chain.back()),
                       registry.get<WorldTransform>(chain.back()).matrix);

    registry.patch<Transform>(chain.back(), [](Transform& t) { t.translation.y = 1; });
    system.update();
    EXPECT_EQ(system.last_visit_count(), 1u) << "a leaf is its own subtree";

    registry.destroy(chain.front());  // the second link becomes a root, keeping its world
    system.update();
    EXPECT_EQ(world_position(registry, chain.back()).x, static_cast<float>(depth + 1));
    destroy_recursive(registry, chain[1]);
    EXPECT_EQ(registry.alive(), 0u);
}

TEST(TransformSystem, ChainBuiltLeafFirstStillResolves) {
    // Linking from the bottom up leaves stale depths at first; the update must still be right.
    constexpr int depth = 2000;
    Registry registry;
    std::vector<Entity> chain;
    for (int i = 0; i < depth; ++i) {
        chain.push_back(spawn(registry, translated(1)));
    }
    for (int i = depth - 1; i > 0; --i) {
        set_parent(registry, chain[static_cast<std::size_t>(i)],
                   chain[static_cast<std::size_t>(i - 1)]);
    }
    TransformSystem system(registry);
    system.update();
    EXPECT_EQ(world_position(registry, chain.back()).x, static_cast<float>(depth));
    EXPECT_EQ(registry.get<Parent>(chain.back()).depth(), static_cast<std::uint32_t>(depth - 1));
    registry.patch<Transform>(chain[depth / 2], [](Transform& t) { t.translation.z = 1; });
    registry.patch<Transform>(chain[depth / 4], [](Transform& t) { t.translation.z = 1; });
    system.update();
    EXPECT_EQ(system.last_visit_count(), static_cast<std::size_t>(depth - depth / 4));
    EXPECT_EQ(world_position(registry, chain.back()).z, 2.0f);
}

TEST(TransformSystem, WideTree) {
    constexpr int width = 100000;
    Registry registry;
    TransformSystem system(registry);
    const Entity root = spawn(registry, translated(0, 5));
    std::vector<Entity> leaves;
    leaves.reserve(width);
    for (int i = 0; i < width; ++i) {
        leaves.push_back(spawn(registry, translated(static_cast<float>(i)), root));
    }
    system.update();
    EXPECT_EQ(registry.get<Children>(root).size(), static_cast<std::size_t>(width));
    EXPECT_EQ(world_position(registry, leaves[777]), glm::vec3(777, 5, 0));

    Observer<WorldTransform> moved = registry.observe<WorldTransform>();
    registry.patch<Transform>(root, [](Transform& t) { t.translation.y = 6; });
    system.update();
    EXPECT_EQ(moved.updated().size(), static_cast<std::size_t>(width) + 1);
    EXPECT_EQ(world_position(registry, leaves[width - 1]), glm::vec3(width - 1, 6, 0));

    for (int i = 0; i < width; i += 2) {  // O(1) each: the sibling list is intrusive
        remove_parent(registry, leaves[static_cast<std::size_t>(i)]);
    }
    EXPECT_EQ(registry.get<Children>(root).size(), static_cast<std::size_t>(width / 2));
    system.update();
    EXPECT_EQ(world_position(registry, leaves[2]), glm::vec3(2, 0, 0));
    EXPECT_EQ(world_position(registry, leaves[3]), glm::vec3(3, 6, 0));
}

TEST(TransformSystem, KeepWorldUnderRotatedScaledParents) {
    Registry registry;
    TransformSystem system(registry);
    Transform turned = translated(3, 0, -2);
    turned.rotation = glm::angleAxis(1.1f, glm::normalize(glm::vec3(1, 1, 0)));
    turned.scale = glm::vec3(2.0f);
    const Entity first = spawn(registry, turned);
    Transform other = translated(-5, 4, 1);
    other.rotation = glm::angleAxis(-0.4f, glm::vec3(0, 0, 1));
    other.scale = glm::vec3(0.5f);
    const Entity second = spawn(registry, other);
    Transform local = translated(1, 2, 3);
    local.rotation = glm::angleAxis(0.7f, glm::vec3(0, 1, 0));
    const Entity child = spawn(registry, local, first);
    system.update();
    const glm::mat4 before = registry.get<WorldTransform>(child).matrix;

    set_parent(registry, child, second, ReparentMode::KeepWorld);
    system.update();
    expect_matrix_near(registry.get<WorldTransform>(child).matrix, before);
    EXPECT_NE(registry.get<Transform>(child), local) << "the local transform was rewritten";
}

TEST(TransformSystem, DestroyingAMiddleLinkKeepsTheTailInPlace) {
    Registry registry;
    TransformSystem system(registry);
    std::vector<Entity> chain;
    for (int i = 0; i < 6; ++i) {
        Transform link = translated(1);
        link.rotation = glm::angleAxis(0.2f, glm::vec3(0, 0, 1));
        chain.push_back(spawn(registry, link, i == 0 ? null_entity : chain.back()));
    }
    system.update();
    const glm::mat4 tail_before = registry.get<WorldTransform>(chain.back()).matrix;
    registry.destroy(chain[2]);
    EXPECT_EQ(parent_of(registry, chain[3]), null_entity);
    EXPECT_TRUE(children_of(registry, chain[1]).empty());
    system.update();
    expect_matrix_near(registry.get<WorldTransform>(chain.back()).matrix, tail_before);
    EXPECT_EQ(registry.get<Parent>(chain.back()).depth(), 2u);
}

TEST(TransformSystem, ClearingARegistryWithHierarchies) {
    Registry registry;
    TransformSystem system(registry);
    const Entity root = spawn(registry, translated(1));
    for (int i = 0; i < 10; ++i) {
        spawn(registry, translated(1), i % 2 == 0 ? root : spawn(registry, translated(2), root));
    }
    system.update();
    registry.clear();
    EXPECT_EQ(registry.alive(), 0u);
    EXPECT_EQ(registry.size<Parent>(), 0u);
    EXPECT_EQ(registry.size<Children>(), 0u);
    EXPECT_EQ(registry.size<WorldTransform>(), 0u);
    system.update();
    EXPECT_EQ(system.last_visit_count(), 0u);
}

TEST(TransformSystem, HooksWorkWithoutASystem) {
    Registry registry;
    const Entity parent = spawn(registry, translated(4));
    const Entity child = spawn(registry, translated(1), parent);
    registry.destroy(parent);
    EXPECT_EQ(parent_of(registry, child), null_entity);
    EXPECT_EQ(registry.get<Transform>(child).translation, glm::vec3(5, 0, 0));
}

}  // namespace
}  // namespace luxel::ecs
