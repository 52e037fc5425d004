#pragma once

#include <cstddef>
#include <string_view>
#include <type_traits>

namespace luxel::ecs {

/// What the ECS accepts as a component: an object type that can be moved into and out of a
/// dense array (swap-and-pop moves the last element into a removed one's place). No registration
/// step exists; using a type is enough.
template <class T>
concept Component =
    std::is_object_v<T> && !std::is_const_v<T> && !std::is_volatile_v<T> && !std::is_array_v<T> &&
    std::is_move_constructible_v<T> && std::is_move_assignable_v<T> && std::is_destructible_v<T>;

namespace detail {

/// Hands out 0, 1, 2, ...: one value per component type, the first time the type is used.
/// The counter is process-wide but only names types; it holds no per-registry state, so any
/// number of registries coexist and each indexes its own pools with these numbers.
std::size_t next_type_index() noexcept;

/// Whether no type appears twice in T...
template <class... T>
inline constexpr bool unique_types = true;
template <class Head, class... Rest>
inline constexpr bool unique_types<Head, Rest...> =
    (!std::is_same_v<Head, Rest> && ...) && unique_types<Rest...>;

}  // namespace detail

/// A small dense integer naming component type T, stable for the life of the process. Registries
/// use it to index their vector of pools in O(1). Thread-safe (static local initialisation).
template <class T>
[[nodiscard]] std::size_t type_index() noexcept {
    static const std::size_t index = detail::next_type_index();
    return index;
}

/// The readable name of T ("Position", "luxel::ecs::Transform"), for error messages. Taken from
/// the compiler's pretty function signature, so it costs nothing at run time and needs no RTTI.
template <class T>
[[nodiscard]] constexpr std::string_view type_name() noexcept {
#if defined(__clang__) || defined(__GNUC__)
    std::string_view signature = __PRETTY_FUNCTION__;
    // GCC: "... type_name() [with T = Foo; std::string_view = ...]"; Clang: "... [T = Foo]".
    const std::size_t start = signature.find("T = ");
    if (start == std::string_view::npos) {
        return "component";
    }
    signature.remove_prefix(start + 4);
    const std::size_t end = signature.find_first_of(";]");
    return signature.substr(0, end);
#else
    return "component";
#endif
}

}  // namespace luxel::ecs
