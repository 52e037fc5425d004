// Chart merging: the bottom-up half of luxel-prep's charting. ChartBuilder (charts.cpp) cuts a
// crease surface top-down until every piece flattens within the bounds; its cuts (by axis
// direction on curved pieces, in halves after a failed flattening) are made without knowing
// whether a coarser piece would have done, so a cylinder's side comes out in four quarters and
// a curved prop in many small charts, each paying a ring of padding. Merging adjacent charts
// back while their union still flattens within the bounds, as chart-growing parameterizers do
// (xatlas, Lévy et al.'s "least squares conformal maps" charts), gives fewer, larger charts.
//
// luxel writes its own: OpenMesh, the project's mesh library, has no charting or
// parameterization (its tools are decimation, subdivision, smoothing and progressive meshes),
// and the bounds that matter here (luxel's stretch measure, whole-texel rectangles, the
// surface budget of the scheduler) are luxel's.

#include <algorithm>
#include <array>
#include <cstdint>
#include <iterator>
#include <set>

#include "parameterization.hpp"

namespace luxel::prep::detail {
namespace {

/// Pairs whose smaller chart has more faces than this are not tried: padding matters little to
/// a large chart, and flattening two large ones costs a conformal solve over both.
constexpr std::size_t kMergeMaxFaces = 4096;
/// Sweeps over all charts; each sweep merges every chart with at most one neighbour.
constexpr int kMergeSweeps = 8;
/// Faces flattened by merge attempts, in multiples of the patch's faces: the merging costs at
/// most a few times what the charting did, however many small charts a curved mesh gave.
constexpr std::size_t kMergeWork = 4;
/// A merge must save this share of the two charts' page texels: merges that save a texel or
/// two trade rectangular charts for odd shapes the packer fits no better.
constexpr double kMinSaving = 0.2;
/// How much less uniform (stretch max over min) a merged chart may be than the worse of the two.
constexpr double kDistortionGrowth = 1.05;

double padded_texels(const FittedChart& fitted, int padding) {
    const double pad = 2.0 * padding;
    return (fitted.width + pad) * (fitted.height + pad);
}

class ChartMerger {
  public:
    ChartMerger(const Patch& patch, std::vector<AcceptedPiece>& charts, const ChartLimits& limits,
                std::vector<int>& vertex_scratch)
        : patch_(patch),
          charts_(charts),
          limits_(limits),
          vertex_scratch_(vertex_scratch),
          chart_of_(patch.face_count(), -1),
          alive_(charts.size(), 1),
          version_(charts.size(), 0),
          work_left_(kMergeWork * patch.face_count()) {
        for (std::size_t c = 0; c < charts_.size(); ++c) {
            for (const int f : charts_[c].piece.faces) {
                chart_of_[static_cast<std::size_t>(f)] = static_cast<int>(c);
            }
        }
    }

    void run() {
        for (int sweep = 0; sweep < kMergeSweeps; ++sweep) {
            bool merged = false;
            // Smallest charts first, and each with its smallest neighbour first: padding costs
            // small charts most, and small unions are the cheapest to flatten.
            for (const std::size_t a : by_size()) {
                if (alive_[a] == 0) {
                    continue;
                }
                for (const int b : neighbours(a)) {
                    // The union is the same whichever chart asks.
                    const auto low = std::min(a, static_cast<std::size_t>(b));
                    const auto high = std::max(a, static_cast<std::size_t>(b));
                    const std::array<int, 4> key{static_cast<int>(low), static_cast<int>(high),
                                                 version_[low], version_[high]};
                    if (failed_.contains(key)) {
                        continue;  // neither chart changed since this merge failed
                    }
                    if (!try_merge(a, static_cast<std::size_t>(b))) {
                        failed_.insert(key);
                    } else {
                        merged = true;
                        break;
                    }
                }
            }
            if (!merged) {
                break;
            }
        }
        std::vector<AcceptedPiece> kept;
        for (std::size_t c = 0; c < charts_.size(); ++c) {
            if (alive_[c] != 0) {
                kept.push_back(std::move(charts_[c]));
            }
        }
        charts_ = std::move(kept);
    }

  private:
    /// The live charts, fewest faces first (ties by index: deterministic).
    std::vector<std::size_t> by_size() const {
        std::vector<std::size_t> order;
        for (std::size_t c = 0; c < charts_.size(); ++c) {
            if (alive_[c] != 0) {
                order.push_back(c);
            }
        }
        std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
            return charts_[x].piece.faces.size() < charts_[y].piece.faces.size();
        });
        return order;
    }

