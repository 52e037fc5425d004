#pragma once

#include <memory>
#include <span>
#include <type_traits>
#include <utility>

#include "luxel/ecs/detail/observer_state.hpp"
#include "luxel/ecs/entity.hpp"
#include "luxel/ecs/storage.hpp"
#include "luxel/ecs/type_id.hpp"

namespace luxel::ecs {

/// "What happened to component T since I last looked", for one reader. Created by
/// Registry::observe<T>(); any number of observers may watch the same pool independently, each
/// with its own notion of "last looked" (its last consume() or clear()).
///
/// ## What is reported
/// Net changes over the interval, each entity at most once per kind:
/// - Constructed: entities that got a T during the interval and still have it. Updates made
///   after the construction are folded in (the reader reads the current value anyway).
/// - Updated: entities that had T before the interval, still have it, and were patched,
///   replaced, emplace_or_replace'd or marked updated, any number of times.
/// - Destroyed: entities that had T before the interval and lost it (remove<T> or destroy). The
///   handle may be stale by now; use it as a key, not for access.
/// So an entity constructed, updated and destroyed within one interval is reported nowhere (no
/// reader ever saw it); one constructed in interval 1, updated in interval 2 and destroyed in
/// interval 3 is reported Constructed, Updated, Destroyed by three successive looks. An entity
/// whose T was removed and re-added within an interval (or whose recycled slot got a new T)
/// appears as Destroyed with the old handle and Constructed with the new one. Writes through a
/// plain reference are invisible until mark_updated<T>.
///
/// ## Costs
/// Recording is O(1) per change per attached observer and nothing when a pool has no observer;
/// a change touches one bit per observer (one bit per entity slot, cache-resident) and appends to
/// a list. Reading is O(changes), independent of the pool size, and hands out each component
/// without a sparse lookup in the common case (its recorded position still holds). Memory is
/// bounded by the pool's size, not by elapsed time: an observer that never looks holds at most
/// about two entries per pending entity, so a forgotten observer cannot grow without bound in a
/// long-running game.
///
/// Move-only; destroying it detaches it from the pool. It may outlive its registry, after which
/// it records nothing. Not thread-safe.
template <Component T>
class Observer {
  public:
    /// A detached observer with no changes.
    Observer() = default;
    explicit Observer(std::shared_ptr<detail::ObserverState> state) : state_(std::move(state)) {}
    Observer(Observer&&) noexcept = default;
    Observer& operator=(Observer&& other) noexcept {
        if (this != &other) {
            detach();
            state_ = std::move(other.state_);
        }
        return *this;
    }
    Observer(const Observer&) = delete;
    Observer& operator=(const Observer&) = delete;
    ~Observer() { detach(); }

    /// The pending lists, for reading without consuming (each entity once, in recording order).
    /// Invalidated by any change to T in the registry and by consume()/clear(). Amortised
    /// O(pending) (the first call after changes drops superseded entries).
    [[nodiscard]] std::span<const Entity> constructed() {
        return state_ ? std::span<const Entity>(state_->constructed()) : std::span<const Entity>{};
    }
    [[nodiscard]] std::span<const Entity> updated() {
        return state_ ? std::span<const Entity>(state_->updated()) : std::span<const Entity>{};
    }
    [[nodiscard]] std::span<const Entity> destroyed() const {
        return state_ ? std::span<const Entity>(state_->destroyed()) : std::span<const Entity>{};
    }

    /// Number of pending changes, all kinds. O(1).
    [[nodiscard]] std::size_t size() const noexcept {
        return state_ ? state_->constructed_count() + state_->updated_count() +
                            state_->destroyed_count()
                      : 0;
    }
    [[nodiscard]] bool empty() const noexcept { return size() == 0; }
    /// False for a default-constructed observer and once the registry is destroyed.
    [[nodiscard]] bool attached() const noexcept { return state_ && state_->owner_ != nullptr; }

    /// Marks everything as seen. O(pending).
    void clear() noexcept {
        if (state_) {
            state_->clear();
        }
    }

    /// Calls fn for every pending change and marks them seen: Destroyed ones first (so a mirror
    /// of the pool frees before it allocates), then Constructed, then Updated. fn is either
    ///     fn(Entity, ChangeKind)
    ///     fn(Entity, ChangeKind, T* component)   // nullptr for Destroyed
    /// fn may change the registry freely, T included: those changes are recorded for the next
    /// look. An entity that loses its T (or is destroyed) inside fn before its turn comes is
    /// skipped now and reported Destroyed next time. If fn throws, the changes not yet handed
    /// out are dropped. Not re-entrant on the same observer (EcsError). O(pending).
    template <class Fn>
    void consume(Fn&& fn) {
        if (!state_) {
            return;
        }
        detail::ObserverState& state = *state_;
        state.consume([&](Entity entity, ChangeKind kind, std::size_t position) {
            if constexpr (std::is_invocable_v<Fn&, Entity, ChangeKind, T*>) {
                T* component = nullptr;
                if (position != SparseSet::npos && state.pool_ != nullptr) {
                    component = &static_cast<Storage<T>*>(state.pool_)->components()[position];
                }
                fn(entity, kind, component);
            } else {
                static_assert(std::is_invocable_v<Fn&, Entity, ChangeKind>,
                              "Observer::consume expects fn(Entity, ChangeKind) or "
                              "fn(Entity, ChangeKind, T*)");
                fn(entity, kind);
            }
        });
    }

  private:
    void detach() noexcept {
        if (state_ && state_->owner_ != nullptr) {
            state_->owner_->detach(state_.get());
        }
        state_.reset();
    }

    std::shared_ptr<detail::ObserverState> state_;
};

}  // namespace luxel::ecs
