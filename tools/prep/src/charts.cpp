#include "luxel/prep/charts.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "luxel/runtime/error.hpp"
#include "parameterization.hpp"

namespace luxel::prep {
namespace {

using detail::FittedChart;
using detail::Patch;
using detail::Piece;

/// Pieces whose normals stray further than this from their mean are cut by axis direction
/// before anything else is tried on them (when they are too large) or after flattening failed.
constexpr double kWideConeCos = 0.5;  // 60 degrees
/// Over-budget pieces with at most this many faces are checked before a cut for whether the
/// cut wastes page texels (ChartBuilder::cut_wastes_texels).
constexpr std::size_t kCutCheckMaxFaces = 256;
/// ... when all their normals are within this cone of their mean (about 8 degrees): the check
/// compares planar charts.
constexpr double kFlatCos = 0.99;
/// A cut whose parts need this many times the whole chart's page texels is not made.
constexpr double kCutWasteRatio = 1.25;

struct PieceShape {
    double area = 0.0;
    glm::dvec3 normal_sum{0.0};  ///< area-weighted
    double min_cos = 1.0;        ///< smallest cosine between a face normal and the mean normal
    bool has_boundary = false;
    glm::dvec3 low{0.0};
    glm::dvec3 high{0.0};
};

class ChartBuilder {
  public:
    ChartBuilder(const NodeGeometry& geometry, const CreaseSurface& surface,
                 const ChartLimits& limits, ChartingCounts& counts)
        : limits_(limits),
          counts_(counts),
          patch_(detail::make_patch(geometry, surface.faces)),
          vertex_scratch_(patch_.positions.size(), -1),
          in_piece_(patch_.face_count(), 0),
          component_(patch_.face_count(), -1) {}

    std::vector<Chart> run() {
        std::vector<int> all(patch_.face_count());
        std::iota(all.begin(), all.end(), 0);
        // Depth first, children in order: the output order is a function of the geometry.
        std::vector<std::vector<int>> stack;
        push_all(stack, components(all));
        while (!stack.empty()) {
            std::vector<int> faces = std::move(stack.back());
            stack.pop_back();
            push_all(stack, process(std::move(faces)));
        }
        detail::merge_adjacent_charts(patch_, accepted_, limits_, vertex_scratch_);
        std::vector<Chart> charts;
        charts.reserve(accepted_.size());
        for (detail::AcceptedPiece& accepted : accepted_) {
            charts.push_back(to_chart(accepted));
        }
        return charts;
    }

  private:
    static void push_all(std::vector<std::vector<int>>& stack,
                         std::vector<std::vector<int>> pieces) {
        for (auto it = pieces.rbegin(); it != pieces.rend(); ++it) {
            stack.push_back(std::move(*it));
        }
    }

    /// Flattens one piece into a chart, or returns the pieces to try instead.
    std::vector<std::vector<int>> process(std::vector<int> faces) {
        const PieceShape shape = measure(faces);
        const bool wide = shape.min_cos < kWideConeCos;
        // A single triangle over the budget stays whole (it cannot be cut without new
        // vertices); the surface budget is a target, not a hard limit.
        if (shape.area > limits_.area_budget && faces.size() > 1) {
            if (wide) {
                auto parts = split_by_direction(faces);
                if (parts.size() > 1) {
                    return parts;
                }
            }
            // Halves: pieces of a rectangle stay rectangles of equal size, which pack well.
            auto halves = split_longest_axis(faces, 2);
            if (!cut_wastes_texels(faces, shape, halves)) {
                return halves;
            }
            // Kept whole, over the budget: see cut_wastes_texels.
        }
        Piece piece = detail::make_piece(patch_, faces, vertex_scratch_);
        detail::Flattening flat =
            detail::flatten_piece(patch_, piece, shape.normal_sum, shape.min_cos,
                                  shape.has_boundary, limits_, &counts_.conformal_failures);
        FittedChart& best = flat.fitted;
        const ChartMethod best_method = flat.method;
        if (best.too_large) {
            if (faces.size() == 1) {
                throw Error("a triangle of " + std::to_string(shape.area) +
                            " m^2 is wider than a light-map page at this texel size; raise "
                            "--texel-size or --page-size");
            }
            return split_for_page(piece, best);
        }
        if (best.ok) {
            accept(piece, std::move(best), best_method, shape.area);
            return {};
        }
        if (faces.size() == 1) {
            // A single triangle always flattens exactly; failing means non-finite input.
            throw Error("a triangle could not be flattened (non-finite or degenerate geometry)");
        }
        if (wide) {
            auto parts = split_by_direction(faces);
            if (parts.size() > 1) {
                return parts;
            }
        }
        return split_longest_axis(faces, 2);
    }

