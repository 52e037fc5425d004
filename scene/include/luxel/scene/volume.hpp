#pragma once

#include <glm/glm.hpp>

#include "luxel/scene/scene.hpp"

/// Transmissive solids: how much light survives a path inside one, and whether a primitive
/// encloses one. The photon tracer, the reference and the renderer all read these, so tinted
/// and absorbing glass looks the same in the three.
namespace luxel::scene {

/// Whether `material` absorbs light inside its volume: transmissive, with a thickness (glTF's
/// thin walls have no inside) and a finite attenuation distance with a colour below white.
[[nodiscard]] bool absorbs_inside(const Material& material);

/// Beer-Lambert as KHR_materials_volume states it: colour ^ (distance / attenuation_distance)
/// per channel, in [0, 1] for any input (white for an infinite attenuation distance or a path
/// of no length; a black colour passes nothing over any positive distance; never NaN).
[[nodiscard]] glm::vec3 beer_lambert(const glm::vec3& colour, float attenuation_distance,
                                     float distance);

/// The fraction of light per channel left after `distance` metres inside `material`'s volume:
/// attenuation_color ^ (distance / attenuation_distance), KHR_materials_volume's Beer-Lambert
/// law (white where the material does not absorb). Always in [0, 1]: a black attenuation colour
/// passes nothing over any positive distance, an infinite distance passes everything.
[[nodiscard]] glm::vec3 volume_transmittance(const Material& material, float distance);

/// Whether the primitive's triangles close up: every edge is shared by exactly two triangles,
/// with vertices welded that lie within 1e-5 of the primitive's size of each other (exporters
/// split vertices along UV and normal seams; a mesh made with trigonometry closes its seam a
/// rounding apart). Degenerate triangles are left out. A ray that enters a closed primitive crosses
/// its surface twice; one that passes an open sheet (a window pane modelled as a single quad),
/// once.
[[nodiscard]] bool is_closed_surface(const Primitive& primitive);

}  // namespace luxel::scene
