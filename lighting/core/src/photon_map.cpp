#include "luxel/lighting/core/photon_map.hpp"

#include <algorithm>

#include "luxel/runtime/error.hpp"

namespace luxel::lighting {
namespace {

double energy_of(const glm::vec3& power) {
    return static_cast<double>(power.r) + static_cast<double>(power.g) +
           static_cast<double>(power.b);
}

}  // namespace

PhotonMap::PhotonMap(std::size_t surface_count, std::size_t group_count)
    : surfaces_(surface_count), groups_(group_count) {
    if (group_count > 0x00FFFFFFu) {
        throw Error("PhotonMap: at most 2^24 photon groups");
    }
}

std::uint32_t PhotonMap::add_surfaces(std::size_t count) {
    const auto first = static_cast<std::uint32_t>(surfaces_.size());
    surfaces_.resize(surfaces_.size() + count);
    return first;
}

std::uint32_t PhotonMap::add_groups(std::size_t count) {
    if (groups_.size() + count > 0x00FFFFFFu) {
        throw Error("PhotonMap: at most 2^24 photon groups");
    }
    const auto first = static_cast<std::uint32_t>(groups_.size());
    groups_.resize(groups_.size() + count);
    return first;
}

void PhotonMap::remove_hit(std::uint32_t surface, std::uint32_t slot) {
    SurfacePhotons& target = surfaces_[surface];
    const StoredHit removed = target.hits[slot];
    const double energy = energy_of(removed.power);
    target.stored_energy.subtract(energy);
    target.changed_full.add(energy);
    if (removed.bounces() > 0) {
        target.changed_indirect.add(energy);
    }
    // Swap-and-pop: the last hit fills the hole, and the hop that owns it learns its new slot.
    const auto last = static_cast<std::uint32_t>(target.hits.size() - 1);
    if (slot != last) {
        const StoredHit& moved = target.hits[last];
        groups_[moved.group_index()].hops[moved.hop].slot_or_object = slot;
        target.hits[slot] = moved;
    }
    target.hits.pop_back();
    --stored_hits_;
}

void PhotonMap::clear_group(std::uint32_t group) {
    GroupPaths& paths = groups_.at(group);
    for (const HopRecord& hop : paths.hops) {
        if (hop.surface >= 0) {
            remove_hit(static_cast<std::uint32_t>(hop.surface), hop.slot_or_object);
        }
    }
    paths.hops.clear();
    paths.starts.clear();
}

void PhotonMap::replace_group(std::uint32_t group, const TracedGroup& traced) {
    clear_group(group);
    GroupPaths& paths = groups_.at(group);
    paths.starts = traced.starts;
    paths.hops.resize(traced.hops.size());
    for (std::size_t h = 0; h < traced.hops.size(); ++h) {
        const TracedHop& hop = traced.hops[h];
        HopRecord& record = paths.hops[h];
        record.surface = hop.surface;
        if (hop.surface < 0 || static_cast<std::size_t>(hop.surface) >= surfaces_.size()) {
            record.surface = -1;
            record.slot_or_object = hop.object;
            continue;
        }
        SurfacePhotons& target = surfaces_[static_cast<std::size_t>(hop.surface)];
        record.slot_or_object = static_cast<std::uint32_t>(target.hits.size());
        const std::uint32_t bounces = std::min<std::uint32_t>(hop.bounces, 255u);
        target.hits.push_back(
            {hop.position, hop.power, group | (bounces << 24), static_cast<std::uint32_t>(h)});
        const double energy = energy_of(hop.power);
        target.stored_energy.add(energy);
        target.changed_full.add(energy);
        if (bounces > 0) {
            target.changed_indirect.add(energy);
        }
        ++stored_hits_;
    }
}

bool PhotonMap::diverges(std::uint32_t group, std::uint32_t photon, std::span<const TracedHop> hops,
                         const DivergenceTolerance& tolerance) const {
    const GroupPaths& paths = groups_.at(group);
    if (photon + 1 >= paths.starts.size()) {
        return true;  // never traced
    }
    const std::uint32_t begin = paths.starts[photon];
    const std::uint32_t end = paths.starts[photon + 1];
    if (end - begin != hops.size()) {
        return true;
    }
    const float tolerance_squared = tolerance.distance * tolerance.distance;
    for (std::uint32_t h = begin; h < end; ++h) {
        const HopRecord& stored = paths.hops[h];
        const TracedHop& now = hops[h - begin];
        const std::int32_t now_surface =
            now.surface >= 0 && static_cast<std::size_t>(now.surface) < surfaces_.size()
                ? now.surface
                : -1;
        if (stored.surface != now_surface) {
            return true;
        }
        if (stored.surface < 0) {
            if (stored.slot_or_object != now.object) {
                return true;
            }
            continue;
        }
        const StoredHit& hit =
            surfaces_[static_cast<std::size_t>(stored.surface)].hits[stored.slot_or_object];
        const glm::vec3 moved = hit.position - now.position;
        if (glm::dot(moved, moved) > tolerance_squared) {
            return true;
        }
    }
    return false;
}

std::size_t PhotonMap::hop_count() const {
    std::size_t total = 0;
    for (const auto& group : groups_) {
        total += group.hops.size();
    }
    return total;
}

std::size_t PhotonMap::bytes_used() const {
    std::size_t bytes =
        surfaces_.capacity() * sizeof(SurfacePhotons) + groups_.capacity() * sizeof(GroupPaths);
    for (const auto& surface : surfaces_) {
        bytes += surface.hits.capacity() * sizeof(StoredHit);
    }
    for (const auto& group : groups_) {
        bytes += group.hops.capacity() * sizeof(HopRecord) +
                 group.starts.capacity() * sizeof(std::uint32_t);
    }
    return bytes;
}

double PhotonMap::recount_energy(std::uint32_t surface) const {
    CompensatedSum total;
    for (const StoredHit& hit : surfaces_.at(surface).hits) {
        total.add(energy_of(hit.power));
    }
    return total.value();
}

}  // namespace luxel::lighting
