#include "luxel/lighting/core/surface_footprint.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "luxel/scene/texel_coverage.hpp"

namespace luxel::lighting {
namespace {

constexpr int kRings = 8;
constexpr int kPerRing = 8;
constexpr int kSamples = kRings * kPerRing;

/// Unit-disc points of equal area: ring i at radius sqrt((i + 0.5) / rings), rotated by half a
/// step every other ring.
const std::array<glm::dvec2, kSamples>& disc_pattern() {
    static const std::array<glm::dvec2, kSamples> pattern = [] {
        std::array<glm::dvec2, kSamples> points{};
        for (int ring = 0; ring < kRings; ++ring) {
            const double r = std::sqrt((ring + 0.5) / kRings);
            for (int k = 0; k < kPerRing; ++k) {
                const double angle = 2.0 * std::numbers::pi * (k + 0.5 * (ring % 2)) / kPerRing;
                points[static_cast<std::size_t>(ring * kPerRing + k)] =
                    glm::dvec2(r * std::cos(angle), r * std::sin(angle));
            }
        }
        return points;
    }();
    return pattern;
}

bool inside(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c, const glm::dvec2& p) {
    const double d0 = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
    const double d1 = (c.x - b.x) * (p.y - b.y) - (c.y - b.y) * (p.x - b.x);
    const double d2 = (a.x - c.x) * (p.y - c.y) - (a.y - c.y) * (p.x - c.x);
    return (d0 >= 0.0 && d1 >= 0.0 && d2 >= 0.0) || (d0 <= 0.0 && d1 <= 0.0 && d2 <= 0.0);
}

}  // namespace

SurfaceFootprint::SurfaceFootprint(const scene::Primitive& primitive, const SurfaceTexels& texels) {
    const auto& uvs = primitive.texcoords1;
    const double size = texels.page_size;
    if (uvs.size() != primitive.positions.size() || texels.page_size <= 0) {
        return;
    }
    glm::dvec2 low(std::numeric_limits<double>::max());
    glm::dvec2 high(std::numeric_limits<double>::lowest());
    for (std::size_t t = 0; t + 2 < primitive.indices.size(); t += 3) {
        bool valid = true;
        for (std::size_t k = 0; k < 3; ++k) {
            valid = valid && primitive.indices[t + k] < uvs.size();
        }
        if (!valid) {
            continue;
        }
        for (std::size_t k = 0; k < 3; ++k) {
            const glm::dvec2 corner = glm::dvec2(uvs[primitive.indices[t + k]]) * size;
            corners_.push_back(corner);
            low = glm::min(low, corner);
            high = glm::max(high, corner);
        }
    }
    if (corners_.empty()) {
        return;
    }
    // One cell of margin all round, so cells outside the triangles exist to measure from. The
    // grid never reaches beyond the page: texels are only there, and UVs far off the page (a
    // hostile file) must not size the grid.
    low = glm::clamp(low, glm::dvec2(0.0), glm::dvec2(size));
    high = glm::clamp(high, glm::dvec2(0.0), glm::dvec2(size));
    x0_ = static_cast<int>(std::floor(low.x)) - 1;
    y0_ = static_cast<int>(std::floor(low.y)) - 1;
    width_ = static_cast<int>(std::ceil(high.x)) + 1 - x0_;
    height_ = static_cast<int>(std::ceil(high.y)) + 1 - y0_;
    cells_.resize(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_));
    for (std::size_t t = 0; t < corners_.size() / 3; ++t) {
        const glm::dvec2 offset(x0_, y0_);
        scene::for_each_covered_texel(
            corners_[3 * t] - offset, corners_[3 * t + 1] - offset, corners_[3 * t + 2] - offset,
            {0, 0, width_, height_}, [&](int x, int y) {
                cells_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                       static_cast<std::size_t>(x)]
                    .push_back(static_cast<std::uint32_t>(t));
            });
    }
    border_distance_ = border_distances(texels);
    points_.reserve(texels.texels.size());
    for (const SurfaceTexel& texel : texels.texels) {
        points_.push_back(texel.page_point);
    }
}

bool SurfaceFootprint::empty_cell(int x, int y) const {
    return x < 0 || y < 0 || x >= width_ || y >= height_ ||
           cells_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                  static_cast<std::size_t>(x)]
               .empty();
}

