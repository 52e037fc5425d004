#include "parameterization.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "luxel/prep/raster.hpp"

namespace luxel::prep::detail {
namespace {

double cross2(const glm::dvec2& a, const glm::dvec2& b) {
    return a.x * b.y - a.y * b.x;
}

/// Andrew's monotone chain: the convex hull, counter-clockwise, without collinear points.
std::vector<glm::dvec2> convex_hull(std::vector<glm::dvec2> points) {
    std::sort(points.begin(), points.end(), [](const glm::dvec2& a, const glm::dvec2& b) {
        return a.x < b.x || (a.x == b.x && a.y < b.y);
    });
    points.erase(std::unique(points.begin(), points.end()), points.end());
    if (points.size() < 3) {
        return points;
    }
    std::vector<glm::dvec2> hull(2 * points.size());
    std::size_t k = 0;
    for (const auto& p : points) {  // lower hull
        while (k >= 2 && cross2(hull[k - 1] - hull[k - 2], p - hull[k - 2]) <= 0.0) {
            --k;
        }
        hull[k++] = p;
    }
    for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {  // upper hull
        const auto& p = points[i];
        while (k >= lower && cross2(hull[k - 1] - hull[k - 2], p - hull[k - 2]) <= 0.0) {
            --k;
        }
        hull[k++] = p;
    }
    hull.resize(k - 1);
    return hull;
}

/// Rotates uv so that its bounding rectangle is the smallest over the directions of its
/// convex hull's edges (the minimum-area rectangle has a side along one of them), then by a
/// quarter turn if needed so the rectangle is at least as wide as it is tall.
void orient_to_smallest_rectangle(std::vector<glm::dvec2>& uv) {
    const std::vector<glm::dvec2> hull = convex_hull(uv);
    glm::dvec2 best_direction(1.0, 0.0);
    double best_area = std::numeric_limits<double>::max();
    // Very round charts have long hulls; a few hundred directions find the rectangle to well
    // within a texel.
    const std::size_t step = std::max<std::size_t>(1, hull.size() / 256);
    for (std::size_t i = 0; i < hull.size(); i += step) {
        const glm::dvec2 edge = hull[(i + 1) % hull.size()] - hull[i];
        const double length = glm::length(edge);
        if (!(length > 0.0)) {
            continue;
        }
        const glm::dvec2 direction = edge / length;
        double min_along = std::numeric_limits<double>::max();
        double max_along = std::numeric_limits<double>::lowest();
        double min_across = min_along;
        double max_across = max_along;
        for (const auto& p : hull) {
            const double along = glm::dot(p, direction);
            const double across = cross2(direction, p);
            min_along = std::min(min_along, along);
            max_along = std::max(max_along, along);
            min_across = std::min(min_across, across);
            max_across = std::max(max_across, across);
        }
        const double area = (max_along - min_along) * (max_across - min_across);
        // Prefer the earlier direction unless clearly better, so near-ties between an axis
        // aligned edge and a rounding-noise variant of it keep the exact axis.
        if (area < best_area * (1.0 - 1e-9)) {
            best_area = area;
            best_direction = direction;
        }
    }
    const glm::dvec2 d = best_direction;
    glm::dvec2 low(std::numeric_limits<double>::max());
    glm::dvec2 high(std::numeric_limits<double>::lowest());
    for (auto& p : uv) {
        p = glm::dvec2(d.x * p.x + d.y * p.y, -d.y * p.x + d.x * p.y);
        low = glm::min(low, p);
        high = glm::max(high, p);
    }
    if (high.y - low.y > high.x - low.x) {
        for (auto& p : uv) {
            p = glm::dvec2(-p.y, p.x);  // a quarter turn keeps the winding
        }
    }
}

}  // namespace

glm::dvec3 Patch::centroid(int face) const {
    const auto& c = corners[static_cast<std::size_t>(face)];
    return (positions[static_cast<std::size_t>(c[0])] + positions[static_cast<std::size_t>(c[1])] +
            positions[static_cast<std::size_t>(c[2])]) /
           3.0;
}

Patch make_patch(const NodeGeometry& geometry, const std::vector<int>& faces) {
    Patch patch;
    patch.node_face = faces;
    patch.corners.resize(faces.size());
    patch.neighbours.resize(faces.size());
    patch.normals.resize(faces.size());
    patch.areas.resize(faces.size());
    std::unordered_map<int, int> local_face;
    std::unordered_map<int, int> local_vertex;
    local_face.reserve(faces.size());
    local_vertex.reserve(faces.size());
    for (std::size_t i = 0; i < faces.size(); ++i) {
        local_face.emplace(faces[i], static_cast<int>(i));
    }
    for (std::size_t i = 0; i < faces.size(); ++i) {
        const Face& face = geometry.faces[static_cast<std::size_t>(faces[i])];
        for (std::size_t c = 0; c < 3; ++c) {
            const auto [entry, inserted] =
                local_vertex.emplace(face.vertices[c], static_cast<int>(patch.node_vertex.size()));
            if (inserted) {
                patch.node_vertex.push_back(face.vertices[c]);
                patch.positions.push_back(geometry.position(face.vertices[c]));
            }
            patch.corners[i][c] = entry->second;
            const auto across = local_face.find(face.neighbours[c]);
            patch.neighbours[i][c] = across == local_face.end() ? -1 : across->second;
        }
        patch.normals[i] = face.normal;
        patch.areas[i] = face.area;
    }
    return patch;
}

Piece make_piece(const Patch& patch, std::vector<int> faces, std::vector<int>& scratch) {
    Piece piece;
    piece.faces = std::move(faces);
    piece.corners.resize(piece.faces.size());
    for (std::size_t i = 0; i < piece.faces.size(); ++i) {
        const auto& corners = patch.corners[static_cast<std::size_t>(piece.faces[i])];
        for (std::size_t c = 0; c < 3; ++c) {
            int& local = scratch[static_cast<std::size_t>(corners[c])];
            if (local < 0) {
                local = static_cast<int>(piece.vertices.size());
                piece.vertices.push_back(corners[c]);
            }
            piece.corners[i][c] = local;
        }
    }
    for (const int v : piece.vertices) {
        scratch[static_cast<std::size_t>(v)] = -1;
    }
    return piece;
}

std::vector<glm::dvec2> planar_projection(const Patch& patch, const Piece& piece,
                                          const glm::dvec3& axis) {
    const glm::dvec3 n = glm::normalize(axis);
    // The world axis least aligned with n gives a well-conditioned tangent.
    const glm::dvec3 a = glm::abs(n);
    const glm::dvec3 helper = a.x <= a.y && a.x <= a.z ? glm::dvec3(1, 0, 0)
                              : a.y <= a.z             ? glm::dvec3(0, 1, 0)
                                                       : glm::dvec3(0, 0, 1);
    const glm::dvec3 tangent = glm::normalize(glm::cross(helper, n));
    const glm::dvec3 bitangent = glm::cross(n, tangent);
    std::vector<glm::dvec2> uv;
    uv.reserve(piece.vertices.size());
    for (const int v : piece.vertices) {
        const glm::dvec3& p = patch.positions[static_cast<std::size_t>(v)];
        uv.emplace_back(glm::dot(p, tangent), glm::dot(p, bitangent));
    }
    return uv;
}

FittedChart fit_chart(const Patch& patch, const Piece& piece, std::vector<glm::dvec2> uv,
                      const ChartLimits& limits) {
    FittedChart fitted;
    auto uv_area = [&](std::size_t i) {
        const auto& c = piece.corners[i];
        const glm::dvec2 a = uv[static_cast<std::size_t>(c[0])];
        return 0.5 * cross2(uv[static_cast<std::size_t>(c[1])] - a,
                            uv[static_cast<std::size_t>(c[2])] - a);
    };
    // Area ratios (world / flattened) before scaling, and the winding of every triangle.
    double ratio_min = std::numeric_limits<double>::max();
    double ratio_max = 0.0;
    double world_area = 0.0;
    double flat_area = 0.0;
    for (std::size_t i = 0; i < piece.faces.size(); ++i) {
        const double area = uv_area(i);
        const double world = patch.areas[static_cast<std::size_t>(piece.faces[i])];
        if (!(area > 0.0) || !std::isfinite(area)) {
            fitted.failure = "flipped or collapsed triangle";
            return fitted;
        }
        ratio_min = std::min(ratio_min, world / area);
        ratio_max = std::max(ratio_max, world / area);
        world_area += world;
        flat_area += area;
    }
    // Scaling the flattening by k divides every ratio by k^2. Aim for exact total area, but
    // keep every triangle inside the bounds, with a little room for the snap to whole texels
    // below.
    const double bound = limits.max_stretch * 0.97;
    const double k2_low = ratio_max / bound;
    const double k2_high = ratio_min * bound;
    if (k2_low > k2_high) {
        fitted.failure = "stretch";
        return fitted;
    }
    const double k2 = std::clamp(world_area / flat_area, k2_low, k2_high);
    const double scale = std::sqrt(k2) / limits.texel_size;
    for (auto& p : uv) {
        p *= scale;
    }
    orient_to_smallest_rectangle(uv);

    // Snap the extent to whole texels: a width just over an integer (rounding, or a wall of an
    // exact texel multiple) shrinks by a hair instead of costing a column of texels, and the
    // chart keeps a margin from the rectangle's border so float UVs stay inside it.
    constexpr double kSnap = 0.01;
    constexpr double kMargin = 1e-3;
    glm::dvec2 low(std::numeric_limits<double>::max());
    glm::dvec2 high(std::numeric_limits<double>::lowest());
    for (const auto& p : uv) {
        low = glm::min(low, p);
        high = glm::max(high, p);
    }
    const glm::dvec2 extent = high - low;
    // A chart wider than a page is cut by the caller, along the long side of this flattening.
    const double max_side = static_cast<double>(limits.max_extent - 2 * limits.padding);
    if (!(extent.x <= max_side && extent.y <= max_side)) {
        fitted.too_large = true;
        fitted.failure = "larger than a page";
        fitted.uv = std::move(uv);
        return fitted;
    }
    fitted.width = std::max(1, static_cast<int>(std::ceil(extent.x - kSnap)));
    fitted.height = std::max(1, static_cast<int>(std::ceil(extent.y - kSnap)));
    const double shrink = std::min({1.0, (fitted.width - 2.0 * kMargin) / extent.x,
                                    (fitted.height - 2.0 * kMargin) / extent.y});
    const glm::dvec2 offset = 0.5 * (glm::dvec2(fitted.width, fitted.height) - extent * shrink);
    for (auto& p : uv) {
        p = (p - low) * shrink + offset;
    }

    fitted.stretch_min = std::numeric_limits<double>::max();
    fitted.stretch_max = 0.0;
    const double texel_area = limits.texel_size * limits.texel_size;
    for (std::size_t i = 0; i < piece.faces.size(); ++i) {
        const double world = patch.areas[static_cast<std::size_t>(piece.faces[i])];
        const double stretch = world / texel_area / uv_area(i);
        fitted.stretch_min = std::min(fitted.stretch_min, stretch);
        fitted.stretch_max = std::max(fitted.stretch_max, stretch);
        fitted.stretch_area_sum += world * stretch;
    }
    if (!(fitted.stretch_max <= limits.max_stretch &&
          fitted.stretch_min >= 1.0 / limits.max_stretch)) {
        fitted.failure = "stretch after snapping";
        return fitted;
    }
    if (triangles_overlap(uv, piece.corners, fitted.width, fitted.height)) {
        fitted.failure = "overlap";
        return fitted;
    }
    fitted.uv = std::move(uv);
    fitted.ok = true;
    return fitted;
}

}  // namespace luxel::prep::detail

