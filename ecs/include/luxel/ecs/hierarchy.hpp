#pragma once

#include <cstddef>
#include <cstdint>
#include <iterator>

#include <glm/glm.hpp>

#include "luxel/ecs/entity.hpp"
#include "luxel/ecs/registry.hpp"

namespace luxel::ecs {

/// # The transform hierarchy
///
/// A child's Transform is relative to its parent; the TransformSystem turns the chain into
/// WorldTransform. The links are two components kept consistent by the functions below (never
/// emplace or replace them yourself; their constructors take a key only this module has):
/// - Parent, on every child: the parent, the child's siblings (an intrusive doubly linked list,
///   so attaching and detaching are O(1) even under a parent with 100,000 children) and its depth.
/// - Children, on every entity with at least one child: first and last child and their count.
///
/// Policies:
/// - Cycles: set_parent(child, p) throws HierarchyCycleError, and changes nothing, when p is
///   child itself or one of its descendants. Checking walks up from p: O(depth).
/// - Re-parenting: set_parent on an entity that has a parent moves it (with its subtree) under
///   the new one. ReparentMode::KeepLocal (default) keeps its Transform, so it moves with its new
///   parent; KeepWorld rewrites its Transform so it stays where it is in the world.
/// - Destroying a parent (Registry::destroy): its children are detached and keep their world
///   transform (their Transform is rewritten from their current world matrix, shear aside, see
///   Transform::from_matrix); their own subtrees are untouched. Nothing else is destroyed: the
///   registry never destroys entities you did not name. Use destroy_recursive to destroy a
///   subtree.
/// - Removing the Parent component directly (registry.remove<Parent>) detaches the child keeping
///   its local Transform, exactly like remove_parent(KeepLocal).
/// All of this holds once the hierarchy is in use in a registry: the first set_parent (or the
/// first TransformSystem) installs the hooks, in the registry's context, that maintain it.

namespace detail {
struct HierarchyAccess;
/// The key that only the hierarchy functions can make: it keeps game code from emplacing a
/// Parent or Children that the intrusive lists would not know about.
class HierarchyKey {
    friend struct HierarchyAccess;
    HierarchyKey() = default;
};
}  // namespace detail

/// How set_parent/remove_parent treat the moved entity's Transform.
enum class ReparentMode {
    KeepLocal,  ///< keep the Transform: the entity moves with its new parent
    KeepWorld,  ///< rewrite the Transform so the world transform does not change
};

/// The parent link of a child entity. Read-only outside this module; move-only so it cannot be
/// copied onto another entity.
class Parent {
  public:
    Parent(detail::HierarchyKey, Entity parent, std::uint32_t depth) noexcept
        : parent_(parent), depth_(depth) {}
    Parent(Parent&&) noexcept = default;
    Parent& operator=(Parent&&) noexcept = default;
    Parent(const Parent&) = delete;
    Parent& operator=(const Parent&) = delete;
    ~Parent() = default;

    /// The parent entity.
    [[nodiscard]] Entity entity() const noexcept { return parent_; }
    /// Distance from the root (a child of a root has depth 1). Exact after the last
    /// TransformSystem::update; in between, re-parenting may leave descendants' values stale.
    [[nodiscard]] std::uint32_t depth() const noexcept { return depth_; }
    [[nodiscard]] Entity next_sibling() const noexcept { return next_; }
    [[nodiscard]] Entity previous_sibling() const noexcept { return previous_; }

  private:
    friend struct detail::HierarchyAccess;
    Entity parent_;
    Entity previous_;
    Entity next_;
    std::uint32_t depth_ = 0;
};

/// The child list of a parent entity, in attachment order. Read-only outside this module.
class Children {
  public:
    Children(detail::HierarchyKey, Entity first) noexcept
        : first_(first), last_(first), count_(1) {}
    Children(Children&&) noexcept = default;
    Children& operator=(Children&&) noexcept = default;
    Children(const Children&) = delete;
    Children& operator=(const Children&) = delete;
    ~Children() = default;