    /// The charts across an edge from chart `a`, fewest faces first (ties by index).
    std::vector<int> neighbours(std::size_t a) const {
        std::vector<int> result;
        for (const int f : charts_[a].piece.faces) {
            for (const int n : patch_.neighbours[static_cast<std::size_t>(f)]) {
                const int c = n >= 0 ? chart_of_[static_cast<std::size_t>(n)] : -1;
                if (c >= 0 && c != static_cast<int>(a)) {
                    result.push_back(c);
                }
            }
        }
        std::sort(result.begin(), result.end());
        result.erase(std::unique(result.begin(), result.end()), result.end());
        std::stable_sort(result.begin(), result.end(), [&](int x, int y) {
            return charts_[static_cast<std::size_t>(x)].piece.faces.size() <
                   charts_[static_cast<std::size_t>(y)].piece.faces.size();
        });
        return result;
    }

    bool try_merge(std::size_t a, std::size_t b) {
        const AcceptedPiece& first = charts_[a];
        const AcceptedPiece& second = charts_[b];
        // The surface budget holds for merged charts as for cut ones.
        if (first.area + second.area > limits_.area_budget ||
            std::min(first.piece.faces.size(), second.piece.faces.size()) > kMergeMaxFaces) {
            return false;
        }
        const std::size_t union_faces = first.piece.faces.size() + second.piece.faces.size();
        // Padding and the empty corners of the two rectangles are all a merge can save: pairs
        // that could not save enough even with a union of no waste at all (and the fewest
        // texels the stretch bound allows) are not flattened.
        const double fewest_texels =
            (first.area + second.area) /
            (limits_.texel_size * limits_.texel_size * limits_.max_stretch);
        const double apart = padded_texels(first.fitted, limits_.padding) +
                             padded_texels(second.fitted, limits_.padding);
        if (fewest_texels > (1.0 - kMinSaving) * apart) {
            return false;
        }
        if (union_faces > work_left_) {
            return false;
        }
        work_left_ -= union_faces;
        std::vector<int> faces;
        faces.reserve(first.piece.faces.size() + second.piece.faces.size());
        std::merge(first.piece.faces.begin(), first.piece.faces.end(), second.piece.faces.begin(),
                   second.piece.faces.end(), std::back_inserter(faces));
        glm::dvec3 normal_sum(0.0);
        for (const int f : faces) {
            const auto i = static_cast<std::size_t>(f);
            normal_sum += patch_.areas[i] * patch_.normals[i];
        }
        const double length = glm::length(normal_sum);
        const glm::dvec3 mean = length > 0.0 ? normal_sum / length : glm::dvec3(0.0);
        double min_cos = 1.0;
        bool has_boundary = false;
        for (const int f : faces) {
            const auto i = static_cast<std::size_t>(f);
            min_cos = std::min(min_cos, glm::dot(patch_.normals[i], mean));
            for (const int n : patch_.neighbours[i]) {
                const int c = n >= 0 ? chart_of_[static_cast<std::size_t>(n)] : -1;
                has_boundary =
                    has_boundary || (c != static_cast<int>(a) && c != static_cast<int>(b));
            }
        }
        Piece piece = make_piece(patch_, std::move(faces), vertex_scratch_);
        Flattening flat =
            flatten_piece(patch_, piece, normal_sum, min_cos, has_boundary, limits_, nullptr);
        // Fewer texels must not cost a less uniform density than the two charts had (a curved
        // piece merged into a wider cone spreads its texels less evenly).
        const double distortion =
            std::max(first.fitted.distortion(), second.fitted.distortion()) * kDistortionGrowth;
        if (!flat.fitted.ok || flat.fitted.distortion() > distortion ||
            padded_texels(flat.fitted, limits_.padding) > (1.0 - kMinSaving) * apart) {
            return false;
        }
        for (const int f : second.piece.faces) {
            chart_of_[static_cast<std::size_t>(f)] = static_cast<int>(a);
        }
        const double area = first.area + second.area;
        charts_[a] = {std::move(piece), std::move(flat.fitted), flat.method, area};
        alive_[b] = 0;
        ++version_[a];
        return true;
    }

    const Patch& patch_;
    std::vector<AcceptedPiece>& charts_;
    const ChartLimits& limits_;
    std::vector<int>& vertex_scratch_;
    std::vector<int> chart_of_;            ///< per patch face: the chart holding it
    std::vector<std::uint8_t> alive_;      ///< per chart: 0 once merged into another
    std::vector<int> version_;             ///< per chart: how many merges changed it
    std::size_t work_left_;                ///< faces merge attempts may still flatten (kMergeWork)
    std::set<std::array<int, 4>> failed_;  ///< (a, b, a's version, b's version) that failed
};

}  // namespace

void merge_adjacent_charts(const Patch& patch, std::vector<AcceptedPiece>& charts,
                           const ChartLimits& limits, std::vector<int>& vertex_scratch) {
    if (charts.size() < 2) {
        return;
    }
    ChartMerger(patch, charts, limits, vertex_scratch).run();
}

}  // namespace luxel::prep::detail