namespace luxel::prep::detail {

Flattening flatten_piece(const Patch& patch, const Piece& piece, const glm::dvec3& normal_sum,
                         double min_cos, bool has_boundary, const ChartLimits& limits,
                         std::size_t* conformal_failures) {
    // A planar projection this close to uniform is kept without trying the conformal map.
    constexpr double kGoodEnoughDistortion = 1.1;
    double area = 0.0;
    for (const int f : piece.faces) {
        area += patch.areas[static_cast<std::size_t>(f)];
    }
    Flattening best;
    if (glm::length(normal_sum) > 1e-6 * area && min_cos > 0.05) {
        best.fitted = fit_chart(patch, piece, planar_projection(patch, piece, normal_sum), limits);
    }
    const bool planar_good = best.fitted.ok && best.fitted.distortion() <= kGoodEnoughDistortion;
    if (planar_good || best.fitted.too_large || !has_boundary ||
        piece.faces.size() > limits.max_conformal_faces) {
        return best;
    }
    std::size_t failures = 0;
    if (auto uv = conformal_map(patch, piece)) {
        FittedChart conformal = fit_chart(patch, piece, std::move(*uv), limits);
        failures += conformal.ok ? 0 : 1;
        // A conformal map too wide for a page is only worth cutting along when nothing else
        // worked.
        if ((conformal.ok &&
             (!best.fitted.ok || conformal.distortion() < best.fitted.distortion())) ||
            (conformal.too_large && !best.fitted.ok)) {
            best.fitted = std::move(conformal);
            best.method = ChartMethod::Conformal;
        }
    } else {
        ++failures;
    }
    if (conformal_failures != nullptr) {
        *conformal_failures += failures;
    }
    return best;
}

}  // namespace luxel::prep::detail
