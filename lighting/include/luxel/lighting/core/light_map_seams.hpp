#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/lighting/core/iim_page.hpp"
#include "luxel/lighting/core/map_surface.hpp"
#include "luxel/scene/scene.hpp"

/// Light-map seams: edges of one object where two charts meet while the surface runs on
/// smoothly (a floor cut into surfaces by luxel-prep's texel budget, a cylinder's unrolled side,
/// a sphere's charts). Each chart's texels are gathered and filtered on their own, so without
/// care the two sides of such an edge show two different noise draws: a step in the light along
/// a line no modeller drew (cornell's back wall showed 3-5%). docs/METHOD.md §6.13.
namespace luxel::lighting {

/// One point of a seam seen from both charts: where it lies on each chart's page, in page-texel
/// units (light-map UV times the page size; texel (x, y) covers [x, x+1] x [y, y+1]).
struct SeamSample {
    std::uint32_t surface_a = 0;
    std::int32_t page_a = -1;
    glm::vec2 point_a{0.0f};
    std::uint32_t surface_b = 0;
    std::int32_t page_b = -1;
    glm::vec2 point_b{0.0f};
    /// Where the sample lies on the object and the edge's direction there (unit), in the
    /// mesh's own frame: what a test that looks for the seam in a rendered frame projects.
    glm::vec3 position{0.0f};
    glm::vec3 along{0.0f};
};

/// One light-mapped primitive of an object, as find_seams reads it. All of an object's
/// primitives share its mesh's frame, so their positions meet where the modeller joined them.
struct SeamSurface {
    std::uint32_t surface = 0;
    const scene::Primitive* primitive = nullptr;
    std::int32_t page = -1;  ///< the registry's page index
    int page_size = 0;
    IimContent content = IimContent::Radiance;
    glm::vec3 albedo{0.5f};
};

/// The samples along every edge of the object where two charts meet (different surfaces, or one
/// surface's triangles with different light-map UVs at the same corners) and the light is
/// continuous: the shading normals on both sides agree within about 8 degrees at both ends (a
/// box's hard edges are left alone: its faces' light really differs there), and the texels
/// hold the same quantity (irradiance on both sides, or radiance of the same albedo). Corners
/// are welded within 1e-5 of the object's size. Two samples per texel of the edge's longer
/// side, at most 8 per texel of the page's edge; edges used by more than two triangles, with
/// non-finite UVs or without a page are left out.
[[nodiscard]] std::vector<SeamSample> find_seams(std::span<const SeamSurface> surfaces);

/// How much the two sides of the seams disagree in what the renderer shows: the RMS of the
/// difference between their bilinear lookups (IimPage::current, as RadiancePage::sample reads
/// it) over the RMS of their mean, over every sample and channel; 0 when there are no samples
/// or no light.
[[nodiscard]] double seam_mismatch(std::span<const SeamSample> samples,
                                   std::span<const IimPage> pages);

}  // namespace luxel::lighting
