#include "luxel/lighting/core/photon_map.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <string>

#include "luxel/lighting/core/splitmix.hpp"
#include "luxel/runtime/error.hpp"

namespace luxel::lighting {
namespace {

double energy_of(const glm::vec3& power) {
    return static_cast<double>(power.r) + static_cast<double>(power.g) +
           static_cast<double>(power.b);
}

bool is_stored(const TracedHop& hop, std::size_t surface_count) {
    return hop.surface >= 0 && static_cast<std::size_t>(hop.surface) < surface_count;
}

// Half floats for powers in [0, 1]. glm's packHalf1x16 / unpackHalf1x16 handle signs,
// infinities and NaN with branches that made them a tenth of a retrace's store (perf, the
// RetraceStore benchmark); for this range both directions are a shift and an add. Rounding is
// to nearest, ties to even (glm rounds ties away from zero, a bias upwards in every sum of such
// powers); PhotonMapStorage checks every half up to 1.
constexpr std::uint32_t kHalfExponentShift = (127u - 15u) << 23;  // float bias - half bias
constexpr float kSmallestNormalHalf = 6.103515625e-05f;           // 2^-14
constexpr float kHalfDenormalStep = 5.9604644775390625e-08f;      // 2^-24

std::uint16_t unit_to_half(float x) {
    if (!(x > 0.0f)) {
        return 0;  // zero and NaN
    }
    if (x >= 1.0f) {
        return 0x3C00;
    }
    if (x < kSmallestNormalHalf) {
        return static_cast<std::uint16_t>(std::nearbyint(x / kHalfDenormalStep));
    }
    const auto bits = std::bit_cast<std::uint32_t>(x);
    // Round the 23-bit mantissa to 10 bits, ties to even; a carry moves into the exponent.
    const std::uint32_t rounded = bits + 0x0FFFu + ((bits >> 13) & 1u);
    return static_cast<std::uint16_t>((rounded - kHalfExponentShift) >> 13);
}

float half_to_float(std::uint16_t half) {
    if (half < 0x0400) {
        return static_cast<float>(half) * kHalfDenormalStep;
    }
    return std::bit_cast<float>((static_cast<std::uint32_t>(half) << 13) + kHalfExponentShift);
}

/// Folds `value` into `state`: a hash-combine step, then a step of splitmix64, so that a one-bit
/// change anywhere moves about half of the result's bits.
std::uint64_t mix(std::uint64_t state, std::uint64_t value) {
    std::uint64_t combined = state ^ (value + (state << 6) + (state >> 2));
    return splitmix64(combined);
}

/// The index of the grid cell holding `x`, for a finite coordinate; far or non-finite values
/// share the outermost cells (a tracer never stores them; this only keeps the cast defined).
std::int64_t cell_of(float x, double inverse_cell) {
    const double index = std::floor(static_cast<double>(x) * inverse_cell);
    constexpr double kLimit = 1e15;
    if (!(index > -kLimit)) {
        return std::isnan(index) ? 0 : -static_cast<std::int64_t>(kLimit);
    }
    return static_cast<std::int64_t>(std::min(index, kLimit));
}

constexpr std::uint32_t kMaxIndex = std::numeric_limits<std::uint32_t>::max();
constexpr std::uint32_t kGroupBits = 24;
constexpr std::uint32_t kGroupMask = (1u << kGroupBits) - 1u;
constexpr std::size_t kMaxGroups = kGroupMask;

std::uint32_t group_of(std::uint32_t owner) {
    return owner & kGroupMask;
}
std::uint32_t bounces_of(std::uint32_t owner) {
    return owner >> kGroupBits;
}

}  // namespace

namespace {

/// `surface_count`, once the map's arguments are known to be sound (before anything is
/// allocated for them).
std::size_t checked_surface_count(std::size_t surface_count, std::size_t group_count,
                                  const DivergenceTolerance& tolerance) {
    if (!(tolerance.distance > 0.0f) || !std::isfinite(tolerance.distance)) {
        throw Error("PhotonMap: the divergence tolerance must be a positive distance");
    }
    if (surface_count >= kMaxIndex || group_count > kMaxGroups) {
        throw Error("PhotonMap: at most 2^32 - 1 surfaces and 2^24 - 1 photon groups");
    }
    return surface_count;
}

}  // namespace

PhotonMap::PhotonMap(std::size_t surface_count, std::size_t group_count,
                     DivergenceTolerance tolerance)
    : surfaces_(checked_surface_count(surface_count, group_count, tolerance)),
      groups_(group_count),
      // Cells this wide put a point that moved farther than the tolerance in another cell along
      // at least one axis.
      inverse_cell_(std::sqrt(3.0) / static_cast<double>(tolerance.distance)),
      clearing_(group_count, 0),
      touched_(surface_count, 0) {}

std::uint32_t PhotonMap::add_surfaces(std::size_t count) {
    if (surfaces_.size() + count >= kMaxIndex) {
        throw Error("PhotonMap: at most 2^32 - 1 surfaces");
    }
    const auto first = static_cast<std::uint32_t>(surfaces_.size());
    surfaces_.resize(surfaces_.size() + count);
    touched_.resize(surfaces_.size(), 0);
    return first;
}

std::uint32_t PhotonMap::add_groups(std::size_t count) {
    if (groups_.size() + count > kMaxGroups) {
        throw Error("PhotonMap: at most 2^24 - 1 photon groups");
    }
    const auto first = static_cast<std::uint32_t>(groups_.size());
    groups_.resize(groups_.size() + count);
    clearing_.resize(groups_.size(), 0);
    return first;
}

glm::vec3 PhotonMap::power(std::uint32_t owner, const HalfPower& power) const {
    const float scale = groups_[group_of(owner)].power_scale;
    return glm::vec3(half_to_float(power[0]), half_to_float(power[1]), half_to_float(power[2])) *
           scale;
}

StoredHit PhotonMap::hit(std::uint32_t surface, std::size_t index) const {
    const SurfacePhotons& photons = surfaces_[surface];
    const std::uint32_t owner = photons.owners[index];
    return {photons.positions[index], power(owner, photons.powers[index]), group_of(owner),
            bounces_of(owner)};
}

void PhotonMap::clear_group(std::uint32_t group) {
    clear_groups(std::span<const std::uint32_t>(&group, 1));
}

void PhotonMap::clear_groups(std::span<const std::uint32_t> groups) {
    // Hits do not know their slot in a path (the back-references that made removal O(1) a hit
    // took 16 of the 46 bytes a hit cost): every surface the cleared groups' hits lie on is
    // passed over once, however many of those groups it holds.
    for (std::uint32_t group : groups) {
        if (group >= groups_.size()) {
            throw Error("PhotonMap: no photon group " + std::to_string(group));
        }
    }
    std::vector<std::uint32_t> surfaces;
    for (std::uint32_t group : groups) {
        clearing_[group] = 1;
        for (std::uint32_t surface : groups_[group].surfaces) {
            if (touched_[surface] == 0) {
                touched_[surface] = 1;
                surfaces.push_back(surface);
            }
        }
    }
    for (std::uint32_t surface : surfaces) {
        touched_[surface] = 0;
        SurfacePhotons& target = surfaces_[surface];
        // Only the owners are read to find the hits; each hit found is filled by the last one
        // (which is looked at in its turn), so the work beyond that read is per hit removed.
        std::size_t size = target.owners.size();
        std::size_t i = 0;
        while (i < size) {
            const std::uint32_t owner = target.owners[i];
            if (clearing_[group_of(owner)] == 0) {
                ++i;
                continue;
            }
            const double energy = energy_of(power(owner, target.powers[i]));
            target.stored_energy.subtract(energy);
            target.changed_full.add(energy);
            if (bounces_of(owner) > 0) {
                target.changed_indirect.add(energy);
            }
            --size;
            target.positions[i] = target.positions[size];
            target.powers[i] = target.powers[size];
            target.owners[i] = target.owners[size];
        }
        stored_hits_ -= target.owners.size() - size;
        target.positions.resize(size);
        target.powers.resize(size);
        target.owners.resize(size);
    }
    for (std::uint32_t group : groups) {
        clearing_[group] = 0;
        GroupPaths& paths = groups_[group];
        paths.fingerprints.clear();
        paths.surfaces.clear();
        paths.power_scale = 0.0f;
    }
}

void PhotonMap::replace_group(std::uint32_t group, const TracedGroup& traced) {
    replace_groups(std::span<const std::uint32_t>(&group, 1),
                   std::span<const TracedGroup>(&traced, 1));
}

void PhotonMap::replace_groups(std::span<const std::uint32_t> groups,
                               std::span<const TracedGroup> traced) {
    if (groups.size() != traced.size()) {
        throw Error("PhotonMap::replace_groups: " + std::to_string(groups.size()) + " groups but " +
                    std::to_string(traced.size()) + " traced groups");
    }
    std::vector<std::uint32_t> sorted(groups.begin(), groups.end());
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) {
        throw Error("PhotonMap::replace_groups: a group is listed twice");
    }
    // Checked before anything changes: a bad path leaves the map as it was.
    for (std::size_t i = 0; i < groups.size(); ++i) {
        const std::vector<std::uint32_t>& starts = traced[i].starts;
        for (std::size_t k = 0; k + 1 < starts.size(); ++k) {
            if (starts[k] > starts[k + 1] || starts[k + 1] > traced[i].hops.size()) {
                throw Error("PhotonMap: photon " + std::to_string(k) + " of group " +
                            std::to_string(groups[i]) + " has hops " + std::to_string(starts[k]) +
                            ".." + std::to_string(starts[k + 1]) + " of " +
                            std::to_string(traced[i].hops.size()));
            }
        }
    }
    clear_groups(groups);
    for (std::size_t i = 0; i < groups.size(); ++i) {
        store_group(groups[i], traced[i]);
    }
}

