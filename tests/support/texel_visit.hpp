#pragma once

// Every texel a level's light maps own, with its AIM and IIM values: for tests that judge the
// maps texel by texel.

#include <cstdint>
#include <functional>

#include <glm/glm.hpp>

#include "luxel/lighting/core/illumination_maps.hpp"

namespace luxel::testing {

/// Visits every texel the level's light maps own: (surface, AIM value, IIM value).
inline void for_each_texel(
    const lighting::IlluminationMaps& maps,
    const std::function<void(std::uint32_t, const glm::vec3&, const glm::vec3&)>& visit) {
    for (std::uint32_t s = 0; s < maps.surfaces().size(); ++s) {
        const std::int32_t page = maps.aim().surface_page[s];
        if (page < 0) {
            continue;
        }
        const auto& aim = maps.aim().pages[static_cast<std::size_t>(page)];
        const auto& iim = maps.iim_pages()[static_cast<std::size_t>(page)].current;
        for (const auto& texel : maps.surfaces()[s].texels.texels) {
            visit(s, aim.at(texel.x, texel.y), iim.at(texel.x, texel.y));
        }
    }
}

}  // namespace luxel::testing
