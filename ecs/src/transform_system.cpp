#include "luxel/ecs/transform_system.hpp"

#include <algorithm>

#include "hierarchy_access.hpp"

namespace luxel::ecs {

TransformSystem::TransformSystem(Registry& registry)
    : registry_(&registry),
      transform_changes_(registry.observe<Transform>(ObserverStart::WithExisting)),
      parent_changes_(registry.observe<Parent>(ObserverStart::WithExisting)) {
    install_hierarchy_hooks(registry);
}

void TransformSystem::update(Registry& registry) {
    if (&registry != registry_) {
        throw EcsError(
            "luxel::ecs: TransformSystem::update called with a registry other than "
            "the one it was made for");
    }
    update();
}

void TransformSystem::update() {
    Registry& registry = *registry_;
    Storage<Transform>& transforms = registry.storage<Transform>();
    Storage<WorldTransform>& worlds = registry.storage<WorldTransform>();
    Storage<Parent>& parents = registry.storage<Parent>();
    Storage<Children>& children = registry.storage<Children>();

    const auto depth_of = [&parents](Entity entity) -> std::uint32_t {
        const Parent* link = parents.try_get(entity);
        return link == nullptr ? 0 : link->depth();
    };

    dirty_.clear();
    transform_changes_.consume([&](Entity entity, ChangeKind kind) {
        if (kind == ChangeKind::Destroyed) {
            if (!registry.valid(entity)) {
                return;  // destroyed with all its components; its children were detached
            }
            registry.remove<WorldTransform>(entity);
        }
        // Its own world changed (or vanished): so did its descendants'.
        dirty_.emplace_back(depth_of(entity), entity);
    });
    parent_changes_.consume([&](Entity entity, ChangeKind) {
        if (registry.valid(entity)) {
            dirty_.emplace_back(depth_of(entity), entity);
        }
    });
    // Shallow first, so that a dirty ancestor's walk covers its dirty descendants before they
    // come up (they are then skipped). Depths can be stale just after a re-parenting; that only
    // costs a repeated walk, never a wrong result, because a walk always rewrites its whole
    // subtree from the parent down.
    std::sort(dirty_.begin(), dirty_.end(), [](const auto& a, const auto& b) {
        return a.first != b.first ? a.first < b.first : a.second.index() < b.second.index();
    });

    if (++update_number_ == 0) {  // wrapped after 4 billion updates: forget old marks
        std::fill(visited_in_update_.begin(), visited_in_update_.end(), 0);
        update_number_ = 1;
    }
    visited_in_update_.resize(std::max(visited_in_update_.size(), registry.slot_count()), 0);
    last_visit_count_ = 0;

    for (const auto& [depth, root] : dirty_) {
        if (visited_in_update_[root.index()] == update_number_) {
            continue;
        }
        stack_.push_back(root);
        while (!stack_.empty()) {
            const Entity entity = stack_.back();
            stack_.pop_back();
            visited_in_update_[entity.index()] = update_number_;
            ++last_visit_count_;

            glm::mat4 parent_world(1.0f);
            if (Parent* link = parents.try_get(entity)) {
                const Entity parent = link->entity();
                if (const WorldTransform* world = worlds.try_get(parent)) {
                    parent_world = world->matrix;
                }
                detail::HierarchyAccess::depth(*link) = depth_of(parent) + 1;
            }
            if (const Transform* local = transforms.try_get(entity)) {
                const glm::mat4 world = parent_world * local->matrix();
                if (WorldTransform* current = worlds.try_get(entity)) {
                    if (current->matrix != world) {
                        current->matrix = world;
                        worlds.mark_updated(entity);
                    }
                } else {
                    worlds.emplace(entity, world);
                }
            }
            if (const Children* list = children.try_get(entity)) {
                for (Entity child = list->first(); !child.is_null();
                     child = parents.get(child).next_sibling()) {
                    stack_.push_back(child);
                }
            }
        }
    }
}

}  // namespace luxel::ecs
