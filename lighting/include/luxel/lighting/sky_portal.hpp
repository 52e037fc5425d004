#pragma once

#include <vector>

#include <glm/glm.hpp>

namespace luxel::lighting {

/// An opening through which the sky and the sun light an interior: a window or a doorway, given
/// by a node with extras.luxel.portal = true (docs/LEVELS.md, "Sky"). When a level has portals,
/// the photons of its skies and directional lights start on them instead of on the disc of the
/// scene's sphere, so a room lit through a window spends its photons inside rather than on the
/// outside of its walls; each carries the light seen through its opening (zero where something
/// outside blocks the view), so the estimate stays unbiased for the light that comes through
/// the portals. Light from infinity that enters elsewhere gets no photons: a level with portals
/// declares that the sky and sun reach its lit inside only through them. Portals are not geometry
/// (rays and views pass through them) and either side may face the room. The gathers and the
/// reference read the sky as before.
struct SkyPortal {
    /// The opening's triangles in the entity's local space, three vertices each.
    std::vector<glm::vec3> triangles;
    bool enabled = true;
};

}  // namespace luxel::lighting