    [[nodiscard]] Entity first() const noexcept { return first_; }
    [[nodiscard]] Entity last() const noexcept { return last_; }
    [[nodiscard]] std::size_t size() const noexcept { return count_; }

  private:
    friend struct detail::HierarchyAccess;
    Entity first_;
    Entity last_;
    std::uint32_t count_ = 0;
};

/// Makes `parent` the parent of `child` (see the policies above). A null parent is
/// remove_parent. Setting the current parent again changes nothing. Records Parent as
/// Constructed or Updated (which is how the TransformSystem learns of it). O(depth of parent)
/// for the cycle check, O(depth) more with KeepWorld. Throws StaleEntityError,
/// HierarchyCycleError.
void set_parent(Registry& registry, Entity child, Entity parent,
                ReparentMode mode = ReparentMode::KeepLocal);

/// Makes `child` a root (no-op if it is one). O(1), O(depth) with KeepWorld.
void remove_parent(Registry& registry, Entity child, ReparentMode mode = ReparentMode::KeepLocal);

/// The parent of `entity`, or null_entity for a root. O(1).
[[nodiscard]] Entity parent_of(const Registry& registry, Entity entity);

/// Whether `ancestor` is a proper ancestor of `entity`. O(depth).
[[nodiscard]] bool is_ancestor_of(const Registry& registry, Entity ancestor, Entity entity);

/// Destroys `root` and all its descendants, children before parents, without recursion (a
/// 10,000-deep chain is fine). O(subtree size x component types).
void destroy_recursive(Registry& registry, Entity root);

/// The local-to-world matrix of `entity` computed now from the Transforms up its chain (an
/// entity without a Transform counts as identity), without waiting for the TransformSystem.
/// O(depth), iterative.
[[nodiscard]] glm::mat4 compute_world_matrix(const Registry& registry, Entity entity);

/// Installs the hooks that keep the hierarchy consistent when entities are destroyed or their
/// links removed directly. Idempotent; set_parent and TransformSystem call it.
void install_hierarchy_hooks(Registry& registry);

/// The children of a parent, in attachment order, as a forward range of Entity:
///     for (Entity child : children_of(registry, parent)) { ... }
/// Valid until the hierarchy changes.
class ChildRange {
  public:
    class Iterator {
      public:
        using value_type = Entity;
        using difference_type = std::ptrdiff_t;
        using iterator_concept = std::forward_iterator_tag;

        Iterator() = default;
        Iterator(const Registry* registry, Entity current) noexcept
            : registry_(registry), current_(current) {}
        [[nodiscard]] Entity operator*() const noexcept { return current_; }
        Iterator& operator++() {
            current_ = registry_->get<Parent>(current_).next_sibling();
            return *this;
        }
        Iterator operator++(int) {
            Iterator before = *this;
            ++*this;
            return before;
        }
        [[nodiscard]] bool operator==(const Iterator& other) const noexcept {
            return current_ == other.current_;
        }

      private:
        const Registry* registry_ = nullptr;
        Entity current_;
    };

    ChildRange(const Registry& registry, Entity first, std::size_t count) noexcept
        : registry_(&registry), first_(first), count_(count) {}
    [[nodiscard]] Iterator begin() const noexcept { return Iterator(registry_, first_); }
    [[nodiscard]] Iterator end() const noexcept { return Iterator(registry_, null_entity); }
    [[nodiscard]] std::size_t size() const noexcept { return count_; }
    [[nodiscard]] bool empty() const noexcept { return count_ == 0; }

  private:
    const Registry* registry_;
    Entity first_;
    std::size_t count_;
};

/// The children of `parent` (empty for a leaf). O(1) to make. Throws StaleEntityError.
[[nodiscard]] ChildRange children_of(const Registry& registry, Entity parent);

}  // namespace luxel::ecs
