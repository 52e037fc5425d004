#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "luxel/ecs/entity.hpp"

namespace luxel::ecs {

/// A set of entities with O(1) insert, erase and lookup and a packed array to iterate: the
/// building block of component pools and change lists.
///
/// Layout: `dense` holds the members contiguously (iteration order); `sparse` maps an entity's
/// index to its position in `dense`. The sparse index is paged (4,096 entries, 16 KiB per page),
/// and a page exists only once an entity in its range has been inserted, so a set of ten entities
/// with indices near four million costs one page, not sixteen megabytes.
///
/// Membership is exact: contains(e) compares the whole handle stored in `dense`, generation
/// included, so a stale handle is never taken for the entity that now owns its slot. At most one
/// handle per index is a member at a time.
///
/// Erase is swap-and-pop: the last member moves into the erased one's position. Positions, and
/// so iteration order, change only through erase.
class SparseSet {
  public:
    static constexpr std::size_t page_size = 4096;
    static constexpr std::size_t npos = std::numeric_limits<std::size_t>::max();

    SparseSet() = default;
    SparseSet(SparseSet&&) noexcept = default;
    SparseSet& operator=(SparseSet&&) noexcept = default;
    SparseSet(const SparseSet&) = delete;
    SparseSet& operator=(const SparseSet&) = delete;
    ~SparseSet() = default;

    [[nodiscard]] std::size_t size() const noexcept { return dense_.size(); }
    [[nodiscard]] bool empty() const noexcept { return dense_.empty(); }

    /// The members, packed, in position order. Invalidated by insert and erase.
    [[nodiscard]] std::span<const Entity> entities() const noexcept { return dense_; }
    [[nodiscard]] Entity operator[](std::size_t position) const noexcept {
        return dense_[position];
    }
    [[nodiscard]] const Entity* data() const noexcept { return dense_.data(); }

    /// O(1). Exact handle comparison (generation included).
    [[nodiscard]] bool contains(Entity entity) const noexcept { return find(entity) != npos; }

    /// Position of `entity` in entities(), or npos. O(1).
    [[nodiscard]] std::size_t find(Entity entity) const noexcept {
        const std::uint32_t index = entity.index();
        const std::size_t page = index / page_size;
        if (page >= pages_.size() || !pages_[page]) {
            return npos;
        }
        const std::uint32_t position = pages_[page][index % page_size];
        // A tombstone (max uint32) fails the bound check; a position left over from an erased
        // member fails the handle comparison.
        if (position >= dense_.size() || dense_[position] != entity) {
            return npos;
        }
        return position;
    }

    /// Appends `entity`, which must not be a member and must not be null. Returns its position.
    /// Amortised O(1); may allocate one sparse page.
    std::size_t insert(Entity entity) {
        const std::size_t position = dense_.size();
        const std::size_t block = position / block_size;
        if (block >= block_versions_.size()) {
            block_versions_.resize(block + 1, 0);
        }
        std::uint32_t& slot = sparse_slot(entity.index());
        dense_.push_back(entity);  // the last step that can throw
        slot = static_cast<std::uint32_t>(position);
        block_versions_[block] = ++version_;
        return position;
    }

    /// Removes the member at `position` by moving the last member into it. O(1).
    void erase_at(std::size_t position) noexcept {
        const Entity removed = dense_[position];
        const Entity last = dense_.back();
        dense_[position] = last;
        pages_[last.index() / page_size][last.index() % page_size] =
            static_cast<std::uint32_t>(position);
        pages_[removed.index() / page_size][removed.index() % page_size] = tombstone;
        dense_.pop_back();
        // Both blocks exist: they held members until now.
        block_versions_[position / block_size] = ++version_;
        block_versions_[dense_.size() / block_size] = version_;
    }

    /// Removes `entity` if it is a member; returns whether it was. O(1).
    bool erase(Entity entity) noexcept {
        const std::size_t position = find(entity);
        if (position == npos) {
            return false;
        }
        erase_at(position);
        return true;
    }

    /// Removes every member. O(size): only the touched sparse entries are reset, and the pages
    /// and the dense capacity are kept for reuse.
    void clear() noexcept {
        for (const Entity entity : dense_) {
            pages_[entity.index() / page_size][entity.index() % page_size] = tombstone;
        }
        dense_.clear();
        block_versions_.clear();
        ++version_;
    }

    /// Reserves room for `capacity` members. Counts as a change (version()): the pool's arrays
    /// may move, and a view walking them must re-read where they are.
    void reserve(std::size_t capacity) {
        dense_.reserve(capacity);
        ++version_;
    }

    /// Changes whenever a member is inserted, erased or moved, and on reserve(): a view compares
    /// it across a callback to know whether the positions and arrays it is using still hold.
    [[nodiscard]] std::uint64_t version() const noexcept { return version_; }

    /// Positions per block for block_version().
    static constexpr std::size_t block_size = 1024;
    /// The version() at the last change to positions [block * block_size, +block_size), or 0 for
    /// a block that never held a member (since the last clear). Equal values across two calls mean
    /// the block's members are the same, in the same order: a view that checked two pools line up
    /// there need not check again.
    [[nodiscard]] std::uint64_t block_version(std::size_t block) const noexcept {
        return block < block_versions_.size() ? block_versions_[block] : 0;
    }

  private:
    static constexpr std::uint32_t tombstone = std::numeric_limits<std::uint32_t>::max();

    std::uint32_t& sparse_slot(std::uint32_t index) {
        const std::size_t page = index / page_size;
        if (page >= pages_.size()) {
            pages_.resize(page + 1);
        }
        if (!pages_[page]) {
            pages_[page] = std::make_unique_for_overwrite<std::uint32_t[]>(page_size);
            std::fill_n(pages_[page].get(), page_size, tombstone);
        }
        return pages_[page][index % page_size];
    }

    std::vector<Entity> dense_;
    std::vector<std::unique_ptr<std::uint32_t[]>> pages_;
    std::vector<std::uint64_t> block_versions_;
    std::uint64_t version_ = 0;
};

}  // namespace luxel::ecs