/// Per texel, the distance from its point to the nearest cell no triangle covers (the cells
/// beyond the grid count as empty): the distance from the point to the nearest point of those
/// closed unit squares. A search per texel costs the square of that distance, which on a
/// page-sized chart is the page: this is linear in the grid instead.
///
/// In each column, the nearest empty cell above and below every cell (two sweeps). For a point
/// at its cell's centre (every texel whose centre lies on the surface) the squared distance to
/// the empty square k columns and j rows away is (|k| - 1/2)^2 + (|j| - 1/2)^2, zero terms for
/// k or j = 0: a sum of a term per axis, so Felzenszwalb and Huttenlocher's lower envelope of
/// parabolas (Theory of Computing 8, 2012) gives every centre's minimum in one pass per row. A
/// border texel's point (the nearest surface point to a centre off the surface) is anywhere:
/// its distance is found exactly by walking the columns outward from it, stopping where the
/// column distance alone passes the best found, so it costs its distance, not its square.
std::vector<float> SurfaceFootprint::border_distances(const SurfaceTexels& texels) const {
    const auto w = static_cast<std::size_t>(width_);
    const auto h = static_cast<std::size_t>(height_);
    // Rows to the nearest empty cell at or above (y decreasing) and at or below each cell;
    // row -1 and row height_ are empty.
    std::vector<std::int32_t> up(w * h);
    std::vector<std::int32_t> down(w * h);
    for (int x = 0; x < width_; ++x) {
        std::int32_t run = 0;  // row -1
        for (int y = 0; y < height_; ++y) {
            run = empty_cell(x, y) ? 0 : run + 1;
            up[static_cast<std::size_t>(y) * w + static_cast<std::size_t>(x)] = run;
        }
        run = 0;  // row height_
        for (int y = height_ - 1; y >= 0; --y) {
            run = empty_cell(x, y) ? 0 : run + 1;
            down[static_cast<std::size_t>(y) * w + static_cast<std::size_t>(x)] = run;
        }
    }
    const std::vector<float> centres = centre_distances(up, down);

    std::vector<float> distances;
    distances.reserve(texels.texels.size());
    for (const SurfaceTexel& texel : texels.texels) {
        const glm::dvec2 point = glm::dvec2(texel.page_point) - glm::dvec2(x0_, y0_);
        const int cx = static_cast<int>(std::floor(point.x));
        const int cy = static_cast<int>(std::floor(point.y));
        if (empty_cell(cx, cy)) {
            distances.push_back(0.0f);
            continue;
        }
        const std::size_t cell = static_cast<std::size_t>(cy) * w + static_cast<std::size_t>(cx);
        const glm::dvec2 offset = point - glm::dvec2(cx, cy);
        if (offset == glm::dvec2(0.5)) {
            distances.push_back(centres[cell]);
            continue;
        }
        // Squared distance from the point to the empty square nearest it in column x.
        const auto column = [&](int x) {
            const double dx = std::max({x - point.x, 0.0, point.x - (x + 1)});
            double dy = 0.0;
            if (x >= 0 && x < width_) {
                const std::size_t at =
                    static_cast<std::size_t>(cy) * w + static_cast<std::size_t>(x);
                // The empty cell `up` rows above ends at cy - up + 1; `down` below starts at
                // cy + down.
                const double above = point.y - (cy - up[at] + 1);
                const double below = (cy + down[at]) - point.y;
                dy = up[at] == 0 ? 0.0 : std::max(0.0, std::min(above, below));
            }
            return dx * dx + dy * dy;
        };
        // The centre's distance plus the way to it bounds the point's (with a margin for the
        // float it was stored as: the bound must not fall below the true distance).
        const double bound = static_cast<double>(centres[cell]) * (1.0 + 1e-6) + 1e-6 +
                             glm::length(offset - glm::dvec2(0.5));
        double best = bound * bound;
        for (int x = cx; x >= -1; --x) {
            const double dx = point.x - (x + 1);
            if (x < cx && dx * dx >= best) {
                break;
            }
            best = std::min(best, column(x));
        }
        for (int x = cx + 1; x <= width_; ++x) {
            const double dx = x - point.x;
            if (dx * dx >= best) {
                break;
            }
            best = std::min(best, column(x));
        }
        distances.push_back(static_cast<float>(std::sqrt(best)));
    }
    return distances;
}

