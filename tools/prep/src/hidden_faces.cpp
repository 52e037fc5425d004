#include "luxel/prep/hidden_faces.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

#include "luxel/scene/level_check.hpp"
#include "luxel/scene/light.hpp"

namespace luxel::prep {
namespace {

/// Cells along the box's longest side: fine enough for a doorway in a 50 m level at 20 cm, and
/// at most 256^3 bytes.
constexpr double kCellsAlong = 256.0;
/// Triangle samples the voxelisation may take in all (a few seconds at most).
constexpr double kMaxSamples = 2e8;

enum : std::uint8_t { kFree = 0, kSolid = 1, kReached = 2 };

class CellGrid {
  public:
    CellGrid(glm::dvec3 lo, glm::dvec3 hi, double cell) : lo_(lo), cell_(cell) {
        const glm::dvec3 span = (hi - lo) / cell;
        count_ = glm::ivec3(glm::ceil(span)) + 1;
        cells_.assign(static_cast<std::size_t>(count_.x) * static_cast<std::size_t>(count_.y) *
                          static_cast<std::size_t>(count_.z),
                      kFree);
    }

    /// The cell holding `p`, or -1 outside the grid.
    [[nodiscard]] std::ptrdiff_t index(const glm::dvec3& p) const {
        const glm::dvec3 f = glm::floor((p - lo_) / cell_);
        if (!(f.x >= 0.0 && f.y >= 0.0 && f.z >= 0.0 && f.x < count_.x && f.y < count_.y &&
              f.z < count_.z)) {
            return -1;
        }
        return index(glm::ivec3(f));
    }
    [[nodiscard]] std::ptrdiff_t index(const glm::ivec3& c) const {
        return (static_cast<std::ptrdiff_t>(c.z) * count_.y + c.y) * count_.x + c.x;
    }
    [[nodiscard]] glm::ivec3 coordinates(std::ptrdiff_t i) const {
        const auto x = static_cast<int>(i % count_.x);
        const auto y = static_cast<int>((i / count_.x) % count_.y);
        const auto z = static_cast<int>(i / (static_cast<std::ptrdiff_t>(count_.x) * count_.y));
        return {x, y, z};
    }
    [[nodiscard]] bool inside(const glm::ivec3& c) const {
        return c.x >= 0 && c.y >= 0 && c.z >= 0 && c.x < count_.x && c.y < count_.y &&
               c.z < count_.z;
    }
    std::uint8_t& at(std::ptrdiff_t i) { return cells_[static_cast<std::size_t>(i)]; }

    /// Marks every cell the triangle passes through solid, sampled at a third of a cell.
    void mark(const VisibilityTriangle& t) {
        const double longest =
            std::max({glm::length(t.b - t.a), glm::length(t.c - t.b), glm::length(t.a - t.c)});
        const int n = std::max(1, static_cast<int>(std::ceil(3.0 * longest / cell_)));
        for (int i = 0; i <= n; ++i) {
            for (int j = 0; i + j <= n; ++j) {
                const double u = static_cast<double>(i) / n;
                const double v = static_cast<double>(j) / n;
                const std::ptrdiff_t cell = index(t.a + u * (t.b - t.a) + v * (t.c - t.a));
                if (cell >= 0) {
                    at(cell) = kSolid;
                }
            }
        }
    }

    /// Six-connected flood of the free cells from `seed`, or when its cell is solid (a light
    /// standing on the floor) from every free cell of the 26 around it, since which side the
    /// viewpoint belongs to is not known; false when there is none.
    bool flood(const glm::dvec3& seed) {
        const std::ptrdiff_t own = index(seed);
        if (own >= 0 && at(own) != kSolid) {
            fill(own);
            return true;
        }
        bool any = false;
        const glm::ivec3 c = glm::ivec3(glm::floor((seed - lo_) / cell_));
        for (int dz = -1; dz <= 1; ++dz) {
            for (int dy = -1; dy <= 1; ++dy) {
                for (int dx = -1; dx <= 1; ++dx) {
                    const glm::ivec3 n = c + glm::ivec3(dx, dy, dz);
                    if (inside(n) && at(index(n)) != kSolid) {
                        fill(index(n));
                        any = true;
                    }
                }
            }
        }
        return any;
    }

    void fill(std::ptrdiff_t start) {
        if (at(start) == kReached) {
            return;
        }
        std::vector<std::ptrdiff_t> stack{start};
        at(start) = kReached;
        constexpr std::array<glm::ivec3, 6> kSteps{glm::ivec3(1, 0, 0), glm::ivec3(-1, 0, 0),
                                                   glm::ivec3(0, 1, 0), glm::ivec3(0, -1, 0),
                                                   glm::ivec3(0, 0, 1), glm::ivec3(0, 0, -1)};
        while (!stack.empty()) {
            const glm::ivec3 c = coordinates(stack.back());
            stack.pop_back();
            for (const glm::ivec3& step : kSteps) {
                const glm::ivec3 n = c + step;
                if (inside(n) && at(index(n)) == kFree) {
                    at(index(n)) = kReached;
                    stack.push_back(index(n));
                }
            }
        }
    }

    [[nodiscard]] bool reached(const glm::dvec3& p) {
        const std::ptrdiff_t i = index(p);
        return i >= 0 && at(i) == kReached;
    }

