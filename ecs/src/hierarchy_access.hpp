#pragma once

#include "luxel/ecs/hierarchy.hpp"

namespace luxel::ecs::detail {

/// The module's private access to the link components' fields: hierarchy.cpp maintains the lists,
/// transform_system.cpp refreshes depths.
struct HierarchyAccess {
    [[nodiscard]] static HierarchyKey key() noexcept { return HierarchyKey{}; }

    static Entity& parent(Parent& link) noexcept { return link.parent_; }
    static Entity& previous(Parent& link) noexcept { return link.previous_; }
    static Entity& next(Parent& link) noexcept { return link.next_; }
    static std::uint32_t& depth(Parent& link) noexcept { return link.depth_; }

    static Entity& first(Children& list) noexcept { return list.first_; }
    static Entity& last(Children& list) noexcept { return list.last_; }
    static std::uint32_t& count(Children& list) noexcept { return list.count_; }
};

}  // namespace luxel::ecs::detail
