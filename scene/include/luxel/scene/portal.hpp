#pragma once

#include "luxel/scene/scene.hpp"

namespace luxel::scene {

/// Whether a node is a sky portal: extras.luxel.portal = true (docs/LEVELS.md, "Sky"). Its mesh
/// is an opening (a window, a doorway) that sky photons start on, not geometry: it is neither
/// drawn, traced nor light-mapped (lighting::SkyPortal). The integer 1 counts as true: Blender 3
/// exports its boolean custom properties so.
[[nodiscard]] inline bool is_portal(const Node& node) {
    const auto found = node.flags.raw.find("portal");
    return found != node.flags.raw.end() && ((found->is_boolean() && found->get<bool>()) ||
                                             (found->is_number_integer() && *found == 1));
}

}  // namespace luxel::scene