    /// Whether cutting a flat piece over the area budget into `parts` would cost far more page
    /// texels than keeping it whole. A coarse mesh (a wall or floor that a modelling tool
    /// writes as one quad of two triangles) can only be cut along its diagonal: two triangle
    /// charts, each in a rectangle as large as the whole quad's, so that half of every page
    /// rectangle is empty and the padding doubles. Such a piece stays one chart, over the
    /// budget, as a single triangle over it does; finely meshed walls (luxel's own levels) are
    /// still cut, because their halves are rectangles too.
    bool cut_wastes_texels(const std::vector<int>& faces, const PieceShape& shape,
                           const std::vector<std::vector<int>>& parts) {
        // Fine meshes cut along straight rows of vertices, so the check is only worth its
        // cost (a planar fit of every part) on coarse pieces.
        if (faces.size() > kCutCheckMaxFaces || shape.min_cos < kFlatCos) {
            return false;
        }
        const double whole = padded_planar_area(faces, shape.normal_sum);
        if (!(whole > 0.0)) {
            return false;
        }
        double cut = 0.0;
        for (const auto& part : parts) {
            const double area = padded_planar_area(part, measure(part).normal_sum);
            if (!(area > 0.0)) {
                return false;
            }
            cut += area;
        }
        return cut > kCutWasteRatio * whole;
    }

    /// The page texels (padding included) of a piece's planar chart; 0 when it does not fit.
    double padded_planar_area(const std::vector<int>& faces, const glm::dvec3& normal_sum) {
        const Piece piece = detail::make_piece(patch_, faces, vertex_scratch_);
        const FittedChart fitted = detail::fit_chart(
            patch_, piece, detail::planar_projection(patch_, piece, normal_sum), limits_);
        if (!fitted.ok) {
            return 0.0;
        }
        const double pad = 2.0 * limits_.padding;
        return (fitted.width + pad) * (fitted.height + pad);
    }

    PieceShape measure(const std::vector<int>& faces) {
        PieceShape shape;
        shape.low = glm::dvec3(std::numeric_limits<double>::max());
        shape.high = glm::dvec3(std::numeric_limits<double>::lowest());
        for (const int f : faces) {
            in_piece_[static_cast<std::size_t>(f)] = 1;
        }
        for (const int f : faces) {
            const auto i = static_cast<std::size_t>(f);
            shape.area += patch_.areas[i];
            shape.normal_sum += patch_.areas[i] * patch_.normals[i];
            const glm::dvec3 c = patch_.centroid(f);
            shape.low = glm::min(shape.low, c);
            shape.high = glm::max(shape.high, c);
            for (const int n : patch_.neighbours[i]) {
                shape.has_boundary =
                    shape.has_boundary || n < 0 || in_piece_[static_cast<std::size_t>(n)] == 0;
            }
        }
        const double length = glm::length(shape.normal_sum);
        const glm::dvec3 mean = length > 0.0 ? shape.normal_sum / length : glm::dvec3(0.0);
        for (const int f : faces) {
            in_piece_[static_cast<std::size_t>(f)] = 0;
            shape.min_cos = std::min(shape.min_cos,
                                     glm::dot(patch_.normals[static_cast<std::size_t>(f)], mean));
        }
        return shape;
    }

    /// The connected components of an ascending set of faces (across edges inside the set),
    /// each ascending, ordered by their first face.
    std::vector<std::vector<int>> components(const std::vector<int>& faces) {
        for (const int f : faces) {
            in_piece_[static_cast<std::size_t>(f)] = 1;
        }
        // Label by breadth-first search from each unlabelled face in ascending order, then
        // collect in ascending order: no sorting needed for either order.
        int count = 0;
        std::vector<int> queue;
        for (const int seed : faces) {
            if (in_piece_[static_cast<std::size_t>(seed)] != 1) {
                continue;
            }
            in_piece_[static_cast<std::size_t>(seed)] = 2;
            component_[static_cast<std::size_t>(seed)] = count;
            queue.assign(1, seed);
            for (std::size_t next = 0; next < queue.size(); ++next) {
                for (const int n : patch_.neighbours[static_cast<std::size_t>(queue[next])]) {
                    if (n >= 0 && in_piece_[static_cast<std::size_t>(n)] == 1) {
                        in_piece_[static_cast<std::size_t>(n)] = 2;
                        component_[static_cast<std::size_t>(n)] = count;
                        queue.push_back(n);
                    }
                }
            }
            ++count;
        }
        std::vector<std::vector<int>> parts(static_cast<std::size_t>(count));
        for (const int f : faces) {
            in_piece_[static_cast<std::size_t>(f)] = 0;
            parts[static_cast<std::size_t>(component_[static_cast<std::size_t>(f)])].push_back(f);
        }
        return parts;
    }

