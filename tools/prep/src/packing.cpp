#include "luxel/prep/packing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <string>

#include "luxel/runtime/error.hpp"
#include "luxel/runtime/jobs.hpp"

namespace luxel::prep {
namespace {

/// The top outline of what is packed on a page so far: segments of constant height covering
/// [0, size) from left to right. A rectangle rests on the outline, never under an overhang,
/// which is what makes skyline packing fast.
class Skyline {
  public:
    explicit Skyline(int size) : size_(size), segments_{{0, 0, size}} {}

    struct Spot {
        int x = 0;
        int y = 0;
        std::int64_t waste = 0;  ///< texels left unusable beneath the rectangle
    };

    /// The lowest resting place for a w x h rectangle (ties: least waste, then leftmost).
    [[nodiscard]] std::optional<Spot> find(int w, int h) const {
        std::optional<Spot> best;
        for (std::size_t i = 0; i < segments_.size(); ++i) {
            const int x = segments_[i].x;
            if (x + w > size_) {
                break;
            }
            int y = 0;
            for (std::size_t j = i; j < segments_.size() && segments_[j].x < x + w; ++j) {
                y = std::max(y, segments_[j].y);
            }
            if (y + h > size_) {
                continue;
            }
            std::int64_t waste = 0;
            for (std::size_t j = i; j < segments_.size() && segments_[j].x < x + w; ++j) {
                const int right = std::min(segments_[j].x + segments_[j].width, x + w);
                waste += static_cast<std::int64_t>(y - segments_[j].y) * (right - segments_[j].x);
            }
            if (!best || y < best->y || (y == best->y && waste < best->waste)) {
                best = Spot{x, y, waste};
            }
        }
        return best;
    }

    void place(int x, int y, int w, int h) {
        std::vector<Segment> next;
        next.reserve(segments_.size() + 2);
        for (const Segment& s : segments_) {
            const int right = s.x + s.width;
            if (right <= x || s.x >= x + w) {
                next.push_back(s);
                continue;
            }
            if (s.x < x) {  // the part left of the new rectangle survives
                next.push_back({s.x, s.y, x - s.x});
            }
            if (s.x <= x) {
                next.push_back({x, y + h, w});
            }
            if (right > x + w) {  // and the part right of it
                next.push_back({x + w, s.y, right - (x + w)});
            }
        }
        // Merge neighbours of equal height so the outline stays short.
        segments_.clear();
        for (const Segment& s : next) {
            if (!segments_.empty() && segments_.back().y == s.y) {
                segments_.back().width += s.width;
            } else {
                segments_.push_back(s);
            }
        }
    }

