#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/scene/lightmap_layout.hpp"
#include "luxel/scene/scene.hpp"

/// The texels of one light-mapped surface: which page texels it owns and where their centres
/// lie on the mesh. Found with the same conservative coverage luxel-prep counts with
/// (luxel/scene/texel_coverage.hpp), so every texel the layout promises gets lit.
namespace luxel::lighting {

/// One texel: its page coordinates and the point of the surface it stands for, in the mesh's
/// own frame (object space).
struct SurfaceTexel {
    std::int32_t x = 0;
    std::int32_t y = 0;
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f, 1.0f, 0.0f};  ///< unit
    /// The geometric normal of the triangle the point lies on (unit, object space, the winding's
    /// side): the face under the texel, which decides which directions leave the surface.
    glm::vec3 face_normal{0.0f, 1.0f, 0.0f};
    /// That point in page-texel units (the texel centre, or the nearest point of the surface
    /// to it for a border texel whose centre lies off the surface).
    glm::vec2 page_point{0.0f};
};

struct SurfaceTexels {
    int page = 0;
    int page_size = 0;
    std::vector<SurfaceTexel> texels;
    double area = 0.0;  ///< object-space area of the primitive, m^2
    /// Object-space metres per page texel, sqrt(area / light-map area): luxel-prep's charts
    /// are conformal, so one scale holds across the surface.
    double metres_per_texel = 0.0;
};

/// Rasterizes a primitive's TEXCOORD_1 triangles at `page_size` texels per page edge. A texel
/// whose centre lies inside a triangle takes that point; one that the triangle only overlaps
/// (at a chart's border) takes the triangle's point nearest to the centre in light-map space,
/// so border texels sit on the surface, not beyond its edge. Normals are interpolated vertex
/// normals (face normals where a primitive has none). A primitive without TEXCOORD_1, or with
/// degenerate UVs, yields no texels.
[[nodiscard]] SurfaceTexels rasterize_surface(const scene::Primitive& primitive, int page,
                                              int page_size);

}  // namespace luxel::lighting
