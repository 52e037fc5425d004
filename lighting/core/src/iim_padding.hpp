#pragma once

#include <cstdint>
#include <span>

#include "luxel/lighting/core/iim_page.hpp"
#include "luxel/lighting/core/surface_texels.hpp"
#include "map_registry.hpp"

namespace luxel::lighting {

/// Rings of padding around a chart that a gather pass fills: the first for bilinear lookups at
/// a chart's border, the second for the bicubic ones (render/iim.glsl, docs/METHOD.md §8.5).
inline constexpr int kPaddingRings = 2;

/// After a pass committed `targets` (indices into `texels`) of a surface on `page`, copies each
/// into the unowned texels around it that a lookup inside its chart reads, with its fade:
/// - ring 1, every unowned texel next to it (as before bicubic lookups existed);
/// - ring 2, the unowned texels two away that are next to no owned texel at all: the second
///   ring of a chart whose padding is at least 2 (`luxel-prep --padding 2`). Where charts are
///   closer (the default padding of 1, charts two texels apart) that texel is a neighbour's
///   first ring, which its bilinear lookups read, and it is left to the neighbour.
void fill_padding(const MapRegistry& registry, std::int32_t page_id, IimPage& page,
                  std::span<const SurfaceTexel> texels, std::span<const std::uint32_t> targets,
                  std::span<const float> fades, double now_seconds);

}  // namespace luxel::lighting
