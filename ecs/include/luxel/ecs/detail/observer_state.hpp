#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "luxel/ecs/entity.hpp"
#include "luxel/ecs/sparse_set.hpp"

namespace luxel::ecs {

class StorageBase;

/// What happened to an entity's component since an observer last looked.
enum class ChangeKind : std::uint8_t {
    Constructed,  ///< the component was added (emplace, emplace_or_replace on a new one)
    Updated,      ///< patch, replace, emplace_or_replace on an existing one, or mark_updated
    Destroyed,    ///< the component was removed, or its entity destroyed
};

/// Where a new observer's change lists start.
enum class ObserverStart {
    Empty,         ///< only changes made after observe() are reported
    WithExisting,  ///< every entity that has the component now is reported as Constructed
};

namespace detail {

class ObserverList;

/// One bit per entity index, grown on demand: "this slot's current entity is pending in a
/// list". 128 KiB covers a million entities, so the per-change membership test of an observer
/// stays in cache where a per-entity position array (4 MiB) would not.
class IndexBits {
  public:
    [[nodiscard]] bool test(std::uint32_t index) const noexcept {
        const std::size_t word = index / 64;
        return word < words_.size() && ((words_[word] >> (index % 64)) & 1u) != 0;
    }
    void set(std::uint32_t index) {
        const std::size_t word = index / 64;
        if (word >= words_.size()) {
            words_.resize(std::max(word + 1, words_.size() * 2), 0);
        }
        words_[word] |= std::uint64_t{1} << (index % 64);
    }
    void reset(std::uint32_t index) noexcept {
        const std::size_t word = index / 64;
        if (word < words_.size()) {
            words_[word] &= ~(std::uint64_t{1} << (index % 64));
        }
    }

  private:
    std::vector<std::uint64_t> words_;
};

/// A list of pending constructed or updated entities, each with the dense position its
/// component had when recorded (a hint that saves a sparse lookup when it still holds).
///
/// Entries are appended and never removed one by one; an entry whose entity later lost the
/// component (destroyed, or removed and re-added) stays behind as a superseded entry. `pending`
/// (the bits) says which slots have a live entry; reading skips superseded entries by checking
/// the bit and the pool. Compaction drops superseded entries once they outnumber live ones, so the
/// list stays within twice the number of entities that are really pending.
struct PendingList {
    std::vector<Entity> entities;
    std::vector<std::uint32_t> positions;
    IndexBits pending;
    std::size_t live = 0;
    /// The pool's version when the oldest entry was recorded. While the pool still has it, no
    /// member was added or removed since, so every recorded position is exact and every entry
    /// whose bit is set is live: reading can skip checking them against the pool.
    std::uint64_t pool_version_at_first = 0;

    void push(Entity entity, std::size_t position, std::uint64_t pool_version) {
        if (entities.empty()) {
            pool_version_at_first = pool_version;
        }
        entities.push_back(entity);
        positions.push_back(static_cast<std::uint32_t>(position));
        pending.set(entity.index());
        ++live;
    }
    void clear() noexcept {
        for (const Entity entity : entities) {
            pending.reset(entity.index());
        }
        entities.clear();
        positions.clear();
        live = 0;
    }
};

/// The change lists of one observer of one pool, net of everything that happened since the
/// observer last looked. See Observer for the semantics.
class ObserverState {
  public:
    void record_constructed(Entity entity, std::size_t position) {
        constructed_.push(entity, position, pool_version());
        compact_if_sparse(constructed_);
    }

    void record_updated(Entity entity, std::size_t position) {
        // Constructed since the last look: reported as Constructed only (the reader reads the
        // current value either way). Already pending as Updated: nothing to add.
        const std::uint32_t index = entity.index();
        if (constructed_.pending.test(index) || updated_.pending.test(index)) {
            return;
        }
        updated_.push(entity, position, pool_version());
        compact_if_sparse(updated_);
    }

    void record_destroyed(Entity entity) {
        const std::uint32_t index = entity.index();
        if (constructed_.pending.test(index)) {
            // Constructed and destroyed between two looks: the reader never saw it.
            constructed_.pending.reset(index);
            --constructed_.live;
            return;
        }
        if (updated_.pending.test(index)) {
            updated_.pending.reset(index);  // Destroyed supersedes Updated
            --updated_.live;
        }
        destroyed_.push_back(entity);
    }

