#pragma once

#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/prep/options.hpp"
#include "luxel/scene/scene.hpp"

namespace luxel::prep {

/// What the texel size of one mesh node is chosen from.
struct NodeExtent {
    double area = 0.0;         ///< light-mapped area, m^2
    glm::dvec3 size{0.0};      ///< its world-space box's extents, m
    double texel_scale = 1.0;  ///< the node's extras.luxel.texel_scale
};

/// The texel size of every mesh node, in order (docs: tools/prep/README.md, "Texel size"):
///  1. --texel-size times the node's extras.luxel.texel_scale (an author's choice: 0.5 for a
///     prop the camera sees close, 4 for a distant wall);
///  2. made finer where the node's width -- the middle of its world box's three extents, so
///     that a slab's thickness does not count -- would hold fewer than
///     `min_texels_across` texels, down to an eighth of step 1's size: a 4 cm lamp stem at
///     5 cm texels would be one texel wide, all padding, lit as a blur;
///  3. when the level's texels (area / size^2 over every node) exceed `texel_budget`, every
///     node's size multiplied by one factor, so that they fit it.
/// Sizes stay within [1e-6, 1e6] m, the range --texel-size accepts.
[[nodiscard]] std::vector<double> node_texel_sizes(std::span<const NodeExtent> nodes,
                                                   const PrepOptions& options);

/// A node's extras.luxel.texel_scale: 1 when absent. Throws luxel::Error naming `where` when it
/// is not a number within [1/64, 64].
[[nodiscard]] double texel_scale_of(const scene::Node& node, const std::string& where);

}  // namespace luxel::prep
