#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "luxel/ecs/entity.hpp"
#include "luxel/ecs/errors.hpp"
#include "luxel/ecs/sparse_set.hpp"
#include "luxel/ecs/storage.hpp"
#include "luxel/ecs/type_id.hpp"

namespace luxel::ecs {

/// A list of types, as a tag.
template <class... T>
struct type_list {};

/// The exclusion filter of a view: registry.view<A, B>(exclude<C, D>) visits entities that have
/// A and B and have neither C nor D.
template <class... T>
struct exclude_t {
    explicit constexpr exclude_t() = default;
};
template <class... T>
inline constexpr exclude_t<T...> exclude{};

template <class Included, class Excluded>
class View;

/// The entities that have every component in T... and none in X..., with their components.
/// Made by Registry::view; cheap to create (a few pointers, no allocation until each() runs).
///
///     registry.view<Position, Velocity>(exclude<Frozen>).each(
///         [dt](Position& p, const Velocity& v) { p.value += v.value * dt; });
///     registry.view<Position, Velocity>().each([](Entity e, Position& p, Velocity& v) { ... });
///     for (auto [entity, position, velocity] : registry.view<Position, Velocity>()) { ... }
///
/// ## Cost
/// The smallest of the T pools leads (chosen when iteration starts); the walk covers it once:
/// O(size of the smallest pool x number of pools). Pools of components that were added together
/// hold their entities at the same positions ("line up"); each() checks that a block of 1,024
/// positions at a time, and then walks the block reading only the components, exactly like a
/// loop over arrays. Where pools do not line up, each entity costs one O(1) lookup per other
/// pool. A view remembers which blocks lined up, per block, until a pool changes there: keep a
/// view object across frames (it stays valid for the registry's life) and a steady-state each()
/// does not even re-read the entity arrays. Range-for always tests entity by entity.
///
/// Order: the leading pool's dense array, from last to first. Do not rely on any order.
///
/// ## Changing the registry while iterating
/// The walk goes backwards over the leading pool by position, re-reading the pool's size at every
/// step, and each entity is tested when reached (not when iteration starts). Hence:
/// - Destroying the current entity, or adding or removing any of its components, is safe. The
///   rest of the walk is unaffected: swap-and-pop moves an already-visited entity into the
///   vacated position, which lies behind the walk.
/// - Adding components to other entities is safe. An entity that gains the leading component is
///   appended behind the walk and not visited in this pass; an entity not yet reached that gains
///   (or loses) a non-leading or excluded component is visited (or skipped) accordingly.
/// - Removing components from, or destroying, an entity other than the current one never skips a
///   member and never touches freed memory, but if it removes a leading component it moves an
///   already-visited entity in front of the walk, which may then be visited a second time. To
///   stay exactly-once, collect such entities and act on them after the loop.
/// - References handed to the callback follow std::vector rules: adding or removing a T (for any
///   entity) may invalidate every T&. Re-fetch after such a change instead of keeping the old
///   reference.
template <Component... T, Component... X>
class View<type_list<T...>, type_list<X...>> {
    static_assert(sizeof...(T) > 0, "a view needs at least one component type");
    static_assert(detail::unique_types<T..., X...>, "a view names each component type once");
    static constexpr std::size_t included_count = sizeof...(T);

  public:
    View(std::tuple<Storage<T>*...> included, std::tuple<Storage<X>*...> excluded) noexcept
        : included_(included), excluded_(excluded) {}

    /// An upper bound on the number of entities visited: the smallest included pool. O(pools).
    [[nodiscard]] std::size_t size_hint() const noexcept { return pool_size(lead_slot()); }

    /// Whether `entity` has every T and no X. O(pools). A stale handle is simply not contained.
    [[nodiscard]] bool contains(Entity entity) const noexcept {
        return (std::get<Storage<T>*>(included_)->contains(entity) && ...) &&
               !excluded_by_any(entity);
    }

