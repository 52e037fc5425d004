#pragma once

#include <cstddef>

#include <glm/glm.hpp>

#include "mesh_cache.hpp"
#include "scene_draws.hpp"

namespace luxel::renderer {

/// Texels of a `width` x `height` target that the world-space box `world` covers under
/// `view_projection`: the clipped rectangle around its eight projected corners, or the whole
/// target when the box reaches behind the eye (a room seen from inside). An upper bound on what
/// one layer of geometry inside the box can cover.
[[nodiscard]] double projected_texels(const Bounds& world, const glm::mat4& view_projection,
                                      int width, int height);

/// What a primitive may cost a pass that covers `rect_texels` with its box: its layers (the
/// times its triangles cover the box's face, GpuPrimitive::layers) times the box, but never more
/// than one box per triangle.
[[nodiscard]] double primitive_texels(const GpuPrimitive& primitive, double rect_texels);

/// A bound on the texels one rendering of a view (a shadow map, a cube-map face, the frame's
/// G-buffer) may cover, spent draw by draw before each is issued.
///
/// Why: the time to draw is the area the triangles cover, which no count of triangles bounds.
/// A level of 40,000 coincident 2 m quads is within every load limit, yet one point light's
/// cube shadow map over it covers a billion texels (7.5 s on llvmpipe, and over a second on a
/// discrete GPU, where a driver's watchdog may reset the device). Real levels cover each view a
/// few times over (a room around its light: about 3); the budget allows `kLayers` times the
/// view's texels, and a draw that would exceed what is left is skipped, so a level stacked on
/// itself still renders, in bounded time, with the skipped draws missing from that view (and a
/// warning).
class FillBudget {
  public:
    /// Layers of geometry a view may be covered with before draws are skipped.
    static constexpr double kLayers = 64.0;

    explicit FillBudget(double view_texels) : left_(kLayers * view_texels) {}

    /// Whether a draw estimated at `texels` fits; it is then taken from what is left.
    bool take(double texels) {
        wanted_ += texels;
        if (texels > left_) {
            ++skipped_;
            return false;
        }
        left_ -= texels;
        return true;
    }
    [[nodiscard]] std::size_t skipped() const { return skipped_; }
    /// Every estimate asked for, drawn or not.
    [[nodiscard]] double wanted() const { return wanted_; }

  private:
    double left_;
    double wanted_ = 0.0;
    std::size_t skipped_ = 0;
};

/// Draws `draws` into one view of `width` x `height` texels: every item `keep` accepts and whose
/// box reaches the view, primitive by primitive while `budget` holds. `bind(item)` is called
/// once before an item's first primitive is drawn, `draw(item, primitive)` for each.
template <class Keep, class Bind, class Draw>
void draw_in_view(const DrawList& draws, const glm::mat4& view_projection, int width, int height,
                  FillBudget& budget, Keep keep, Bind bind, Draw draw) {
    for (const DrawItem& item : draws.items) {
        if (!keep(item)) {
            continue;
        }
        const double rect = projected_texels(item.bounds, view_projection, width, height);
        if (rect <= 0.0) {
            continue;  // outside the view
        }
        bool bound = false;
        for (std::size_t i = item.first; i < item.first + item.count; ++i) {
            const DrawPrimitive& primitive = draws.primitives[i];
            if (primitive.range->index_count == 0 ||
                !budget.take(primitive_texels(*primitive.range, rect))) {
                continue;
            }
            if (!bound) {
                bind(item);
                bound = true;
            }
            draw(item, primitive);
        }
    }
}

}  // namespace luxel::renderer
