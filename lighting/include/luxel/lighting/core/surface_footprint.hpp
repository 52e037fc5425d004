#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/lighting/core/photon_density.hpp"
#include "luxel/lighting/core/surface_texels.hpp"
#include "luxel/scene/scene.hpp"

namespace luxel::lighting {

/// How much of a disc around a texel lies on its surface, measured in light-map space.
///
/// Why: the density estimate divides the photons' power by pi r^2, which assumes the whole disc
/// lies on the surface. Near a border (a floor meeting a wall, a corner) a part of the disc is
/// off the surface, no photon can land there, and the plain estimate darkens the border by up
/// to half (a quarter at a corner). Dividing by the disc's area on the surface instead makes
/// the estimate unbiased up to the border. Luxel-prep's charts are conformal with a known
/// metres-per-texel scale, so that area is measured on the surface's own light-map triangles:
/// no ray, no mesh walk. Texels farther from the chart border than the disc's radius skip the
/// measurement (a distance transform, linear in the chart's texels, says which), so interior
/// texels cost nothing.
class SurfaceFootprint {
  public:
    SurfaceFootprint() = default;
    SurfaceFootprint(const scene::Primitive& primitive, const SurfaceTexels& texels);

    /// The fraction (1/64 .. 1) of the disc of `radius_texels` (page texels) around texel
    /// `texel` (an index into SurfaceTexels::texels) that lies on the surface, each part of
    /// the disc weighted as the density kernel weights photons there.
    [[nodiscard]] double fraction(std::size_t texel, double radius_texels,
                                  DensityKernel kernel = DensityKernel::Disc) const;

    /// The distance (page texels) from texel `texel`'s point to the nearest cell of the chart's
    /// grid no triangle covers: below it, fraction() is 1 without measuring. 0 past the end.
    [[nodiscard]] float border_distance(std::size_t texel) const {
        return texel < border_distance_.size() ? border_distance_[texel] : 0.0f;
    }

  private:
    [[nodiscard]] bool covers(const glm::dvec2& point) const;
    [[nodiscard]] bool empty_cell(int x, int y) const;
    [[nodiscard]] std::vector<float> border_distances(const SurfaceTexels& texels) const;
    [[nodiscard]] std::vector<float> centre_distances(const std::vector<std::int32_t>& up,
                                                      const std::vector<std::int32_t>& down) const;

    std::vector<glm::dvec2> corners_;  ///< three per triangle, page-texel units
    int x0_ = 0;
    int y0_ = 0;
    int width_ = 0;
    int height_ = 0;
    /// Per cell of the rectangle, the triangles overlapping it.
    std::vector<std::vector<std::uint32_t>> cells_;
    /// Per texel, the distance (texels) from its point to the nearest cell no triangle covers.
    std::vector<float> border_distance_;
    std::vector<glm::vec2> points_;
};

}  // namespace luxel::lighting