    /// The entity's U (one of T...). Throws MissingComponentError if absent.
    template <class U>
    [[nodiscard]] U& get(Entity entity) const {
        return std::get<Storage<U>*>(included_)->get(entity);
    }

    /// Calls fn(entity, T&...) or fn(T&...) for every entity in the view (see the class comment
    /// for order and for what fn may change).
    template <class Fn>
    void each(Fn&& fn) {
        each_dispatch(fn, lead_slot(), Slots{});
    }

    /// Range-for support: yields std::tuple<Entity, T&...>, with the same semantics as each()
    /// (each() is faster: it can skip the per-entity checks where pools line up).
    class Iterator {
      public:
        using value_type = std::tuple<Entity, T&...>;
        using reference = value_type;
        using difference_type = std::ptrdiff_t;
        using iterator_concept = std::input_iterator_tag;

        Iterator() = default;
        Iterator(View* view, std::size_t lead) noexcept
            : view_(view), lead_set_(&view->pool_set(lead)), lead_(lead), next_(lead_set_->size()) {
            advance();
        }

        [[nodiscard]] value_type operator*() const { return view_->row(current_, found_, Slots{}); }
        Iterator& operator++() {
            advance();
            return *this;
        }
        void operator++(int) { advance(); }
        [[nodiscard]] bool operator==(std::default_sentinel_t) const noexcept { return done_; }

      private:
        void advance() {
            while (next_ > 0) {
                --next_;
                if (next_ >= lead_set_->size()) {
                    next_ = lead_set_->size();  // the pool shrank behind us: resume at its end
                    continue;
                }
                const Entity entity = (*lead_set_)[next_];
                if (view_->match(entity, next_, lead_, found_)) {
                    current_ = entity;
                    return;
                }
            }
            done_ = true;
        }

        View* view_ = nullptr;
        const SparseSet* lead_set_ = nullptr;
        std::size_t lead_ = 0;
        std::size_t next_ = 0;
        Entity current_;
        std::array<std::size_t, included_count> found_{};
        bool done_ = false;
    };

    [[nodiscard]] Iterator begin() { return Iterator(this, lead_slot()); }
    [[nodiscard]] std::default_sentinel_t end() const noexcept { return {}; }

  private:
    using Slots = std::index_sequence_for<T...>;
    using Positions = std::array<std::size_t, included_count>;
    using Versions = std::array<std::uint64_t, included_count>;
    /// The walk goes a block at a time (SparseSet::block_size, 1,024 positions): big enough
    /// that the per-block bookkeeping (a few words, fetched from memory after the previous pass
    /// evicted them) is noise, small enough that a block's entities (4 KiB per pool) stay in L1
    /// between the alignment check and the walk.
    static constexpr std::size_t chunk_size = SparseSet::block_size;

    /// What each() last verified about one block: the pools' block versions at that time and
    /// the end of the range that lined up. While the versions are unchanged the block still
    /// lines up, so a view kept across frames stops re-reading the entity arrays.
    struct AlignedBlock {
        Versions versions{};
        std::size_t verified_end = 0;
    };

    template <std::size_t Slot>
    [[nodiscard]] auto& pool() const noexcept {
        return *std::get<Slot>(included_);
    }

    /// Which of T... has the fewest entities.
    [[nodiscard]] std::size_t lead_slot() const noexcept {
        std::size_t best = 0;
        for (std::size_t slot = 1; slot < included_count; ++slot) {
            if (pool_size(slot) < pool_size(best)) {
                best = slot;
            }
        }
        return best;
    }

    [[nodiscard]] const SparseSet& pool_set(std::size_t slot) const noexcept {
        return pool_set(slot, Slots{});
    }
    template <std::size_t... Slot>
    [[nodiscard]] const SparseSet& pool_set(std::size_t slot,
                                            std::index_sequence<Slot...>) const noexcept {
        const SparseSet* set = nullptr;
        static_cast<void>(
            ((slot == Slot ? (set = &pool<Slot>().entity_set(), true) : false) || ...));
        return *set;
    }
    [[nodiscard]] std::size_t pool_size(std::size_t slot) const noexcept {
        return pool_set(slot).size();
    }

