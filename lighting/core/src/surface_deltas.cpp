#include "luxel/lighting/core/surface_deltas.hpp"

#include <algorithm>

namespace luxel::lighting {

SurfaceDeltas::Position SurfaceDeltas::position(std::uint32_t surface) const {
    return surface < positions_.size() ? positions_[surface] : Position{};
}

SurfaceDeltas::Position& SurfaceDeltas::position_for_update(std::uint32_t surface) {
    if (surface >= positions_.size()) {
        positions_.resize(static_cast<std::size_t>(surface) + 1);
    }
    return positions_[surface];
}

// The counts only grow, so a delta is never negative but for the last bits of rounding in the
// compensated sums; the clamp keeps "no change" exactly 0.
double SurfaceDeltas::full(const PhotonMap& map, std::uint32_t surface) const {
    return std::max(0.0, map.surface(surface).changed_full.value() - position(surface).full);
}

double SurfaceDeltas::indirect(const PhotonMap& map, std::uint32_t surface) const {
    return std::max(0.0,
                    map.surface(surface).changed_indirect.value() - position(surface).indirect);
}

void SurfaceDeltas::consume_full(const PhotonMap& map, std::uint32_t surface) {
    position_for_update(surface).full = map.surface(surface).changed_full.value();
}

void SurfaceDeltas::consume_indirect(const PhotonMap& map, std::uint32_t surface) {
    position_for_update(surface).indirect = map.surface(surface).changed_indirect.value();
}

}  // namespace luxel::lighting
