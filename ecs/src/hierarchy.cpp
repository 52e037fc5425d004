#include "luxel/ecs/hierarchy.hpp"

#include <vector>

#include "hierarchy_access.hpp"
#include "luxel/ecs/transform.hpp"

namespace luxel::ecs {

namespace detail {

/// The registry-context object that keeps the links consistent under direct removals and
/// destruction. One per registry; its connections disconnect when the registry goes.
class HierarchyHooks {
  public:
    explicit HierarchyHooks(Registry& registry);

    /// Takes `child` out of its parent's list (the Parent component itself stays). Removes the
    /// parent's Children once it is empty.
    static void unlink(Registry& registry, Entity child);
    /// Appends `child`, whose Parent names `parent` already, to the parent's list.
    static void link(Registry& registry, Entity child, Entity parent);
    /// Detaches every child of `parent`, each keeping its world transform.
    static void detach_children_keeping_world(Registry& registry, Entity parent);

  private:
    Connection entity_destroyed_;
    Connection parent_removed_;
    Connection children_removed_;
};

HierarchyHooks::HierarchyHooks(Registry& registry)
    : entity_destroyed_(registry.on_destroy_entity().connect([](Registry& owner, Entity entity) {
          // Before any component goes: the parent's Transform is still there to compute the
          // children's world transform from.
          if (owner.has<Children>(entity)) {
              detach_children_keeping_world(owner, entity);
          }
      })),
      parent_removed_(registry.on_destroy<Parent>().connect(
          [](Registry& owner, Entity child) { unlink(owner, child); })),
      children_removed_(registry.on_destroy<Children>().connect([](Registry& owner, Entity parent) {
          if (owner.get<Children>(parent).size() > 0) {
              detach_children_keeping_world(owner, parent);
          }
      })) {}

void HierarchyHooks::unlink(Registry& registry, Entity child) {
    Parent& link = registry.get<Parent>(child);
    const Entity parent = link.entity();
    if (parent.is_null() || !registry.valid(parent)) {
        return;
    }
    Children* list = registry.try_get<Children>(parent);
    if (list == nullptr) {
        return;  // already torn down: the parent's Children is being removed
    }
    const Entity previous = link.previous_sibling();
    const Entity next = link.next_sibling();
    if (previous.is_null()) {
        HierarchyAccess::first(*list) = next;
    } else {
        HierarchyAccess::next(registry.get<Parent>(previous)) = next;
    }
    if (next.is_null()) {
        HierarchyAccess::last(*list) = previous;
    } else {
        HierarchyAccess::previous(registry.get<Parent>(next)) = previous;
    }
    HierarchyAccess::previous(link) = null_entity;
    HierarchyAccess::next(link) = null_entity;
    if (--HierarchyAccess::count(*list) == 0) {
        registry.remove<Children>(parent);
    }
}

void HierarchyHooks::link(Registry& registry, Entity child, Entity parent) {
    if (Children* list = registry.try_get<Children>(parent)) {
        const Entity last = list->last();
        HierarchyAccess::next(registry.get<Parent>(last)) = child;
        HierarchyAccess::previous(registry.get<Parent>(child)) = last;
        HierarchyAccess::last(*list) = child;
        ++HierarchyAccess::count(*list);
    } else {
        registry.emplace<Children>(parent, HierarchyAccess::key(), child);
    }
}

void HierarchyHooks::detach_children_keeping_world(Registry& registry, Entity parent) {
    const glm::mat4 parent_world = compute_world_matrix(registry, parent);
    // Collected first: detaching rewrites the very links we would be walking.
    std::vector<Entity> children;
    for (const Entity child : children_of(registry, parent)) {
        children.push_back(child);
    }
    for (const Entity child : children) {
        registry.remove<Parent>(child);
        if (const Transform* local = registry.try_get<Transform>(child)) {
            registry.replace<Transform>(child,
                                        Transform::from_matrix(parent_world * local->matrix()));
        }
    }
}

}  // namespace detail

using detail::HierarchyAccess;
using detail::HierarchyHooks;

void install_hierarchy_hooks(Registry& registry) {
    registry.ctx().get_or_emplace<HierarchyHooks>(registry);
}

Entity parent_of(const Registry& registry, Entity entity) {
    const Parent* link = registry.try_get<Parent>(entity);
    return link == nullptr ? null_entity : link->entity();
}

bool is_ancestor_of(const Registry& registry, Entity ancestor, Entity entity) {
    for (Entity current = parent_of(registry, entity); !current.is_null();
         current = parent_of(registry, current)) {
        if (current == ancestor) {
            return true;
        }
    }
    return false;
}

ChildRange children_of(const Registry& registry, Entity parent) {
    const Children* list = registry.try_get<Children>(parent);
    if (list == nullptr) {
        return ChildRange(registry, null_entity, 0);
    }
    return ChildRange(registry, list->first(), list->size());
}

glm::mat4 compute_world_matrix(const Registry& registry, Entity entity) {
    glm::mat4 world(1.0f);
    for (Entity current = entity; !current.is_null(); current = parent_of(registry, current)) {
        if (const Transform* local = registry.try_get<Transform>(current)) {
            world = local->matrix() * world;
        }
    }
    return world;
}

void set_parent(Registry& registry, Entity child, Entity parent, ReparentMode mode) {
    if (!registry.valid(child)) {
        throw StaleEntityError(child, "set_parent (child)");
    }
    if (parent.is_null()) {
        remove_parent(registry, child, mode);
        return;
    }
    if (!registry.valid(parent)) {
        throw StaleEntityError(parent, "set_parent (parent)");
    }
    if (parent == child || is_ancestor_of(registry, child, parent)) {
        throw HierarchyCycleError(child, parent);
    }
    install_hierarchy_hooks(registry);
    if (parent_of(registry, child) == parent) {
        return;
    }

    // KeepWorld: the local transform that puts the child where it is now, under the new parent.
    // Computed before any link changes.
    const bool rewrite_local = mode == ReparentMode::KeepWorld && registry.has<Transform>(child);
    Transform kept_world_local;
    if (rewrite_local) {
        kept_world_local =
            Transform::from_matrix(glm::inverse(compute_world_matrix(registry, parent)) *
                                   compute_world_matrix(registry, child));
    }

    const Parent* parent_link = registry.try_get<Parent>(parent);
    const std::uint32_t depth = parent_link == nullptr ? 1 : parent_link->depth() + 1;
    if (registry.has<Parent>(child)) {
        HierarchyHooks::unlink(registry, child);
        Parent& current = registry.get<Parent>(child);
        HierarchyAccess::parent(current) = parent;
        HierarchyAccess::depth(current) = depth;
        HierarchyHooks::link(registry, child, parent);
        registry.mark_updated<Parent>(child);
    } else {
        registry.emplace<Parent>(child, HierarchyAccess::key(), parent, depth);
        HierarchyHooks::link(registry, child, parent);
    }
    if (rewrite_local) {
        registry.replace<Transform>(child, kept_world_local);
    }
}

void remove_parent(Registry& registry, Entity child, ReparentMode mode) {
    if (!registry.valid(child)) {
        throw StaleEntityError(child, "remove_parent");
    }
    if (!registry.has<Parent>(child)) {
        return;
    }
    install_hierarchy_hooks(registry);
    const bool rewrite_local = mode == ReparentMode::KeepWorld && registry.has<Transform>(child);
    const glm::mat4 world = rewrite_local ? compute_world_matrix(registry, child) : glm::mat4(1.0f);
    registry.remove<Parent>(child);  // the hook unlinks it
    if (rewrite_local) {
        registry.replace<Transform>(child, Transform::from_matrix(world));
    }
}

void destroy_recursive(Registry& registry, Entity root) {
    if (!registry.valid(root)) {
        throw StaleEntityError(root, "destroy_recursive");
    }
    // Pre-order with an explicit stack; destroying in reverse pre-order then takes every child
    // before its parent, so no destruction has children left to detach.
    std::vector<Entity> order;
    std::vector<Entity> pending{root};
    while (!pending.empty()) {
        const Entity entity = pending.back();
        pending.pop_back();
        order.push_back(entity);
        for (const Entity child : children_of(registry, entity)) {
            pending.push_back(child);
        }
    }
    for (auto it = order.rbegin(); it != order.rend(); ++it) {
        registry.destroy(*it);
    }
}

}  // namespace luxel::ecs