    [[nodiscard]] bool excluded_by_any(Entity entity) const noexcept {
        if constexpr (sizeof...(X) == 0) {
            return false;
        } else {
            return (std::get<Storage<X>*>(excluded_)->contains(entity) || ...);
        }
    }

    /// Position of `entity` in `set`, trying `hint` (the lead's position) first: pools filled in
    /// the same order line up, and then no sparse lookup is needed.
    [[nodiscard]] static std::size_t locate(const SparseSet& set, Entity entity,
                                            std::size_t hint) noexcept {
        if (hint < set.size() && set[hint] == entity) {
            return hint;
        }
        return set.find(entity);
    }

    /// Tests `entity`, found at `position` in the leading pool (slot `lead`); on success fills
    /// `found` with its position in every included pool.
    bool match(Entity entity, std::size_t position, std::size_t lead, Positions& found) const {
        return !excluded_by_any(entity) && locate_all(entity, position, lead, found, Slots{});
    }
    template <std::size_t... Slot>
    bool locate_all(Entity entity, std::size_t position, std::size_t lead, Positions& found,
                    std::index_sequence<Slot...>) const noexcept {
        return ((found[Slot] =
                     Slot == lead ? position : locate(pool<Slot>().entity_set(), entity, position),
                 found[Slot] != SparseSet::npos) &&
                ...);
    }

    template <std::size_t... Slot>
    [[nodiscard]] std::tuple<Entity, T&...> row(Entity entity, const Positions& found,
                                                std::index_sequence<Slot...>) const {
        return std::tuple<Entity, T&...>(entity, pool<Slot>().components()[found[Slot]]...);
    }

    template <class Fn, std::size_t... Slot>
    void each_dispatch(Fn& fn, std::size_t lead, std::index_sequence<Slot...>) {
        static_cast<void>(((lead == Slot ? (each_led_by<Slot>(fn), true) : false) || ...));
    }

    /// The loop of each(), specialised on the leading pool. It walks the lead backwards a chunk at
    /// a time; where the other pools hold the same entities at the same positions (components
    /// added together) the chunk is walked without any lookup, otherwise entity by entity.
    template <std::size_t Lead, class Fn>
    void each_led_by(Fn& fn) {
        const SparseSet& lead_set = pool<Lead>().entity_set();
        std::size_t remaining = lead_set.size();  // positions [0, remaining) are still to walk
        while (remaining > 0) {
            remaining = std::min(remaining, lead_set.size());  // fn may have shrunk the pool
            if (remaining == 0) {
                break;
            }
            const std::size_t begin = (remaining - 1) / chunk_size * chunk_size;
            if (aligned_with_lead<Lead>(begin, remaining, Slots{})) {
                remaining = walk_aligned<Lead>(fn, begin, remaining, Slots{});
            } else {
                remaining = walk_checked<Lead>(fn, begin, remaining);
            }
        }
    }