  private:
    struct Segment {
        int x;
        int y;
        int width;
    };
    int size_;
    std::vector<Segment> segments_;
};

/// Places one group's charts on a page, all or none.
bool place_group(Skyline& page, const std::vector<int>& order, const std::vector<PackChart>& charts,
                 int padding, int page_index, std::vector<ChartPlacement>& placements) {
    Skyline trial = page;
    std::vector<std::pair<int, ChartPlacement>> placed;
    for (const int c : order) {
        const int w = charts[static_cast<std::size_t>(c)].width + 2 * padding;
        const int h = charts[static_cast<std::size_t>(c)].height + 2 * padding;
        const auto upright = trial.find(w, h);
        const auto turned = w != h ? trial.find(h, w) : std::nullopt;
        const bool use_turned =
            turned && (!upright || turned->y + w < upright->y + h ||
                       (turned->y + w == upright->y + h && turned->waste < upright->waste));
        if (!upright && !use_turned) {
            return false;
        }
        const Skyline::Spot spot = use_turned ? *turned : *upright;
        trial.place(spot.x, spot.y, use_turned ? h : w, use_turned ? w : h);
        placed.push_back({c, {page_index, spot.x + padding, spot.y + padding, use_turned}});
    }
    page = std::move(trial);
    for (const auto& [c, placement] : placed) {
        placements[static_cast<std::size_t>(c)] = placement;
    }
    return true;
}

int longest_side(const PackChart& chart) {
    return std::max(chart.width, chart.height);
}

/// Groups, and the charts inside each, in the order the packer takes them: tallest first
/// (long sides), then largest, then by index.
struct PackOrder {
    std::vector<std::vector<int>> charts_of_group;
    std::vector<int> groups;
};

PackOrder pack_order(const std::vector<PackChart>& charts,
                     const std::vector<std::vector<int>>& groups) {
    auto chart_before = [&](int a, int b) {
        const PackChart& ca = charts[static_cast<std::size_t>(a)];
        const PackChart& cb = charts[static_cast<std::size_t>(b)];
        if (longest_side(ca) != longest_side(cb)) {
            return longest_side(ca) > longest_side(cb);
        }
        if (ca.width * ca.height != cb.width * cb.height) {
            return ca.width * ca.height > cb.width * cb.height;
        }
        return a < b;
    };
    PackOrder order;
    order.charts_of_group = groups;
    for (auto& group : order.charts_of_group) {
        std::sort(group.begin(), group.end(), chart_before);
    }
    order.groups.resize(groups.size());
    std::iota(order.groups.begin(), order.groups.end(), 0);
    std::sort(order.groups.begin(), order.groups.end(), [&](int a, int b) {
        const auto& ga = order.charts_of_group[static_cast<std::size_t>(a)];
        const auto& gb = order.charts_of_group[static_cast<std::size_t>(b)];
        if (ga.empty() || gb.empty()) {
            return !ga.empty() && gb.empty() ? true : (ga.empty() == gb.empty() && a < b);
        }
        const PackChart& ca = charts[static_cast<std::size_t>(ga.front())];
        const PackChart& cb = charts[static_cast<std::size_t>(gb.front())];
        if (longest_side(ca) != longest_side(cb)) {
            return longest_side(ca) > longest_side(cb);
        }
        if (ca.width * ca.height != cb.width * cb.height) {
            return ca.width * ca.height > cb.width * cb.height;
        }
        return a < b;
    });
    return order;
}

/// Packs at one page size; nothing when some group does not fit an empty page.
std::optional<PackLayout> try_pack(const std::vector<PackChart>& charts, const PackOrder& order,
                                   int padding, int page_size) {
    // Only the most recent pages are tried: older ones are nearly full, and looking back over
    // all of them would make large scenes quadratic.
    constexpr std::size_t kOpenPages = 8;
    PackLayout layout;
    layout.page_size = page_size;
    layout.placements.resize(charts.size());
    std::vector<Skyline> pages;
    for (const int g : order.groups) {
        const auto& group = order.charts_of_group[static_cast<std::size_t>(g)];
        bool placed = false;
        const std::size_t first = pages.size() > kOpenPages ? pages.size() - kOpenPages : 0;
        for (std::size_t p = first; p < pages.size() && !placed; ++p) {
            placed = place_group(pages[p], group, charts, padding, static_cast<int>(p),
                                 layout.placements);
        }
        if (!placed) {
            pages.emplace_back(page_size);
            if (!place_group(pages.back(), group, charts, padding,
                             static_cast<int>(pages.size() - 1), layout.placements)) {
                return std::nullopt;
            }
        }
    }
    layout.page_count = static_cast<int>(pages.size());
    return layout;
}

}  // namespace

std::vector<std::vector<int>> split_to_fit(const std::vector<PackChart>& charts,
                                           const std::vector<int>& group, int padding,
                                           int page_size) {
    std::vector<ChartPlacement> scratch(charts.size());
    const PackOrder whole = pack_order(charts, {group});
    Skyline page(page_size);
    if (place_group(page, whole.charts_of_group.front(), charts, padding, 0, scratch)) {
        return {group};
    }
    std::vector<std::vector<int>> runs(1);
    page = Skyline(page_size);
    for (const int c : group) {
        if (!runs.back().empty() && !place_group(page, {c}, charts, padding, 0, scratch)) {
            runs.emplace_back();
            page = Skyline(page_size);
        }
        if (runs.back().empty()) {
            (void)place_group(page, {c}, charts, padding, 0, scratch);
        }
        runs.back().push_back(c);
    }
    return runs;
}

PackLayout pack_fixed(const std::vector<PackChart>& charts,
                      const std::vector<std::vector<int>>& groups, int padding, int page_size) {
    auto layout = try_pack(charts, pack_order(charts, groups), padding, page_size);
    if (!layout) {
        throw Error("--page-size " + std::to_string(page_size) +
                    " is too small: a surface with its padding does not fit on one page");
    }
    return *layout;
}

PackLayout pack_automatic(const std::vector<PackChart>& charts,
                          const std::vector<std::vector<int>>& groups, int padding,
                          int largest_page, JobSystem* jobs) {
    if (charts.empty()) {
        return PackLayout{};
    }
    const PackOrder order = pack_order(charts, groups);
    // No page can be smaller than the largest chart or the area of the largest group.
    int smallest = 1;
    double total_area = 0.0;
    for (const auto& group : groups) {
        double group_area = 0.0;
        for (const int c : group) {
            const PackChart& chart = charts[static_cast<std::size_t>(c)];
            smallest = std::max(smallest, longest_side(chart) + 2 * padding);
            group_area +=
                static_cast<double>(chart.width + 2 * padding) * (chart.height + 2 * padding);
        }
        smallest = std::max(smallest, static_cast<int>(std::ceil(std::sqrt(group_area))));
        total_area += group_area;
    }
    const int largest = std::max(
        smallest,
        std::min(largest_page, static_cast<int>(std::ceil(std::sqrt(total_area) * 1.5)) + 2));
    // Every size when there are few, otherwise sizes spaced evenly on a log scale.
    std::vector<int> sizes;
    constexpr int kMaxCandidates = 160;
    if (largest - smallest < kMaxCandidates) {
        for (int n = smallest; n <= largest; ++n) {
            sizes.push_back(n);
        }
    } else {
        const double ratio =
            std::log(static_cast<double>(largest) / smallest) / (kMaxCandidates - 1);
        for (int i = 0; i < kMaxCandidates; ++i) {
            const int n = static_cast<int>(std::lround(smallest * std::exp(ratio * i)));
            if (sizes.empty() || n > sizes.back()) {
                sizes.push_back(std::min(n, largest));
            }
        }
    }
    // Fewer pages are preferred among near-equal sizes, so the sizes just above a single
    // page's minimum are all tried, however coarse the spacing above.
    const int single = static_cast<int>(std::ceil(std::sqrt(total_area)));
    for (int n = std::max(smallest, single);
         n <= std::min(largest, single + single / 12 + 1) && n < std::max(smallest, single) + 96;
         ++n) {
        sizes.push_back(n);
    }
    std::sort(sizes.begin(), sizes.end());
    sizes.erase(std::unique(sizes.begin(), sizes.end()), sizes.end());
    std::vector<std::optional<PackLayout>> trials(sizes.size());
    auto trial = [&](std::size_t i) { trials[i] = try_pack(charts, order, padding, sizes[i]); };
    if (jobs != nullptr) {
        jobs->parallel_for(0, sizes.size(), trial);
    } else {
        for (std::size_t i = 0; i < sizes.size(); ++i) {
            trial(i);
        }
    }
    std::int64_t best_texels = std::numeric_limits<std::int64_t>::max();
    for (const auto& t : trials) {
        if (t) {
            best_texels = std::min(best_texels, t->page_texels());
        }
    }
    if (best_texels == std::numeric_limits<std::int64_t>::max()) {
        throw Error("the charts do not fit pages of up to " + std::to_string(largest_page) +
                    " texels");
    }
    // Among sizes within 1% of the least waste, fewer pages are easier on the renderer.
    const PackLayout* chosen = nullptr;
    for (const auto& t : trials) {
        if (!t || static_cast<double>(t->page_texels()) > 1.01 * static_cast<double>(best_texels)) {
            continue;
        }
        if (chosen == nullptr || t->page_count < chosen->page_count ||
            (t->page_count == chosen->page_count && t->page_texels() < chosen->page_texels())) {
            chosen = &*t;
        }
    }
    return *chosen;
}

}  // namespace luxel::prep