    /// Cuts a strongly curved piece by the world axis direction (+-x, +-y, +-z) each face's
    /// normal is closest to, like the faces of a cube map: every part then spans at most about
    /// 55 degrees of normals, which a planar projection flattens within the stretch bound.
    std::vector<std::vector<int>> split_by_direction(const std::vector<int>& faces) {
        std::array<std::vector<int>, 6> buckets;
        for (const int f : faces) {
            const glm::dvec3& n = patch_.normals[static_cast<std::size_t>(f)];
            const std::array<double, 6> along{n.x, -n.x, n.y, -n.y, n.z, -n.z};
            const auto best = std::max_element(along.begin(), along.end()) - along.begin();
            buckets[static_cast<std::size_t>(best)].push_back(f);
        }
        std::vector<std::vector<int>> parts;
        for (const auto& bucket : buckets) {
            for (auto& part : components(bucket)) {
                parts.push_back(std::move(part));
            }
        }
        std::sort(parts.begin(), parts.end(),
                  [](const auto& a, const auto& b) { return a.front() < b.front(); });
        return parts;
    }

    /// Cuts a piece across the longest axis of its bounding box, into two parts holding about
    /// floor(k/2)/k and the rest of its area (k: how many pieces it must become).
    std::vector<std::vector<int>> split_longest_axis(const std::vector<int>& faces, int k) {
        const PieceShape shape = measure(faces);
        const glm::dvec3 extent = shape.high - shape.low;
        const int axis =
            extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
        std::vector<double> key(faces.size());
        std::vector<double> cuts;
        cuts.reserve(3 * faces.size());
        for (std::size_t i = 0; i < faces.size(); ++i) {
            key[i] = patch_.centroid(faces[i])[axis];
            for (const int v : patch_.corners[static_cast<std::size_t>(faces[i])]) {
                cuts.push_back(patch_.positions[static_cast<std::size_t>(v)][axis]);
            }
        }
        return split_by_key(faces, key, cuts, k);
    }

    /// Cuts a flattening that is wider than a page across its long side.
    std::vector<std::vector<int>> split_for_page(const Piece& piece, const FittedChart& fitted) {
        glm::dvec2 low(std::numeric_limits<double>::max());
        glm::dvec2 high(std::numeric_limits<double>::lowest());
        for (const auto& p : fitted.uv) {
            low = glm::min(low, p);
            high = glm::max(high, p);
        }
        const glm::dvec2 extent = high - low;
        const int axis = extent.x >= extent.y ? 0 : 1;
        const double usable = std::max(1.0, limits_.max_extent - 2.0 * limits_.padding);
        const int k =
            std::max(2, static_cast<int>(std::ceil(std::min(extent[axis] / usable, 1e6))));
        std::vector<double> key(piece.faces.size());
        std::vector<double> cuts;
        cuts.reserve(fitted.uv.size());
        for (std::size_t i = 0; i < piece.faces.size(); ++i) {
            const auto& c = piece.corners[i];
            key[i] = (fitted.uv[static_cast<std::size_t>(c[0])][axis] +
                      fitted.uv[static_cast<std::size_t>(c[1])][axis] +
                      fitted.uv[static_cast<std::size_t>(c[2])][axis]) /
                     3.0;
        }
        for (const auto& p : fitted.uv) {
            cuts.push_back(p[axis]);
        }
        return split_by_key(piece.faces, key, cuts, k);
    }

