#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/prep/charts.hpp"
#include "luxel/prep/geometry.hpp"
#include "luxel/prep/options.hpp"
#include "luxel/prep/raster.hpp"
#include "luxel/prep/report.hpp"
#include "luxel/runtime/jobs.hpp"
#include "luxel/scene/lightmap_layout.hpp"
#include "luxel/scene/scene.hpp"

namespace luxel::prep {

/// A chart after packing: where it is and which texels it covers.
struct PlacedChart {
    int page = 0;
    scene::TexelRect rect;  ///< on the page, padding excluded
    /// Per chart vertex: the TEXCOORD_1 written to the file (page coordinates in [0, 1]).
    std::vector<glm::vec2> page_uv;
    /// Its conservative coverage inside `rect`, computed from `page_uv` as stored.
    CoverageMask mask;
    std::int64_t texels = 0;
};

/// A surface: one output primitive, one entry of the light-map table.
struct PreparedSurface {
    int id = -1;  ///< unique in the scene
    int material = -1;
    double area = 0.0;        ///< m^2
    std::vector<int> charts;  ///< indices into PreparedNode::charts
    int page = 0;
    scene::TexelRect rect;  ///< bounds of its charts
    std::int64_t texels = 0;
    /// Metres per texel edge where not the node's (a surface no viewpoint sees); 0: the node's.
    double texel_size = 0.0;
};

/// Everything luxel-prep worked out for one mesh node.
struct PreparedNode {
    int node = -1;
    double texel_size = 0.0;  ///< metres per texel edge for this node (texel_density.hpp)
    NodeGeometry geometry;
    std::vector<Chart> charts;
    std::vector<PlacedChart> placed;  ///< per chart
    std::vector<PreparedSurface> surfaces;
};

struct PrepResult {
    scene::Scene scene;  ///< the prepared scene, ready for save_gltf
    PrepReport report;
    int page_size = 0;
    int page_count = 0;
    int padding = 0;
    std::vector<PreparedNode> nodes;  ///< mesh nodes with at least one surface
};

/// Prepares a loaded scene: surfaces, charts, packing, output (see options.hpp). Meshes are
/// processed in parallel on `jobs`; the result is the same for any thread count. Throws
/// luxel::Error for options or scenes it cannot prepare; repairs (non-manifold edges,
/// degenerate faces, missing normals) are counted in the report instead.
[[nodiscard]] PrepResult prepare(const scene::Scene& input, const PrepOptions& options,
                                 JobSystem& jobs, Progress* progress = nullptr);

}  // namespace luxel::prep