    /// Pending counts. O(1).
    [[nodiscard]] std::size_t constructed_count() const noexcept { return constructed_.live; }
    [[nodiscard]] std::size_t updated_count() const noexcept { return updated_.live; }
    [[nodiscard]] std::size_t destroyed_count() const noexcept { return destroyed_.size(); }

    /// The pending lists with superseded entries dropped. O(list) after changes.
    const std::vector<Entity>& constructed() {
        compact(constructed_);
        return constructed_.entities;
    }
    const std::vector<Entity>& updated() {
        compact(updated_);
        return updated_.entities;
    }
    [[nodiscard]] const std::vector<Entity>& destroyed() const noexcept { return destroyed_; }

    /// Marks everything seen. O(pending entries).
    void clear() noexcept {
        constructed_.clear();
        updated_.clear();
        destroyed_.clear();
    }

    /// Hands every pending change to visit(entity, kind, position) — position is the component's
    /// dense position, or SparseSet::npos for Destroyed — destroyed first, then constructed,
    /// then updated, and marks them seen. Changes recorded while visiting go to fresh lists, for
    /// the next look; an entry whose entity lost the component before being reached is skipped.
    template <class Visit>
    void consume(Visit&& visit) {
        if (consuming_) {
            throw_reentrant_consume();
        }
        std::swap(constructed_, consuming_constructed_);
        std::swap(updated_, consuming_updated_);
        std::swap(destroyed_, consuming_destroyed_);
        struct ConsumeScope {
            ObserverState& state;
            explicit ConsumeScope(ObserverState& consuming) noexcept : state(consuming) {
                state.consuming_ = true;
            }
            ConsumeScope(const ConsumeScope&) = delete;
            ConsumeScope& operator=(const ConsumeScope&) = delete;
            ~ConsumeScope() {
                state.consuming_constructed_.clear();
                state.consuming_updated_.clear();
                state.consuming_destroyed_.clear();
                state.consuming_ = false;
            }
        } scope(*this);
        for (const Entity entity : consuming_destroyed_) {
            visit(entity, ChangeKind::Destroyed, SparseSet::npos);
        }
        visit_pending(consuming_constructed_, ChangeKind::Constructed, visit);
        visit_pending(consuming_updated_, ChangeKind::Updated, visit);
    }

    /// The pool's entities (for checking entries) and the pool itself (for typed access); both
    /// null once the pool is destroyed.
    const SparseSet* members_ = nullptr;
    StorageBase* pool_ = nullptr;
    /// The pool's observer list; null once the pool is destroyed.
    ObserverList* owner_ = nullptr;

  private:
    [[noreturn]] static void throw_reentrant_consume();

    [[nodiscard]] std::uint64_t pool_version() const noexcept {
        return members_ != nullptr ? members_->version() : 0;
    }

    /// Where `entity` is in the pool now, or npos: the recorded position if it still holds the
    /// entity, else a sparse lookup. Without a pool (registry gone), entries are taken on trust.
    [[nodiscard]] std::size_t current_position(Entity entity, std::uint32_t hint) const noexcept {
        if (members_ == nullptr) {
            return hint;
        }
        if (hint < members_->size() && (*members_)[hint] == entity) {
            return hint;
        }
        return members_->find(entity);
    }

