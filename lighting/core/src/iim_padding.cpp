#include "iim_padding.hpp"

#include <algorithm>
#include <cstdlib>

namespace luxel::lighting {
namespace {

bool owned(const MapRegistry& registry, std::int32_t page_id, int size, int x, int y) {
    return x >= 0 && y >= 0 && x < size && y < size && registry.owner(page_id, x, y) >= 0;
}

/// Whether any of the nine texels around and at (x, y) is owned by a surface.
bool next_to_a_chart(const MapRegistry& registry, std::int32_t page_id, int size, int x, int y) {
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            if (owned(registry, page_id, size, x + dx, y + dy)) {
                return true;
            }
        }
    }
    return false;
}

}  // namespace

void fill_padding(const MapRegistry& registry, std::int32_t page_id, IimPage& page,
                  std::span<const SurfaceTexel> texels, std::span<const std::uint32_t> targets,
                  std::span<const float> fades, double now_seconds) {
    const int size = page.current.size;
    for (const std::uint32_t i : targets) {
        if (i >= texels.size() || i >= fades.size()) {
            continue;
        }
        const SurfaceTexel& texel = texels[i];
        for (int dy = -kPaddingRings; dy <= kPaddingRings; ++dy) {
            for (int dx = -kPaddingRings; dx <= kPaddingRings; ++dx) {
                const int x = texel.x + dx;
                const int y = texel.y + dy;
                if (x < 0 || y < 0 || x >= size || y >= size ||
                    registry.owner(page_id, x, y) >= 0) {
                    continue;
                }
                const bool first_ring = std::max(std::abs(dx), std::abs(dy)) == 1;
                if (!first_ring && next_to_a_chart(registry, page_id, size, x, y)) {
                    continue;
                }
                page.commit(x, y, page.current.at(texel.x, texel.y), now_seconds, fades[i]);
            }
        }
    }
}

}  // namespace luxel::lighting