    /// Whether every included pool holds the lead's entities at positions [begin, end), begin
    /// being the start of a block. Remembered per block (see AlignedBlock).
    template <std::size_t Lead, std::size_t... Slot>
    [[nodiscard]] bool aligned_with_lead(std::size_t begin, std::size_t end,
                                         std::index_sequence<Slot...>) {
        if constexpr (included_count == 1) {
            return true;
        } else {
            const std::size_t block = begin / chunk_size;
            const Versions versions{pool<Slot>().entity_set().block_version(block)...};
            if (block < aligned_blocks_.size() && aligned_blocks_[block].versions == versions &&
                end <= aligned_blocks_[block].verified_end) {
                return true;
            }
            const Entity* lead = pool<Lead>().entity_set().data();
            if (!((Slot == Lead || same_entities(pool<Slot>().entity_set(), lead, begin, end)) &&
                  ...)) {
                return false;
            }
            if (block >= aligned_blocks_.size()) {
                aligned_blocks_.resize(block + 1);
            }
            aligned_blocks_[block] = AlignedBlock{versions, end};
            return true;
        }
    }
    [[nodiscard]] static bool same_entities(const SparseSet& set, const Entity* lead,
                                            std::size_t begin, std::size_t end) noexcept {
        if (end > set.size()) {
            return false;
        }
        // Backwards like the walk that follows, and with no early exit: a straight stream of
        // loads (measured faster here than a forward memcmp of the block).
        const Entity* other = set.data();
        std::uint32_t difference = 0;
        for (std::size_t i = end; i > begin;) {
            --i;
            difference |= lead[i].bits() ^ other[i].bits();
        }
        return difference == 0;
    }

    /// Walks [begin, end) backwards over aligned pools: the components of the entity at position
    /// p are at position p in every pool. Returns begin, or, right after a callback that changed
    /// an included pool (whose positions then no longer hold), the position it stopped at.
    ///
    /// Kept out of line on purpose (fn is still inlined into it): as its own function the loop
    /// gets the registers to itself, and GCC keeps fn's constants in them; inlined into the
    /// block loop it reloaded them every iteration, which cost a third of the walk.
    template <std::size_t Lead, class Fn, std::size_t... Slot>
    [[gnu::noinline]] std::size_t walk_aligned(Fn& fn, std::size_t begin, std::size_t end,
                                               std::index_sequence<Slot...>) {
        const std::array<std::uint64_t, included_count> versions{
            pool<Slot>().entity_set().version()...};
        const Entity* entities = pool<Lead>().entity_set().data();
        const std::tuple<T*...> components{pool<Slot>().components().data()...};
        for (std::size_t position = end; position > begin;) {
            --position;
            const Entity entity = entities[position];
            if (excluded_by_any(entity)) {
                continue;
            }
            invoke_with(fn, entity, std::get<Slot>(components)[position]...);
            if (((pool<Slot>().entity_set().version() != versions[Slot]) || ...)) {
                return position;
            }
        }
        return begin;
    }

    /// Walks [begin, end) backwards testing every entity against the other pools. Returns
    /// begin, or less when fn shrank the lead below begin.
    template <std::size_t Lead, class Fn>
    [[gnu::noinline]] std::size_t walk_checked(Fn& fn, std::size_t begin, std::size_t end) {
        const SparseSet& lead_set = pool<Lead>().entity_set();
        std::size_t position = end;
        while (position > begin) {
            --position;
            if (position >= lead_set.size()) {
                position = lead_set.size();  // fn removed several: resume at the end
                continue;
            }
            const Entity entity = lead_set[position];
            Positions found{};
            if (match(entity, position, Lead, found)) {
                invoke_found(fn, entity, found, Slots{});
            }
        }
        return position;
    }

    template <class Fn, std::size_t... Slot>
    void invoke_found(Fn& fn, Entity entity, const Positions& found, std::index_sequence<Slot...>) {
        invoke_with(fn, entity, pool<Slot>().components()[found[Slot]]...);
    }

    template <class Fn>
    static void invoke_with(Fn& fn, Entity entity, T&... components) {
        if constexpr (std::is_invocable_v<Fn&, Entity, T&...>) {
            fn(entity, components...);
        } else if constexpr (std::is_invocable_v<Fn&, T&...>) {
            fn(components...);
        } else {
            static_assert(std::is_invocable_v<Fn&, T&...>,
                          "View::each expects fn(Entity, T&...) or fn(T&...)");
        }
    }

    std::tuple<Storage<T>*...> included_;
    std::tuple<Storage<X>*...> excluded_;
    std::vector<AlignedBlock> aligned_blocks_;
};

}  // namespace luxel::ecs
