#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

#include "luxel/ecs/entity.hpp"

namespace luxel::ecs {

/// Base of every error the ECS reports. They are all programming errors (a stale handle, a
/// missing component, a cycle in the hierarchy), hence std::logic_error: the ECS checks them so a
/// bug fails loudly at the call that made it, instead of corrupting another entity's data.
class EcsError : public std::logic_error {
  public:
    explicit EcsError(const std::string& message) : std::logic_error(message) {}
};

/// A call was given a handle of a destroyed entity (or null_entity, or a handle from another
/// registry whose slot does not match). Every Registry call except valid() throws it.
class StaleEntityError : public EcsError {
  public:
    StaleEntityError(Entity entity, std::string_view operation);
    [[nodiscard]] Entity entity() const noexcept { return entity_; }

  private:
    Entity entity_;
};

/// get<T>/patch<T>/replace<T>/mark_updated<T> on an entity that has no T.
class MissingComponentError : public EcsError {
  public:
    MissingComponentError(Entity entity, std::string_view component);
};

/// emplace<T> on an entity that already has a T (use emplace_or_replace to overwrite).
class DuplicateComponentError : public EcsError {
  public:
    DuplicateComponentError(Entity entity, std::string_view component);
};

/// set_parent would make an entity its own ancestor.
class HierarchyCycleError : public EcsError {
  public:
    HierarchyCycleError(Entity child, Entity parent);
};

/// The registry cannot hold more entities at once (Entity::max_index + 1 slots, minus retired
/// ones).
class CapacityError : public EcsError {
  public:
    using EcsError::EcsError;
};

}  // namespace luxel::ecs
