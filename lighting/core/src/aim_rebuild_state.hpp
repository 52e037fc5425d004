#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "luxel/lighting/core/illumination_maps.hpp"
#include "luxel/lighting/core/photon_density.hpp"

namespace luxel::lighting {

/// A rebuild in progress: the surface's kd-tree (the only one in memory) and where it got to.
struct IlluminationMaps::AimRebuildState {
    std::uint32_t surface = 0;
    std::unique_ptr<PhotonDensity> density;
    std::vector<GatherTexel> texels;  ///< world space, at the rebuild's start
    std::size_t cursor = 0;
};

}  // namespace luxel::lighting
