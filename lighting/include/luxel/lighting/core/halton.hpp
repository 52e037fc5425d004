#pragma once

#include <array>
#include <cstdint>
#include <utility>

#include <glm/glm.hpp>

/// Quasi-Monte Carlo points (docs/METHOD.md §2). Photon i of a light always gets the same sample,
/// so a retraced photon follows the same initial direction and results do not depend on threads.
namespace luxel::lighting {

/// The first 32 primes: the Halton bases of sample dimensions 0-31.
inline constexpr std::array<std::uint32_t, 32> kHaltonPrimes = {
    2,  3,  5,  7,  11, 13, 17, 19, 23, 29,  31,  37,  41,  43,  47,  53,
    59, 61, 67, 71, 73, 79, 83, 89, 97, 101, 103, 107, 109, 113, 127, 131};

/// The radical inverse as the sum of its digits' weights, each term rounded: the definition,
/// for any base and index, and the baseline `luxel_photon_bench`'s `RadicalInverse` compares
/// the per-prime quotients with. Every digit costs a 64-bit division.
[[nodiscard]] inline double radical_inverse_sum(std::uint32_t base, std::uint64_t index) {
    const double inverse_base = 1.0 / static_cast<double>(base);
    double weight = inverse_base;
    double result = 0.0;
    while (index > 0) {
        result += static_cast<double>(index % base) * weight;
        index /= base;
        weight *= inverse_base;
    }
    return result;
}

namespace detail {

[[nodiscard]] inline std::uint64_t reverse_bits(std::uint64_t x) {
    x = __builtin_bswap64(x);
    x = ((x >> 4) & 0x0F0F0F0F0F0F0F0Full) | ((x & 0x0F0F0F0F0F0F0F0Full) << 4);
    x = ((x >> 2) & 0x3333333333333333ull) | ((x & 0x3333333333333333ull) << 2);
    x = ((x >> 1) & 0x5555555555555555ull) | ((x & 0x5555555555555555ull) << 1);
    return x;
}

/// Phi_b(i) as one quotient: the base-b digits of i reversed into an integer numerator over b^k
/// (k digits). Both stay below 2^53 for every index below 2^32 and base up to 131 (b^k <= i b
/// < 2^40), so they are exact in double and the result is the correctly rounded value; the sum
/// of rounded terms is not. Always inlined so that a base known at compile time turns the digit
/// divisions into multiplications.
[[gnu::always_inline]] inline double reversed_digits_quotient(std::uint32_t base,
                                                              std::uint64_t index) {
    std::uint64_t reversed = 0;
    std::uint64_t scale = 1;
    while (index > 0) {
        const std::uint64_t next = index / base;
        reversed = reversed * base + (index - next * base);
        scale *= base;
        index = next;
    }
    return static_cast<double>(reversed) / static_cast<double>(scale);
}

/// Phi_b(i) for a base known at compile time. The photon tracer's dimensions dispatch to one
/// instance per prime: with a hardware division per digit, photon_sample was 14% of a photon
/// trace's profile (issue 24; `luxel_photon_bench --benchmark_filter=RadicalInverse` times both).
template <std::uint32_t Base>
[[nodiscard]] inline double radical_inverse_of(std::uint64_t index) {
    static_assert(Base >= 2, "a radical inverse needs a base of at least 2");
    if constexpr (Base == 2) {
        // Base 2 reverses the bits: exact for every index below 2^53.
        return static_cast<double>(reverse_bits(index) >> 11) * 0x1.0p-53;
    } else {
        return index < (std::uint64_t{1} << 32) ? reversed_digits_quotient(Base, index)
                                                : radical_inverse_sum(Base, index);
    }
}

template <std::size_t... Dims>
constexpr std::array<double (*)(std::uint64_t), sizeof...(Dims)> radical_inverse_table(
    std::index_sequence<Dims...> /*dims*/) {
    return {&radical_inverse_of<kHaltonPrimes[Dims]>...};
}

inline constexpr auto kRadicalInverses =
    radical_inverse_table(std::make_index_sequence<kHaltonPrimes.size()>{});

}  // namespace detail

/// The radical inverse Phi_b(i) = sum_j a_j(i) b^(-j-1), where a_j(i) are the base-b digits of
/// i. In [0, 1); computed in double so that indices up to 2^32 keep full float resolution, and
/// correctly rounded for indices below 2^32.
[[nodiscard]] inline double radical_inverse(std::uint32_t base, std::uint64_t index) {
    if (base == 2) {
        return detail::radical_inverse_of<2>(index);
    }
    if (base < 2) {
        return 0.0;  // no digits in base 0 or 1 (the sum would never end)
    }
    return index < (std::uint64_t{1} << 32) ? detail::reversed_digits_quotient(base, index)
                                            : radical_inverse_sum(base, index);
}

/// The radical inverse in the dim-th prime (dim < 32), the bases of the photons' sample
/// dimensions: equal to radical_inverse(kHaltonPrimes[dim], index), without a division per digit.
[[nodiscard]] inline double radical_inverse_in_dimension(std::uint32_t dim, std::uint64_t index) {
    return detail::kRadicalInverses[dim](index);
}

/// The 2D Halton point of index i with the prime bases 2 and 3.
[[nodiscard]] inline glm::dvec2 halton2(std::uint64_t index) {
    return {detail::radical_inverse_of<2>(index), detail::radical_inverse_of<3>(index)};
}

}  // namespace luxel::lighting
