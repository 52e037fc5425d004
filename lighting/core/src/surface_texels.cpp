#include "luxel/lighting/core/surface_texels.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "luxel/scene/texel_coverage.hpp"

namespace luxel::lighting {
namespace {

/// Barycentric coordinates of the point of triangle (a, b, c) nearest to p, in 2D.
glm::dvec3 nearest_barycentric(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c,
                               const glm::dvec2& p) {
    const double twice_area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    if (twice_area != 0.0) {
        const double wa = ((b.x - p.x) * (c.y - p.y) - (b.y - p.y) * (c.x - p.x)) / twice_area;
        const double wb = ((c.x - p.x) * (a.y - p.y) - (c.y - p.y) * (a.x - p.x)) / twice_area;
        const double wc = 1.0 - wa - wb;
        if (wa >= 0.0 && wb >= 0.0 && wc >= 0.0) {
            return {wa, wb, wc};
        }
    }
    // Outside: the nearest point lies on an edge.
    const std::array<glm::dvec2, 3> corner{a, b, c};
    glm::dvec3 best(1.0, 0.0, 0.0);
    double best_distance = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 3; ++i) {
        const glm::dvec2 from = corner[static_cast<std::size_t>(i)];
        const glm::dvec2 to = corner[static_cast<std::size_t>((i + 1) % 3)];
        const glm::dvec2 edge = to - from;
        const double length2 = glm::dot(edge, edge);
        const double t =
            length2 > 0.0 ? std::clamp(glm::dot(p - from, edge) / length2, 0.0, 1.0) : 0.0;
        const double distance = glm::length(from + t * edge - p);
        if (distance < best_distance) {
            best_distance = distance;
            glm::dvec3 weights(0.0);
            weights[i] = 1.0 - t;
            weights[(i + 1) % 3] = t;
            best = weights;
        }
    }
    return best;
}

double distance_to_triangle(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c,
                            const glm::dvec2& p, const glm::dvec3& weights) {
    return glm::length(weights.x * a + weights.y * b + weights.z * c - p);
}

}  // namespace

SurfaceTexels rasterize_surface(const scene::Primitive& primitive, int page, int page_size) {
    SurfaceTexels result;
    result.page = page;
    result.page_size = page_size;
    const auto& positions = primitive.positions;
    const auto& uvs = primitive.texcoords1;
    if (page_size <= 0 || uvs.size() != positions.size()) {
        return result;
    }
    struct Candidate {
        double distance = std::numeric_limits<double>::infinity();
        std::size_t triangle = 0;
        glm::dvec3 weights{0.0};
    };
    // Keyed by page texel; a surface covers a compact rectangle, so this stays small.
    std::unordered_map<std::int64_t, Candidate> best;
    const double size = page_size;
    const std::size_t triangles = primitive.indices.size() / 3;
    double uv_area = 0.0;
    for (std::size_t t = 0; t < triangles; ++t) {
        const std::uint32_t i0 = primitive.indices[3 * t];
        const std::uint32_t i1 = primitive.indices[3 * t + 1];
        const std::uint32_t i2 = primitive.indices[3 * t + 2];
        if (i0 >= uvs.size() || i1 >= uvs.size() || i2 >= uvs.size()) {
            continue;
        }
        const glm::dvec3 p0(positions[i0]);
        const glm::dvec3 p1(positions[i1]);
        const glm::dvec3 p2(positions[i2]);
        result.area += 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0));
        const glm::dvec2 a = glm::dvec2(uvs[i0]) * size;
        const glm::dvec2 b = glm::dvec2(uvs[i1]) * size;
        const glm::dvec2 c = glm::dvec2(uvs[i2]) * size;
        uv_area += 0.5 * std::abs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
        scene::for_each_covered_texel(a, b, c, {0, 0, page_size, page_size}, [&](int x, int y) {
            const glm::dvec2 centre(x + 0.5, y + 0.5);
            const glm::dvec3 weights = nearest_barycentric(a, b, c, centre);
            const double distance = distance_to_triangle(a, b, c, centre, weights);
            Candidate& slot = best[static_cast<std::int64_t>(y) * page_size + x];
            if (distance < slot.distance) {
                slot = {distance, t, weights};
            }
        });
    }
    result.metres_per_texel = uv_area > 0.0 ? std::sqrt(result.area / uv_area) : 0.0;
    result.texels.reserve(best.size());
    for (const auto& [key, candidate] : best) {
        const std::size_t t = candidate.triangle;
        const std::array<std::uint32_t, 3> corner{
            primitive.indices[3 * t], primitive.indices[3 * t + 1], primitive.indices[3 * t + 2]};
        const glm::dvec3& w = candidate.weights;
        glm::dvec3 position(0.0);
        glm::dvec3 normal(0.0);
        for (std::size_t k = 0; k < 3; ++k) {
            position += w[static_cast<glm::length_t>(k)] * glm::dvec3(positions[corner[k]]);
            if (primitive.normals.size() == positions.size()) {
                normal +=
                    w[static_cast<glm::length_t>(k)] * glm::dvec3(primitive.normals[corner[k]]);
            }
        }
        const glm::dvec3 face =
            glm::cross(glm::dvec3(positions[corner[1]]) - glm::dvec3(positions[corner[0]]),
                       glm::dvec3(positions[corner[2]]) - glm::dvec3(positions[corner[0]]));
        if (!(glm::length(normal) > 1e-12)) {
            normal = face;
        }
        if (!(glm::length(normal) > 0.0)) {
            continue;  // a degenerate triangle has no side to light
        }
        SurfaceTexel texel;
        texel.x = static_cast<std::int32_t>(key % page_size);
        texel.y = static_cast<std::int32_t>(key / page_size);
        texel.position = glm::vec3(position);
        texel.normal = glm::vec3(glm::normalize(normal));
        texel.face_normal =
            glm::length(face) > 0.0 ? glm::vec3(glm::normalize(face)) : texel.normal;
        glm::dvec2 point(0.0);
        for (std::size_t k = 0; k < 3; ++k) {
            point += w[static_cast<glm::length_t>(k)] * glm::dvec2(uvs[corner[k]]) * size;
        }
        texel.page_point = glm::vec2(point);
        result.texels.push_back(texel);
    }
    // Row order: deterministic, and neighbouring texels are gathered together.
    std::sort(result.texels.begin(), result.texels.end(),
              [](const SurfaceTexel& l, const SurfaceTexel& r) {
                  return l.y != r.y ? l.y < r.y : l.x < r.x;
              });
    return result;
}

}  // namespace luxel::lighting
