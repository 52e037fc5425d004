#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <tuple>
#include <utility>
#include <vector>

#include "luxel/ecs/context.hpp"
#include "luxel/ecs/entity.hpp"
#include "luxel/ecs/errors.hpp"
#include "luxel/ecs/observer.hpp"
#include "luxel/ecs/signal.hpp"
#include "luxel/ecs/storage.hpp"
#include "luxel/ecs/type_id.hpp"
#include "luxel/ecs/view.hpp"

namespace luxel::ecs {

/// A world of entities and their components.
///
///     Registry registry;
///     Entity ball = registry.create();
///     registry.emplace<Position>(ball, 0.f, 1.f, 0.f);
///     registry.patch<Position>(ball, [](Position& p) { p.y -= 0.1f; });  // tracked change
///     for (auto [e, p, v] : registry.view<Position, Velocity>()) { ... }
///     Observer<Position> moved = registry.observe<Position>();           // "what changed?"
///
/// Components: any movable object type, no registration (see Component). Each type gets its own
/// pool (Storage<T>) the first time the registry sees it.
///
/// Handles: every call except valid() checks its entity first and throws StaleEntityError for a
/// destroyed entity, null_entity, or a handle that does not belong to a live slot, so a stale
/// handle can never read or write the entity that has since taken over its slot. Missing and
/// duplicate components are checked errors too (MissingComponentError, DuplicateComponentError);
/// try_get is the non-throwing way to ask for a component that may be absent.
///
/// Change tracking: emplace records Constructed; patch, replace, emplace_or_replace on an
/// existing component and mark_updated record Updated; remove and destroy record Destroyed.
/// Observers (observe<T>) read those net changes in time proportional to their number; signals
/// (on_construct/on_update/on_destroy<T>) call back as they happen. Writing through a reference
/// from get<T> or a view is not tracked: follow it with mark_updated<T> when it matters.
///
/// Several registries coexist independently: nothing is global except the numbering of
/// component types. A registry is neither copyable nor movable (pools, observers and hooks point
/// back to it); hold it by value in one place or in a unique_ptr. Not thread-safe: use it from one
/// thread at a time (concurrent readers are safe only through const member functions, with no
/// writer).
class Registry {
  public:
    Registry();
    Registry(const Registry&) = delete;
    Registry& operator=(const Registry&) = delete;
    Registry(Registry&&) = delete;
    Registry& operator=(Registry&&) = delete;
    /// Destroys every component without emitting on_destroy (the world is ending, not changing).
    ~Registry();

    // ---- Entities -------------------------------------------------------------------------

    /// A new entity with no components. Reuses the slot of a destroyed entity (with a higher
    /// generation) when one is free. O(1). Throws CapacityError past Entity::max_index + 1 live
    /// slots.
    [[nodiscard]] Entity create();

    /// Destroys the entity: emits on_destroy_entity, then removes each of its components (each
    /// pool emits on_destroy and records Destroyed), then frees the slot. From then on the handle
    /// is stale everywhere. O(number of component types) plus the hooks. A slot whose generation
    /// is exhausted is retired instead of reused. Throws StaleEntityError for a stale handle.
    /// Calling destroy(e) from a hook while e is being destroyed does nothing; emplacing on e from
    /// such a hook throws EcsError (it would outlive its entity).
    ///
    /// Hierarchy (hierarchy.hpp): destroying a parent detaches its children, which keep their
    /// world transform; destroy_recursive destroys a whole subtree instead.
    void destroy(Entity entity);

    /// Whether `entity` names a live entity of this registry. O(1), never throws.
    [[nodiscard]] bool valid(Entity entity) const noexcept {
        const std::uint32_t index = entity.index();
        return index < slots_.size() && slots_[index].alive &&
               slots_[index].generation == entity.generation();
    }

    /// Destroys every live entity (with all hooks, as destroy does). O(slots).
    void clear();

    /// Number of live entities.
    [[nodiscard]] std::size_t alive() const noexcept { return alive_; }
    /// One past the highest slot index ever used: the size for arrays indexed by
    /// Entity::index().
    [[nodiscard]] std::size_t slot_count() const noexcept { return slots_.size(); }

    /// Emitted at the start of destroy(e), while e and all its components are still intact.
    [[nodiscard]] Sink<Registry&, Entity> on_destroy_entity() noexcept {
        return Sink<Registry&, Entity>(on_destroy_entity_);
    }

    // ---- Components -----------------------------------------------------------------------