/// For every cell, the distance from its centre to the nearest empty square (see
/// border_distances), by rows: per column the vertical term g(x) = (k - 1/2)^2 (k rows to the
/// nearest empty cell, 0 when the cell is empty), then per row the minimum over columns x' of
/// g(x') plus the horizontal term, which is (x - 1/2 - x')^2 for x' < x, (x + 1/2 - x')^2 for
/// x' > x and 0 for x' = x. Each of the first two, taken over all x', is never below the true
/// term (the wrong side's offset only adds), so the minimum of the two lower envelopes (at
/// x - 1/2 and x + 1/2) and g(x) itself is exact. Columns -1 and width_ are empty.
std::vector<float> SurfaceFootprint::centre_distances(const std::vector<std::int32_t>& up,
                                                      const std::vector<std::int32_t>& down) const {
    const auto w = static_cast<std::size_t>(width_);
    std::vector<float> result(up.size());
    const std::size_t n = w + 2;  // parabola i stands at column i - 1
    std::vector<double> g(n);
    std::vector<std::size_t> vertex(n);
    std::vector<double> boundary(n + 1);
    for (int y = 0; y < height_; ++y) {
        g.front() = 0.0;
        g.back() = 0.0;
        for (std::size_t x = 0; x < w; ++x) {
            const std::size_t at = static_cast<std::size_t>(y) * w + x;
            const std::int32_t k = std::min(up[at], down[at]);
            g[x + 1] = k == 0 ? 0.0 : (k - 0.5) * (k - 0.5);
        }
        // The lower envelope of the parabolas (q - i)^2 + g[i] over q.
        std::size_t count = 0;
        vertex[0] = 0;
        boundary[0] = -std::numeric_limits<double>::infinity();
        boundary[1] = std::numeric_limits<double>::infinity();
        for (std::size_t i = 1; i < n; ++i) {
            const auto meet = [&](std::size_t j) {
                const auto a = static_cast<double>(i);
                const auto b = static_cast<double>(j);
                return ((g[i] + a * a) - (g[j] + b * b)) / (2.0 * (a - b));
            };
            double s = meet(vertex[count]);
            while (s <= boundary[count]) {
                --count;  // boundary[0] is -inf: the loop ends at the first parabola at latest
                s = meet(vertex[count]);
            }
            ++count;
            vertex[count] = i;
            boundary[count] = s;
            boundary[count + 1] = std::numeric_limits<double>::infinity();
        }
        // Queries at x - 1/2 and x + 1/2, in increasing order, in envelope coordinates (+1).
        std::size_t left = 0;
        std::size_t right = 0;
        const auto value = [&](std::size_t piece, double q) {
            const double d = q - static_cast<double>(vertex[piece]);
            return d * d + g[vertex[piece]];
        };
        for (std::size_t x = 0; x < w; ++x) {
            const double before = static_cast<double>(x) + 0.5;  // x - 1/2, shifted by one
            const double after = static_cast<double>(x) + 1.5;
            while (boundary[left + 1] < before) {
                ++left;
            }
            while (boundary[right + 1] < after) {
                ++right;
            }
            result[static_cast<std::size_t>(y) * w + x] = static_cast<float>(
                std::sqrt(std::min({g[x + 1], value(left, before), value(right, after)})));
        }
    }
    return result;
}

bool SurfaceFootprint::covers(const glm::dvec2& point) const {
    const int x = static_cast<int>(std::floor(point.x)) - x0_;
    const int y = static_cast<int>(std::floor(point.y)) - y0_;
    if (x < 0 || y < 0 || x >= width_ || y >= height_) {
        return false;
    }
    for (std::uint32_t t : cells_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                                  static_cast<std::size_t>(x)]) {
        if (inside(corners_[3 * t], corners_[3 * t + 1], corners_[3 * t + 2], point)) {
            return true;
        }
    }
    return false;
}

double SurfaceFootprint::fraction(std::size_t texel, double radius_texels,
                                  DensityKernel kernel) const {
    if (texel >= border_distance_.size() || !(radius_texels > 0.0) ||
        radius_texels <= static_cast<double>(border_distance_[texel])) {
        return 1.0;
    }
    const glm::dvec2 centre(points_[texel]);
    double covered = 0.0;
    double total = 0.0;
    for (const glm::dvec2& unit : disc_pattern()) {
        const double weight =
            kernel == DensityKernel::Epanechnikov ? 1.0 - glm::dot(unit, unit) : 1.0;
        covered += covers(centre + radius_texels * unit) ? weight : 0.0;
        total += weight;
    }
    // The texel's own point lies on the surface, so some of its disc does: never divide by 0.
    return std::max(covered / total, 1.0 / kSamples);
}

}  // namespace luxel::lighting