    /// Splits faces by a key (a centroid coordinate) at one of the `cuts` (vertex coordinates
    /// on the same axis): cutting where vertices are, rather than between two face centroids,
    /// keeps a grid's rows whole instead of leaving a sawtooth of triangles along the cut. The
    /// cut chosen leaves closest to floor(k/2)/k of the area on the low side.
    std::vector<std::vector<int>> split_by_key(const std::vector<int>& faces,
                                               const std::vector<double>& key,
                                               const std::vector<double>& cuts, int k) {
        const std::size_t n = faces.size();
        std::vector<std::pair<double, int>> sorted(n);
        for (std::size_t i = 0; i < n; ++i) {
            sorted[i] = {key[i], static_cast<int>(i)};
        }
        std::sort(sorted.begin(), sorted.end());
        std::vector<double> area_before(n + 1, 0.0);
        for (std::size_t i = 0; i < n; ++i) {
            area_before[i + 1] =
                area_before[i] + patch_.areas[static_cast<std::size_t>(
                                     faces[static_cast<std::size_t>(sorted[i].second)])];
        }
        const double target = area_before[n] * static_cast<double>(k / 2) / static_cast<double>(k);
        // Never less than a sixteenth of the faces on a side, so that a few huge triangles
        // among many small ones cannot make the cutting go on for ever.
        const std::size_t lowest = std::max<std::size_t>(1, n / 16);
        const std::size_t highest = std::min(n - 1, n - n / 16);
        // The area below a cut grows with the cut, so the best cut is the last one that stays
        // under the target or the first one that reaches it. Faces with key < c are below c.
        const auto reaching = static_cast<std::size_t>(
            std::lower_bound(area_before.begin() + 1, area_before.end(), target) -
            area_before.begin() - 1);  // the face whose area reaches the target
        const double threshold = sorted[std::min(reaching, n - 1)].first;
        double under = std::numeric_limits<double>::lowest();
        double over = std::numeric_limits<double>::max();
        for (const double c : cuts) {
            if (c <= threshold) {
                under = std::max(under, c);
            } else {
                over = std::min(over, c);
            }
        }
        auto below = [&](double c) {
            return static_cast<std::size_t>(
                std::lower_bound(sorted.begin(), sorted.end(), std::make_pair(c, -1)) -
                sorted.begin());
        };
        std::size_t cut = 0;
        double best_error = std::numeric_limits<double>::max();
        for (const double c : {under, over}) {
            if (c == std::numeric_limits<double>::lowest() ||
                c == std::numeric_limits<double>::max()) {
                continue;
            }
            const std::size_t count = below(c);
            const double error = std::abs(area_before[count] - target);
            if (count >= lowest && count <= highest && error < best_error) {
                best_error = error;
                cut = count;
            }
        }
        if (cut == 0) {
            // No vertex coordinate gives an acceptable split: cut between centroids.
            cut = std::clamp(reaching + 1, lowest, highest);
        }
        std::vector<std::uint8_t> low_side(n, 0);
        for (std::size_t i = 0; i < cut; ++i) {
            low_side[static_cast<std::size_t>(sorted[i].second)] = 1;
        }
        std::vector<int> first;
        std::vector<int> second;
        for (std::size_t i = 0; i < n; ++i) {  // faces are ascending, and so are both sides
            (low_side[i] != 0 ? first : second).push_back(faces[i]);
        }
        auto parts = components(first);
        for (auto& part : components(second)) {
            parts.push_back(std::move(part));
        }
        return parts;
    }

    void accept(Piece& piece, FittedChart fitted, ChartMethod method, double area) {
        accepted_.push_back({std::move(piece), std::move(fitted), method, area});
    }

    Chart to_chart(detail::AcceptedPiece& accepted) {
        const Piece& piece = accepted.piece;
        Chart chart;
        chart.faces.reserve(piece.faces.size());
        for (const int f : piece.faces) {
            chart.faces.push_back(patch_.node_face[static_cast<std::size_t>(f)]);
        }
        chart.vertices.reserve(piece.vertices.size());
        for (const int v : piece.vertices) {
            chart.vertices.push_back(patch_.node_vertex[static_cast<std::size_t>(v)]);
        }
        chart.corners = piece.corners;
        chart.uv = std::move(accepted.fitted.uv);
        chart.width = accepted.fitted.width;
        chart.height = accepted.fitted.height;
        chart.method = accepted.method;
        chart.area = accepted.area;
        chart.stretch_min = accepted.fitted.stretch_min;
        chart.stretch_max = accepted.fitted.stretch_max;
        chart.stretch_area_sum = accepted.fitted.stretch_area_sum;
        (chart.method == ChartMethod::Planar ? counts_.planar : counts_.conformal) += 1;
        return chart;
    }

    const ChartLimits& limits_;
    ChartingCounts& counts_;
    Patch patch_;
    std::vector<int> vertex_scratch_;
    std::vector<std::uint8_t> in_piece_;  ///< scratch marks per patch face, 0 between uses
    std::vector<int> component_;          ///< scratch component labels per patch face
    std::vector<detail::AcceptedPiece> accepted_;
};

}  // namespace

std::vector<Chart> build_charts(const NodeGeometry& geometry, const CreaseSurface& surface,
                                const ChartLimits& limits, ChartingCounts* counts) {
    ChartingCounts local;
    ChartBuilder builder(geometry, surface, limits, counts != nullptr ? *counts : local);
    return builder.run();
}

}  // namespace luxel::prep