  private:
    glm::dvec3 lo_;
    double cell_;
    glm::ivec3 count_{0};
    std::vector<std::uint8_t> cells_;
};

bool finite(const glm::dvec3& p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

/// Whether a point two cells in front of the triangle (at a grid of points a cell apart, at
/// most 16 along an edge) lies in a reached cell.
bool front_reached(const VisibilityTriangle& t, double cell, CellGrid& grid) {
    const glm::dvec3 cross = glm::cross(t.b - t.a, t.c - t.a);
    const double length = glm::length(cross);
    if (!(length > 0.0) || !std::isfinite(length)) {
        return false;
    }
    const glm::dvec3 offset = 2.0 * cell * cross / length;
    const double longest =
        std::max({glm::length(t.b - t.a), glm::length(t.c - t.b), glm::length(t.a - t.c)});
    const int n = std::clamp(static_cast<int>(std::ceil(longest / cell)), 1, 16);
    for (int i = 0; i <= n; ++i) {
        for (int j = 0; i + j <= n; ++j) {
            // Pulled a little towards the centroid, so corners shared with a neighbour in
            // another plane do not decide.
            const double u = (static_cast<double>(i) + 1.0 / 3.0) / (n + 1.0);
            const double v = (static_cast<double>(j) + 1.0 / 3.0) / (n + 1.0);
            if (grid.reached(t.a + u * (t.b - t.a) + v * (t.c - t.a) + offset)) {
                return true;
            }
        }
    }
    return false;
}

}  // namespace

std::vector<glm::dvec3> viewpoints(const scene::Scene& scene) {
    const std::vector<glm::mat4> world = scene.world_matrices();
    std::vector<glm::dvec3> points;
    for (std::size_t i = 0; i < scene.nodes.size() && i < world.size(); ++i) {
        const scene::Node& node = scene.nodes[i];
        bool viewpoint = node.camera >= 0;
        if (node.light >= 0 && static_cast<std::size_t>(node.light) < scene.lights.size()) {
            // A directional light has no place; its node may stand anywhere, outside too.
            viewpoint = viewpoint || scene.lights[static_cast<std::size_t>(node.light)].type !=
                                         scene::LightType::Directional;
        }
        if (viewpoint) {
            points.emplace_back(glm::dvec3(world[i][3]));
        }
    }
    if (points.empty()) {
        // Neither a camera nor a light with a place: luxel shows the level from its default
        // view. (A level with lights but no camera is judged from its lights: the default view
        // is an arbitrary point, outside many rooms, and the game brings its own camera.)
        points.emplace_back(glm::dvec3(scene::DefaultView{}.eye));
    }
    return points;
}

Visibility find_seen_surfaces(std::span<const VisibilityTriangle> triangles,
                              std::size_t surface_count, std::span<const glm::dvec3> viewpoints,
                              double min_cell, double max_cell) {
    Visibility result;
    result.seen.assign(surface_count, true);
    glm::dvec3 lo(std::numeric_limits<double>::max());
    glm::dvec3 hi(std::numeric_limits<double>::lowest());
    for (const VisibilityTriangle& t : triangles) {
        for (const glm::dvec3& p : {t.a, t.b, t.c}) {
            if (finite(p)) {
                lo = glm::min(lo, p);
                hi = glm::max(hi, p);
            }
        }
    }
    std::vector<glm::dvec3> seeds;
    for (const glm::dvec3& p : viewpoints) {
        if (finite(p)) {
            seeds.push_back(p);
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
    }
    if (triangles.empty() || seeds.empty() || !(hi.x >= lo.x)) {
        result.skipped = "no geometry or no viewpoint";
        return result;
    }
    const double longest = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    // No finer than `min_cell` (a texel): finer cells would find gaps no texel resolves, at
    // eight times the cost per halving.
    const double cell = std::max(longest / kCellsAlong, min_cell);
    if (!(cell > 0.0) || cell > max_cell) {
        result.skipped = "the level is too large to judge at cells of " + std::to_string(max_cell) +
                         " m or finer";
        return result;
    }
    // Estimate the voxelisation's samples before taking them.
    double samples = 0.0;
    for (const VisibilityTriangle& t : triangles) {
        if (!t.dynamic) {
            const double edge =
                std::max({glm::length(t.b - t.a), glm::length(t.c - t.b), glm::length(t.a - t.c)});
            const double n = std::max(1.0, std::ceil(3.0 * edge / cell));
            samples += 0.5 * (n + 1.0) * (n + 2.0);
        }
    }
    if (!(samples <= kMaxSamples)) {
        result.skipped = "too much geometry to sample";
        return result;
    }
    // Two free cells of margin all round, so the flood can pass around an open level.
    CellGrid grid(lo - 2.0 * cell, hi + 2.0 * cell, cell);
    for (const VisibilityTriangle& t : triangles) {
        if (!t.dynamic && finite(t.a) && finite(t.b) && finite(t.c)) {
            grid.mark(t);
        }
    }
    bool flooded = false;
    for (const glm::dvec3& seed : seeds) {
        flooded = grid.flood(seed) || flooded;
    }
    if (!flooded) {
        result.skipped = "every viewpoint lies inside geometry";
        return result;
    }
    result.cell_size = cell;
    // A surface smaller than 4 x 4 cells is not judged: a 10 cm cube among others 10 cm apart
    // is below what the cells resolve, and its few texels cost nothing.
    std::vector<double> area(surface_count, 0.0);
    for (const VisibilityTriangle& t : triangles) {
        if (t.surface < surface_count) {
            area[t.surface] += 0.5 * glm::length(glm::cross(t.b - t.a, t.c - t.a));
        }
    }
    std::vector<bool> seen(surface_count, false);
    for (const VisibilityTriangle& t : triangles) {
        if (t.surface >= surface_count || seen[t.surface]) {
            continue;
        }
        if (t.dynamic || !finite(t.a) || !finite(t.b) || !finite(t.c) ||
            !(area[t.surface] >= 16.0 * cell * cell) || front_reached(t, cell, grid)) {
            seen[t.surface] = true;
        }
    }
    result.seen = std::move(seen);
    return result;
}

}  // namespace luxel::prep