    /// Adds a T built from args (brace-initialised for aggregates); returns it. Records
    /// Constructed, emits on_construct. Throws DuplicateComponentError if e already has a T.
    /// Amortised O(1).
    template <Component T, class... Args>
    T& emplace(Entity entity, Args&&... args) {
        check_valid_for_emplace(entity);
        return storage<T>().emplace(entity, std::forward<Args>(args)...);
    }

    /// emplace, or replace if e already has a T (recording Updated rather than Constructed).
    template <Component T, class... Args>
    T& emplace_or_replace(Entity entity, Args&&... args) {
        check_valid_for_emplace(entity);
        Storage<T>& pool = storage<T>();
        if (pool.contains(entity)) {
            return pool.replace(entity, std::forward<Args>(args)...);
        }
        return pool.emplace(entity, std::forward<Args>(args)...);
    }

    /// The T, emplacing one from args first if absent.
    template <Component T, class... Args>
    T& get_or_emplace(Entity entity, Args&&... args) {
        check_valid_for_emplace(entity);
        Storage<T>& pool = storage<T>();
        if (T* existing = pool.try_get(entity)) {
            return *existing;
        }
        return pool.emplace(entity, std::forward<Args>(args)...);
    }

    /// The entity's T. Throws MissingComponentError if absent. O(1). The reference is valid
    /// until a T is added to or removed from any entity (see Storage).
    template <Component T>
    [[nodiscard]] T& get(Entity entity) {
        check_valid(entity, "get");
        return storage<T>().get(entity);
    }
    template <Component T>
    [[nodiscard]] const T& get(Entity entity) const {
        check_valid(entity, "get");
        const Storage<T>* pool = find_storage<T>();
        if (pool == nullptr) {
            throw MissingComponentError(entity, type_name<T>());
        }
        return pool->get(entity);
    }
    /// Several components at once: auto [p, v] = registry.get<Position, Velocity>(e);
    template <Component... T>
    requires(sizeof...(T) > 1) [[nodiscard]] std::tuple<T&...> get(Entity entity) {
        check_valid(entity, "get");
        return std::tuple<T&...>(storage<T>().get(entity)...);
    }

    /// The entity's T, or nullptr if it has none. O(1). Still throws StaleEntityError.
    template <Component T>
    [[nodiscard]] T* try_get(Entity entity) {
        check_valid(entity, "try_get");
        return storage<T>().try_get(entity);
    }
    template <Component T>
    [[nodiscard]] const T* try_get(Entity entity) const {
        check_valid(entity, "try_get");
        const Storage<T>* pool = find_storage<T>();
        return pool == nullptr ? nullptr : pool->try_get(entity);
    }

    /// Whether the entity has every one of T... (true for an empty list). O(sizeof...(T)).
    template <Component... T>
    [[nodiscard]] bool has(Entity entity) const {
        check_valid(entity, "has");
        return (has_one<T>(entity) && ...);
    }
    /// Whether the entity has at least one of T...
    template <Component... T>
    [[nodiscard]] bool has_any(Entity entity) const {
        check_valid(entity, "has_any");
        return (has_one<T>(entity) || ...);
    }

    /// Removes each of T... the entity has (on_destroy, then Destroyed recorded, then
    /// swap-and-pop); absent ones are skipped. Returns how many were removed. O(sizeof...(T)).
    template <Component... T>
    std::size_t remove(Entity entity) {
        check_valid(entity, "remove");
        return (std::size_t{0} + ... + static_cast<std::size_t>(storage<T>().remove(entity)));
    }

    /// Modifies the T in place with fn(T&), then records Updated and emits on_update.
    template <Component T, class Fn>
    T& patch(Entity entity, Fn&& fn) {
        check_valid(entity, "patch");
        return storage<T>().patch(entity, std::forward<Fn>(fn));
    }

    /// Assigns a T built from args to the existing T, then records Updated and emits on_update.
    /// Throws MissingComponentError if absent.
    template <Component T, class... Args>
    T& replace(Entity entity, Args&&... args) {
        check_valid(entity, "replace");
        return storage<T>().replace(entity, std::forward<Args>(args)...);
    }

    /// Records Updated and emits on_update for a T that was modified through a reference.
    template <Component T>
    T& mark_updated(Entity entity) {
        check_valid(entity, "mark_updated");
        return storage<T>().mark_updated(entity);
    }

