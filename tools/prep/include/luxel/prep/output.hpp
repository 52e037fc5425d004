#pragma once

#include <string>
#include <vector>

#include "luxel/prep/packing.hpp"
#include "luxel/prep/prep.hpp"

namespace luxel::prep {

/// Moves a chart to its place on a page: TEXCOORD_1 (quantized to float, as stored) and the
/// texels it covers, computed from those stored values so that what the runtime reads and
/// what the table says agree exactly.
[[nodiscard]] PlacedChart place_chart(const Chart& chart, const ChartPlacement& placement,
                                      int page_size);

/// The output scene: every prepared mesh node gets its own copy of its mesh (light maps are
/// per instance) holding one primitive per surface, in surface order, with vertices split
/// where charts meet and TEXCOORD_1 written, followed by the primitives that get no light map;
/// its extras.luxel.lightmap holds the surface table. Meshes used only by nodes without light
/// maps lose any stale TEXCOORD_1. Each layout records its node's own texel size.
[[nodiscard]] scene::Scene build_output_scene(const scene::Scene& input,
                                              const std::vector<PreparedNode>& nodes, int page_size,
                                              std::vector<std::string>& warnings);

}  // namespace luxel::prep