    /// Hands out the live entries of `list`. Two passes: the first, with no callback in it,
    /// resolves every entry's current position in a tight loop (many cache misses in flight at
    /// once); the second calls visit, re-resolving only if a callback has changed the pool.
    template <class Visit>
    void visit_pending(PendingList& list, ChangeKind kind, Visit& visit) {
        resolved_entities_.clear();
        resolved_positions_.clear();
        const bool positions_exact =
            members_ != nullptr && members_->version() == list.pool_version_at_first;
        for (std::size_t i = 0; i < list.entities.size(); ++i) {
            const Entity entity = list.entities[i];
            if (!list.pending.test(entity.index())) {
                continue;  // superseded, or a duplicate already taken
            }
            const std::size_t position =
                positions_exact ? list.positions[i] : current_position(entity, list.positions[i]);
            if (position == SparseSet::npos) {
                continue;  // superseded: the slot's current entity is another one
            }
            list.pending.reset(entity.index());
            resolved_entities_.push_back(entity);
            resolved_positions_.push_back(static_cast<std::uint32_t>(position));
        }
        const std::uint64_t version = members_ != nullptr ? members_->version() : 0;
        for (std::size_t i = 0; i < resolved_entities_.size(); ++i) {
            const Entity entity = resolved_entities_[i];
            std::size_t position = resolved_positions_[i];
            if (members_ != nullptr && members_->version() != version) {
                position = current_position(entity, resolved_positions_[i]);
                if (position == SparseSet::npos) {
                    continue;  // lost its component to an earlier callback
                }
            }
            visit(entity, kind, position);
        }
    }

    /// Drops superseded entries and duplicates, keeping order.
    void compact(PendingList& list) {
        if (list.entities.size() == list.live) {
            return;
        }
        std::size_t kept = 0;
        for (std::size_t i = 0; i < list.entities.size(); ++i) {
            const Entity entity = list.entities[i];
            if (!list.pending.test(entity.index())) {
                continue;
            }
            const std::size_t position = current_position(entity, list.positions[i]);
            if (position == SparseSet::npos) {
                continue;
            }
            list.pending.reset(entity.index());  // so a later duplicate is dropped
            list.entities[kept] = entity;
            list.positions[kept] = static_cast<std::uint32_t>(position);
            ++kept;
        }
        list.entities.resize(kept);
        list.positions.resize(kept);
        list.pool_version_at_first = pool_version();  // every position is current now
        for (const Entity entity : list.entities) {
            list.pending.set(entity.index());
        }
        list.live = kept;
    }

    void compact_if_sparse(PendingList& list) {
        if (list.entities.size() > 2 * list.live + 64) {
            compact(list);
        }
    }

    PendingList constructed_;
    PendingList updated_;
    std::vector<Entity> destroyed_;
    // The lists being handed out by consume(); swapped with the live ones so that changes made
    // while consuming are recorded for the next look.
    PendingList consuming_constructed_;
    PendingList consuming_updated_;
    std::vector<Entity> consuming_destroyed_;
    // visit_pending's first pass, kept to reuse the allocation.
    std::vector<Entity> resolved_entities_;
    std::vector<std::uint32_t> resolved_positions_;
    bool consuming_ = false;
};

/// A pool's observers. Destroying the list detaches them, so an observer may outlive its
/// registry (it then reports what it had and records nothing more).
class ObserverList {
  public:
    ObserverList() = default;
    ObserverList(const ObserverList&) = delete;
    ObserverList& operator=(const ObserverList&) = delete;
    ~ObserverList() {
        for (const auto& state : states_) {
            state->owner_ = nullptr;
            state->members_ = nullptr;
            state->pool_ = nullptr;
        }
    }

    void attach(std::shared_ptr<ObserverState> state, const SparseSet& members, StorageBase& pool) {
        state->owner_ = this;
        state->members_ = &members;
        state->pool_ = &pool;
        states_.push_back(std::move(state));
    }
    void detach(const ObserverState* state) noexcept {
        std::erase_if(states_, [state](const auto& held) { return held.get() == state; });
    }
    [[nodiscard]] bool empty() const noexcept { return states_.empty(); }
    [[nodiscard]] std::size_t size() const noexcept { return states_.size(); }

    void record_constructed(Entity entity, std::size_t position) {
        for (const auto& state : states_) {
            state->record_constructed(entity, position);
        }
    }
    void record_updated(Entity entity, std::size_t position) {
        for (const auto& state : states_) {
            state->record_updated(entity, position);
        }
    }
    void record_destroyed(Entity entity) {
        for (const auto& state : states_) {
            state->record_destroyed(entity);
        }
    }

  private:
    std::vector<std::shared_ptr<ObserverState>> states_;
};

}  // namespace detail

}  // namespace luxel::ecs
