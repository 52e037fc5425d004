#pragma once

#include <cstdint>
#include <vector>

namespace luxel {
class JobSystem;
}

namespace luxel::prep {

/// A chart's texel rectangle, padding excluded.
struct PackChart {
    int width = 1;
    int height = 1;
};

/// Where a chart landed: its rectangle's corner on its page (padding excluded; the padding
/// ring around it is free of other charts and inside the page). A rotated chart occupies
/// height x width texels, turned a quarter counter-clockwise: (u, v) -> (height - v, u).
struct ChartPlacement {
    int page = -1;
    int x = 0;
    int y = 0;
    bool rotated = false;
};

struct PackLayout {
    int page_size = 0;
    int page_count = 0;
    std::vector<ChartPlacement> placements;  ///< per chart

    [[nodiscard]] std::int64_t page_texels() const {
        return static_cast<std::int64_t>(page_count) * page_size * page_size;
    }
};

/// Packs charts into square pages of `page_size` texels, every chart with `padding` texels of
/// its own on each side, all charts of one group (a surface) on the same page. A skyline
/// packer, bottom-left first with quarter turns, filling pages first fit. Throws luxel::Error
/// when a group cannot fit even an empty page.
[[nodiscard]] PackLayout pack_fixed(const std::vector<PackChart>& charts,
                                    const std::vector<std::vector<int>>& groups, int padding,
                                    int page_size);

/// Splits a group (a surface's charts, in order) into consecutive runs that each fit an empty
/// page of `page_size`, for pages too small to hold a whole surface. One run when it fits.
[[nodiscard]] std::vector<std::vector<int>> split_to_fit(const std::vector<PackChart>& charts,
                                                         const std::vector<int>& group, int padding,
                                                         int page_size);

/// Picks the page size up to `largest_page` that wastes the fewest texels (pages x size^2,
/// preferring fewer pages among sizes within 1% of the best) and packs into it. The choice is
/// deterministic; `jobs` (optional) only spreads the trial packings over threads.
[[nodiscard]] PackLayout pack_automatic(const std::vector<PackChart>& charts,
                                        const std::vector<std::vector<int>>& groups, int padding,
                                        int largest_page, JobSystem* jobs);

}  // namespace luxel::prep
