#include "luxel/ecs/entity.hpp"

#include <atomic>
#include <ostream>

#include "luxel/ecs/errors.hpp"
#include "luxel/ecs/type_id.hpp"

namespace luxel::ecs {

std::string to_string(Entity entity) {
    if (entity.is_null()) {
        return "null";
    }
    return std::to_string(entity.index()) + "v" + std::to_string(entity.generation());
}

std::ostream& operator<<(std::ostream& out, Entity entity) {
    return out << to_string(entity);
}

StaleEntityError::StaleEntityError(Entity entity, std::string_view operation)
    : EcsError("luxel::ecs: " + std::string(operation) + " on stale entity " + to_string(entity) +
               (entity.is_null() ? " (the null entity)" : " (destroyed, or not of this registry)")),
      entity_(entity) {}

MissingComponentError::MissingComponentError(Entity entity, std::string_view component)
    : EcsError("luxel::ecs: entity " + to_string(entity) + " has no " + std::string(component)) {}

DuplicateComponentError::DuplicateComponentError(Entity entity, std::string_view component)
    : EcsError("luxel::ecs: entity " + to_string(entity) + " already has a " +
               std::string(component) + " (use emplace_or_replace to overwrite it)") {}

HierarchyCycleError::HierarchyCycleError(Entity child, Entity parent)
    : EcsError("luxel::ecs: cannot make " + to_string(parent) + " the parent of " +
               to_string(child) + ": " +
               (child == parent ? std::string("an entity cannot be its own parent")
                                : to_string(parent) + " is a descendant of " + to_string(child))) {}

namespace detail {

std::size_t next_type_index() noexcept {
    // Only ever incremented while a type's static index is initialised, which the language
    // already serialises per type; the atomic serialises different types' first uses.
    static std::atomic<std::size_t> next{0};
    return next.fetch_add(1, std::memory_order_relaxed);
}

}  // namespace detail

}  // namespace luxel::ecs