    /// Number of entities that have a T.
    template <Component T>
    [[nodiscard]] std::size_t size() const noexcept {
        const Storage<T>* pool = find_storage<T>();
        return pool == nullptr ? 0 : pool->size();
    }

    // ---- Views, change tracking, hooks ----------------------------------------------------

    /// The entities that have all of T... and none of X...; see View for iteration order, cost
    /// and what may change during iteration. O(number of types) to create.
    template <Component... T, Component... X>
    [[nodiscard]] View<type_list<T...>, type_list<X...>> view(exclude_t<X...> = exclude_t<X...>{}) {
        return View<type_list<T...>, type_list<X...>>(std::tuple<Storage<T>*...>(&storage<T>()...),
                                                      std::tuple<Storage<X>*...>(&storage<X>()...));
    }

    /// A new, independent observer of T's changes; see Observer for the semantics. With
    /// ObserverStart::WithExisting, every current T is reported as Constructed at the first look
    /// (O(pool size) once); otherwise the first look reports changes made after this call.
    template <Component T>
    [[nodiscard]] Observer<T> observe(ObserverStart start = ObserverStart::Empty) {
        Storage<T>& pool = storage<T>();
        auto state = std::make_shared<detail::ObserverState>();
        pool.attach_observer(state);
        if (start == ObserverStart::WithExisting) {
            const std::span<const Entity> members = pool.entities();
            for (std::size_t position = 0; position < members.size(); ++position) {
                state->record_constructed(members[position], position);
            }
        }
        return Observer<T>(std::move(state));
    }

    /// Called as fn(registry, entity) right after a T is added (the T is readable).
    template <Component T>
    [[nodiscard]] ComponentSink on_construct() {
        return storage<T>().on_construct();
    }
    /// Called after patch, replace, emplace_or_replace of an existing T, and mark_updated.
    template <Component T>
    [[nodiscard]] ComponentSink on_update() {
        return storage<T>().on_update();
    }
    /// Called right before a T is removed (remove<T> or destroy; the T is still readable). A
    /// handler must not remove that same T from that same entity.
    template <Component T>
    [[nodiscard]] ComponentSink on_destroy() {
        return storage<T>().on_destroy();
    }

    // ---- Pools and context ----------------------------------------------------------------

    /// T's pool, created on first use. The reference is stable for the registry's life.
    template <Component T>
    [[nodiscard]] Storage<T>& storage() {
        const std::size_t index = type_index<T>();
        if (index < storages_.size() && storages_[index]) {
            return static_cast<Storage<T>&>(*storages_[index]);
        }
        return create_storage<T>(index);  // once per type: kept out of the inlined path
    }
    /// T's pool if it exists, else nullptr (never creates one).
    template <Component T>
    [[nodiscard]] const Storage<T>* find_storage() const noexcept {
        const std::size_t index = type_index<T>();
        if (index >= storages_.size() || !storages_[index]) {
            return nullptr;
        }
        return static_cast<const Storage<T>*>(storages_[index].get());
    }

    /// The registry's singletons (see Context).
    [[nodiscard]] Context& ctx() noexcept { return context_; }
    [[nodiscard]] const Context& ctx() const noexcept { return context_; }

  private:
    struct Slot {
        std::uint16_t generation = 0;
        bool alive = false;
        bool dying = false;  // inside destroy(): hooks may read it, nobody may add to it
    };

    void check_valid(Entity entity, const char* operation) const {
        if (!valid(entity)) {
            throw StaleEntityError(entity, operation);
        }
    }
    void check_valid_for_emplace(Entity entity) const;

    template <Component T>
    [[gnu::noinline]] Storage<T>& create_storage(std::size_t index) {
        if (index >= storages_.size()) {
            storages_.resize(index + 1);
        }
        storages_[index] = std::make_unique<Storage<T>>(*this);
        return static_cast<Storage<T>&>(*storages_[index]);
    }

    template <Component T>
    [[nodiscard]] bool has_one(Entity entity) const noexcept {
        const Storage<T>* pool = find_storage<T>();
        return pool != nullptr && pool->contains(entity);
    }

    std::vector<Slot> slots_;
    std::vector<std::uint32_t> free_slots_;
    std::size_t alive_ = 0;
    std::vector<std::unique_ptr<StorageBase>> storages_;
    Signal<Registry&, Entity> on_destroy_entity_;
    // Declared last so it is destroyed first: context objects (hierarchy hooks, caches) may
    // still refer to pools while they shut down.
    Context context_;
};

}  // namespace luxel::ecs
