#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "contact_texels.hpp"
#include "luxel/lighting/core/surface_texels.hpp"

namespace luxel::lighting {

/// The filter over a completed gather pass of one surface (IlluminationMaps): a tent of radius
/// r texels over the surface's own texels (never across to another surface, which may be
/// across a crease), optionally weighing each neighbour by how well the two texels' noise
/// explains their difference (IlluminationSettings::iim_filter_noise_sigmas).
///
/// It runs in slices (run()), so that filtering a large surface does not land in one budgeted
/// unit of work: the filter reads 25 neighbours per texel (radius 2), which made the unit that
/// completed a pass overrun small budgets (docs/PERFORMANCE.md, lighting budget).
class IimPassFilter {
  public:
    /// `values`: the pass's (or the passes' mean) irradiance per texel, in the order of
    /// `texels`; `noise`: per texel the variance of that mean summed over channels, or empty
    /// for the plain tent. Copies what it needs: the surface may change while it runs.
    IimPassFilter(const std::vector<SurfaceTexel>& texels, std::vector<glm::vec3> values,
                  std::vector<double> noise, int radius, double noise_sigmas);

    /// Filters only the texels whose filtered value can differ from the last pass's: those of
    /// `changed` (indices into the texels) and their neighbours within the radius. What a local
    /// pass needs: the other texels' means did not change, so neither did their filtered
    /// values, and filtering the whole of a large floor for a few hundred texels next to a
    /// moved crate held the footprint dark for frames at a small budget (docs/RESULTS.md).
    void restrict_to(const std::vector<std::uint32_t>& changed);
    /// Per texel (in the order of the texels), its cover (ContactTexels): an Enclosed texel,
    /// under an object and a texel or more from the open surface, holds the object's unlit
    /// inside; it is no one's neighbour (the tent around a texel beside the object would blend
    /// its black in) and keeps its own value. Empty: every texel is open.
    void leave_out_enclosed(std::span<const TexelCover> cover);
    /// The texels filtered, in order: every texel, or those restrict_to() chose.
    [[nodiscard]] const std::vector<std::uint32_t>& targets() const { return targets_; }

    /// Filters up to `max_texels` more texels; returns how many.
    std::size_t run(std::size_t max_texels);
    [[nodiscard]] bool done() const { return cursor_ >= targets_.size(); }
    /// The filtered irradiance per texel (complete for the targets once done()).
    [[nodiscard]] const std::vector<glm::vec3>& filtered() const { return filtered_; }
    /// The targets' bounding rectangle on the page (x0, y0, x1, y1 inclusive; empty when
    /// x1 < x0).
    [[nodiscard]] glm::ivec4 bounds() const { return bounds_; }

  private:
    /// The texel at (dx, dy) from texel i on the page, or -1 (none, or another surface's).
    [[nodiscard]] std::int32_t neighbour(std::size_t i, int dx, int dy) const;

    std::vector<glm::ivec2> positions_;  ///< texel (x, y) on the page
    std::vector<glm::vec3> values_;
    std::vector<double> noise_;
    std::vector<std::uint8_t> left_out_;  ///< by texel; empty: none
    std::vector<std::int32_t> index_;     ///< texel index by position in the bounds; -1: none
    std::vector<glm::vec3> filtered_;
    std::vector<std::uint32_t> targets_;
    glm::ivec4 bounds_{0, 0, -1, -1};
    int x0_ = 0;
    int y0_ = 0;
    int width_ = 0;
    int height_ = 0;
    int radius_ = 0;
    double sigmas_ = 0.0;
    std::size_t cursor_ = 0;
};

}  // namespace luxel::lighting
