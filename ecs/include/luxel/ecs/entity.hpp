#pragma once

#include <compare>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <string>

namespace luxel::ecs {

/// A handle to an entity: 32 bits holding a slot index (low 22 bits) and a generation (high 10
/// bits). The index addresses the registry's slot and every component pool's sparse index; the
/// generation tells a live handle from a stale one that names a recycled slot.
///
/// Handles are plain values: cheap to copy, hash and compare, and meaningless outside the
/// Registry that created them. A default-constructed Entity is `null_entity`, which no registry
/// ever hands out and which `Registry::valid` always rejects.
///
/// Why 22/10: 4,194,302 entities may be alive at once, and a slot is reused 1,023 times before
/// the registry retires it for good (see Registry::destroy). Retiring rather than wrapping the
/// generation is what makes "a stale handle never hits a recycled slot" a guarantee instead of a
/// likelihood.
class Entity {
  public:
    static constexpr unsigned index_bits = 22;
    static constexpr unsigned generation_bits = 10;
    static constexpr std::uint32_t index_mask = (std::uint32_t{1} << index_bits) - 1;
    static constexpr std::uint32_t generation_mask = (std::uint32_t{1} << generation_bits) - 1;
    /// The largest index a live entity can have; index_mask itself is reserved for null.
    static constexpr std::uint32_t max_index = index_mask - 1;
    /// The largest generation; a slot whose generation reaches it is retired when destroyed.
    static constexpr std::uint32_t max_generation = generation_mask;

    /// The null entity.
    constexpr Entity() noexcept = default;
    constexpr Entity(std::uint32_t index, std::uint32_t generation) noexcept
        : bits_((index & index_mask) | ((generation & generation_mask) << index_bits)) {}

    /// Rebuilds a handle from bits() (for serialisation and hashing; not a way to forge handles:
    /// the registry still checks the generation).
    [[nodiscard]] static constexpr Entity from_bits(std::uint32_t bits) noexcept {
        Entity entity;
        entity.bits_ = bits;
        return entity;
    }

    [[nodiscard]] constexpr std::uint32_t bits() const noexcept { return bits_; }
    [[nodiscard]] constexpr std::uint32_t index() const noexcept { return bits_ & index_mask; }
    [[nodiscard]] constexpr std::uint32_t generation() const noexcept {
        return bits_ >> index_bits;
    }
    [[nodiscard]] constexpr bool is_null() const noexcept { return index() == index_mask; }

    friend constexpr bool operator==(Entity, Entity) noexcept = default;
    friend constexpr auto operator<=>(Entity, Entity) noexcept = default;

  private:
    std::uint32_t bits_ = ~std::uint32_t{0};
};

static_assert(sizeof(Entity) == 4, "an entity handle is 32 bits");

/// The null entity: never valid, the value of a default-constructed Entity.
inline constexpr Entity null_entity{};

/// "12v3" (index 12, generation 3) or "null": the form every ECS error message uses.
[[nodiscard]] std::string to_string(Entity entity);
std::ostream& operator<<(std::ostream& out, Entity entity);

}  // namespace luxel::ecs

template <>
struct std::hash<luxel::ecs::Entity> {
    std::size_t operator()(luxel::ecs::Entity entity) const noexcept {
        return std::hash<std::uint32_t>{}(entity.bits());
    }
};
