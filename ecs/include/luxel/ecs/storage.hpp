#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <span>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "luxel/ecs/detail/observer_state.hpp"
#include "luxel/ecs/entity.hpp"
#include "luxel/ecs/errors.hpp"
#include "luxel/ecs/signal.hpp"
#include "luxel/ecs/sparse_set.hpp"
#include "luxel/ecs/type_id.hpp"

namespace luxel::ecs {

class Registry;

/// The signal type of the construct / update / destroy hooks: (registry, entity).
using ComponentSignal = Signal<Registry&, Entity>;
using ComponentSink = Sink<Registry&, Entity>;

/// The type-erased face of a component pool: membership, the hooks, the observers, and removal,
/// which is what Registry::destroy needs to strip an entity of components it knows nothing about.
class StorageBase {
  public:
    explicit StorageBase(Registry& registry) noexcept : registry_(&registry) {}
    StorageBase(const StorageBase&) = delete;
    StorageBase& operator=(const StorageBase&) = delete;
    virtual ~StorageBase() = default;

    /// Removes the entity's component if it has one (on_destroy first, then observers, then
    /// swap-and-pop). Returns whether it had one. O(1) plus the hooks.
    virtual bool remove(Entity entity) = 0;
    [[nodiscard]] virtual std::string_view component_name() const noexcept = 0;

    [[nodiscard]] bool contains(Entity entity) const noexcept { return entities_.contains(entity); }
    [[nodiscard]] std::size_t size() const noexcept { return entities_.size(); }
    [[nodiscard]] bool empty() const noexcept { return entities_.empty(); }
    /// The entities that have the component, in the same order as the components.
    [[nodiscard]] std::span<const Entity> entities() const noexcept { return entities_.entities(); }
    [[nodiscard]] const SparseSet& entity_set() const noexcept { return entities_; }

    [[nodiscard]] ComponentSink on_construct() noexcept { return ComponentSink(on_construct_); }
    [[nodiscard]] ComponentSink on_update() noexcept { return ComponentSink(on_update_); }
    [[nodiscard]] ComponentSink on_destroy() noexcept { return ComponentSink(on_destroy_); }

    /// Attaches a new observer state (see Registry::observe).
    void attach_observer(std::shared_ptr<detail::ObserverState> state) {
        observers_.attach(std::move(state), entities_, *this);
    }
    [[nodiscard]] std::size_t observer_count() const noexcept { return observers_.size(); }

  protected:
    SparseSet entities_;
    detail::ObserverList observers_;
    ComponentSignal on_construct_;
    ComponentSignal on_update_;
    ComponentSignal on_destroy_;
    Registry* registry_;
};

/// The pool of component T: a sparse set of entities plus a parallel dense vector of T, so that
/// entities()[i] owns components()[i]. Iterating either is a linear walk over packed memory.
///
/// Reference stability: like std::vector, adding a T may reallocate (invalidating every T& and
/// T*), and removing one moves the last T into its place. Hold entities, not references, across
/// changes to the pool.
///
/// Normally used through Registry, which checks handles for staleness first; the pool itself
/// only checks membership.
template <Component T>
class Storage final : public StorageBase {
  public:
    using StorageBase::StorageBase;

    [[nodiscard]] std::string_view component_name() const noexcept override {
        return type_name<T>();
    }

    /// Constructs a T for `entity` from args (brace-initialised for aggregates, so
    /// emplace<Position>(e, 1.f, 2.f) works on a plain struct). Records Constructed and emits
    /// on_construct. Throws DuplicateComponentError if the entity already has one. Amortised
    /// O(1). Strong exception guarantee up to the hooks.
    template <class... Args>
    T& emplace(Entity entity, Args&&... args) {
        if (entities_.contains(entity)) {
            throw DuplicateComponentError(entity, type_name<T>());
        }
        if constexpr (std::is_aggregate_v<T>) {
            components_.push_back(T{std::forward<Args>(args)...});
        } else {
            components_.emplace_back(std::forward<Args>(args)...);
        }
        std::size_t position = 0;
        try {
            position = entities_.insert(entity);
        } catch (...) {
            components_.pop_back();
            throw;
        }
        observers_.record_constructed(entity, position);
        if (on_construct_.has_slots()) {
            on_construct_.emit(*registry_, entity);
            // Looked up again: a hook may have added components and reallocated the vector.
            return get(entity);
        }
        return components_[position];
    }

    bool remove(Entity entity) override {
        if (!entities_.contains(entity)) {
            return false;
        }
        // Hooks run while the component is still readable.
        on_destroy_.emit(*registry_, entity);
        const std::size_t position = entities_.find(entity);
        if (position == SparseSet::npos) {
            return true;
        }
        observers_.record_destroyed(entity);
        const std::size_t last = components_.size() - 1;
        if (position != last) {
            components_[position] = std::move(components_[last]);
        }
        components_.pop_back();
        entities_.erase_at(position);
        return true;
    }

    /// The entity's T. Throws MissingComponentError if it has none. O(1).
    [[nodiscard]] T& get(Entity entity) { return components_[position_of(entity)]; }
    [[nodiscard]] const T& get(Entity entity) const { return components_[position_of(entity)]; }

    /// The entity's T, or nullptr. O(1).
    [[nodiscard]] T* try_get(Entity entity) noexcept {
        const std::size_t position = entities_.find(entity);
        return position == SparseSet::npos ? nullptr : &components_[position];
    }
    [[nodiscard]] const T* try_get(Entity entity) const noexcept {
        const std::size_t position = entities_.find(entity);
        return position == SparseSet::npos ? nullptr : &components_[position];
    }

    /// Calls fn(T&) to modify the component in place, then records Updated and emits on_update.
    template <class Fn>
    T& patch(Entity entity, Fn&& fn) {
        const std::size_t position = position_of(entity);
        std::invoke(std::forward<Fn>(fn), components_[position]);
        return updated_at(entity, position);
    }

    /// Assigns a T built from args (brace-initialised for aggregates) to the existing component,
    /// then records Updated and emits on_update.
    template <class... Args>
    T& replace(Entity entity, Args&&... args) {
        const std::size_t position = position_of(entity);
        if constexpr (std::is_aggregate_v<T>) {
            components_[position] = T{std::forward<Args>(args)...};
        } else {
            components_[position] = T(std::forward<Args>(args)...);
        }
        return updated_at(entity, position);
    }

    /// Records Updated and emits on_update, for components modified through a reference.
    T& mark_updated(Entity entity) { return updated_at(entity, position_of(entity)); }

    /// The components, in the same order as entities(). Writing through this span is invisible
    /// to change tracking; call mark_updated for entities whose change matters to observers.
    [[nodiscard]] std::span<T> components() noexcept { return components_; }
    [[nodiscard]] std::span<const T> components() const noexcept { return components_; }

    /// Reserves room for `capacity` components (one allocation instead of several while a pool
    /// is filled).
    void reserve(std::size_t capacity) {
        components_.reserve(capacity);
        entities_.reserve(capacity);
    }

  private:
    [[nodiscard]] std::size_t position_of(Entity entity) const {
        const std::size_t position = entities_.find(entity);
        if (position == SparseSet::npos) {
            throw MissingComponentError(entity, type_name<T>());
        }
        return position;
    }

    T& updated_at(Entity entity, std::size_t position) {
        observers_.record_updated(entity, position);
        if (on_update_.has_slots()) {
            on_update_.emit(*registry_, entity);
            return get(entity);  // a hook may have changed the pool
        }
        return components_[position];
    }

    std::vector<T> components_;
};

}  // namespace luxel::ecs
