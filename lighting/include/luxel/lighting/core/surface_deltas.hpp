#pragma once

#include <cstdint>
#include <vector>

#include "luxel/lighting/core/photon_map.hpp"

namespace luxel::lighting {

/// delta_f and delta_i of every surface (docs/METHOD.md §4.4), owned by the maps that consume
/// them. The photon map only counts: SurfacePhotons::changed_full and changed_indirect grow by
/// the energy of every hit stored on or removed from a surface, and are never reset. A reader
/// keeps its own position in those counts, and its delta is the count minus the position it
/// took when it last consumed the surface (an AIM rebuild began: consume_full; a gather pass
/// began: consume_indirect). So the photon tracer is the photon map's only writer, the maps
/// read it const, and a second reader (a tool, a test) can keep deltas of its own.
class SurfaceDeltas {
  public:
    /// delta_f of `surface`: energy changed on it since consume_full (or since it was created).
    [[nodiscard]] double full(const PhotonMap& map, std::uint32_t surface) const;
    /// delta_i of `surface`: the same for hits with at least one bounce, since consume_indirect.
    [[nodiscard]] double indirect(const PhotonMap& map, std::uint32_t surface) const;

    /// The surface's AIM rebuild began: what changed until now is in it, delta_f is 0.
    void consume_full(const PhotonMap& map, std::uint32_t surface);
    /// A gather pass over the surface began: delta_i is 0.
    void consume_indirect(const PhotonMap& map, std::uint32_t surface);

  private:
    struct Position {
        double full = 0.0;
        double indirect = 0.0;
    };
    [[nodiscard]] Position position(std::uint32_t surface) const;
    Position& position_for_update(std::uint32_t surface);

    std::vector<Position> positions_;  ///< by surface; surfaces past the end are at 0
};

}  // namespace luxel::lighting