void PhotonMap::store_group(std::uint32_t group, const TracedGroup& traced) {
    GroupPaths& paths = groups_[group];
    float scale = 0.0f;
    for (const TracedHop& hop : traced.hops) {
        if (is_stored(hop, surfaces_.size())) {
            const float brightest = std::max({hop.power.r, hop.power.g, hop.power.b});
            if (std::isfinite(brightest)) {
                scale = std::max(scale, brightest);
            }
        }
    }
    paths.power_scale = scale;
    const float inverse = scale > 0.0f ? 1.0f / scale : 0.0f;

    const std::size_t photons = traced.starts.empty() ? 0 : traced.starts.size() - 1;
    paths.fingerprints.resize(photons);
    for (std::size_t k = 0; k < photons; ++k) {
        const std::uint32_t begin = traced.starts[k];
        const std::uint32_t end = traced.starts[k + 1];
        paths.fingerprints[k] =
            fingerprint(std::span<const TracedHop>(traced.hops.data() + begin, end - begin));
    }

    for (const TracedHop& hop : traced.hops) {
        if (!is_stored(hop, surfaces_.size())) {
            continue;
        }
        const auto surface = static_cast<std::uint32_t>(hop.surface);
        HalfPower half{};
        for (int c = 0; c < 3; ++c) {
            half[c] = unit_to_half(hop.power[c] * inverse);
        }
        const std::uint32_t bounces = std::min<std::uint32_t>(hop.bounces, 255u);
        const std::uint32_t owner = group | (bounces << kGroupBits);
        SurfacePhotons& target = surfaces_[surface];
        target.positions.push_back(hop.position);
        target.powers.push_back(half);
        target.owners.push_back(owner);
        // What is counted is what hit() will give back, so the running sums match a recount.
        const double energy = energy_of(power(owner, half));
        target.stored_energy.add(energy);
        target.changed_full.add(energy);
        if (bounces > 0) {
            target.changed_indirect.add(energy);
        }
        ++stored_hits_;
        if (touched_[surface] == 0) {
            touched_[surface] = 1;
            paths.surfaces.push_back(surface);
        }
    }
    for (std::uint32_t surface : paths.surfaces) {
        touched_[surface] = 0;
    }
}

std::uint32_t PhotonMap::fingerprint(std::span<const TracedHop> hops) const {
    // One mix a hop: its surface and its three cell indices folded into one word first, with
    // odd multipliers, so that a hop one cell over or on another surface changes the word.
    std::uint64_t state = mix(0x6C7578656Cull, hops.size());
    for (const TracedHop& hop : hops) {
        if (!is_stored(hop, surfaces_.size())) {
            state = mix(state, 0xFFFFFFFF00000000ull | hop.object);
            continue;
        }
        const std::uint64_t word =
            static_cast<std::uint64_t>(cell_of(hop.position.x, inverse_cell_)) *
                0x9E3779B97F4A7C15ull +
            static_cast<std::uint64_t>(cell_of(hop.position.y, inverse_cell_)) *
                0xC2B2AE3D27D4EB4Full +
            static_cast<std::uint64_t>(cell_of(hop.position.z, inverse_cell_)) *
                0x165667B19E3779F9ull +
            static_cast<std::uint64_t>(hop.surface) * 0x27D4EB2F165667C5ull;
        state = mix(state, word);
    }
    return static_cast<std::uint32_t>(state ^ (state >> 32));
}

bool PhotonMap::diverges(std::uint32_t group, std::uint32_t photon,
                         std::span<const TracedHop> hops) const {
    const GroupPaths& paths = groups_.at(group);
    if (photon >= paths.fingerprints.size()) {
        return true;  // never traced
    }
    return paths.fingerprints[photon] != fingerprint(hops);
}

std::size_t PhotonMap::path_count() const {
    std::size_t total = 0;
    for (const auto& group : groups_) {
        total += group.fingerprints.size();
    }
    return total;
}

std::size_t PhotonMap::bytes_used() const {
    std::size_t bytes = surfaces_.capacity() * sizeof(SurfacePhotons) +
                        groups_.capacity() * sizeof(GroupPaths) + clearing_.capacity() +
                        touched_.capacity();
    for (const auto& surface : surfaces_) {
        bytes += surface.positions.capacity() * sizeof(glm::vec3) +
                 surface.powers.capacity() * sizeof(HalfPower) +
                 surface.owners.capacity() * sizeof(std::uint32_t);
    }
    for (const auto& group : groups_) {
        bytes +=
            (group.fingerprints.capacity() + group.surfaces.capacity()) * sizeof(std::uint32_t);
    }
    return bytes;
}

double PhotonMap::recount_energy(std::uint32_t surface) const {
    CompensatedSum total;
    const SurfacePhotons& photons = surfaces_.at(surface);
    for (std::size_t i = 0; i < photons.hit_count(); ++i) {
        total.add(energy_of(power(photons.owners[i], photons.powers[i])));
    }
    return total.value();
}

}  // namespace luxel::lighting
