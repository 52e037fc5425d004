#include "luxel/lighting/core/light_map_seams.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <tuple>

#include "luxel/scene/welding.hpp"

namespace luxel::lighting {

namespace {

/// Shading normals closer than this (cos 8 degrees) run on smoothly across an edge: the same
/// vertex normal written twice, or a smooth mesh's normals interpolated a rounding apart. A
/// crease (luxel-prep's default 45 degrees, a box's 90) is far outside it.
constexpr float kSmoothCos = 0.99f;
/// UVs closer than this (texels) are the same corner of one chart.
constexpr float kSameCorner = 1e-3f;

/// One triangle's use of an edge, its corners ordered by welded id (low first). Kept in one flat
/// list sorted by edge (32 bytes a use, three a triangle), not a hash map of lists: a level of
/// millions of triangles finds its seams in a few hundred bytes a triangle at most.
struct EdgeUse {
    std::uint64_t edge = 0;  ///< the two welded ids, low in the high bits
    std::uint32_t side = 0;  ///< index into the surfaces
    std::uint32_t low = 0;
    std::uint32_t high = 0;
    glm::vec3 face_normal{0.0f};
};

bool finite(const glm::vec2& v) {
    return std::isfinite(v.x) && std::isfinite(v.y);
}

glm::vec3 shading_normal(const scene::Primitive& primitive, std::uint32_t vertex,
                         const glm::vec3& face_normal) {
    if (primitive.normals.size() == primitive.positions.size()) {
        const glm::vec3 n = primitive.normals[vertex];
        const float length = glm::length(n);
        if (length > 0.0f && std::isfinite(length)) {
            return n / length;
        }
    }
    return face_normal;
}

bool same_quantity(const SeamSurface& a, const SeamSurface& b) {
    if (a.content != b.content) {
        return false;
    }
    // Irradiance is continuous whatever the albedo; radiance only where the albedo is too.
    return a.content == IimContent::Irradiance ||
           glm::all(glm::lessThanEqual(glm::abs(a.albedo - b.albedo), glm::vec3(1e-4f)));
}

bool usable(const SeamSurface& s) {
    return s.primitive != nullptr && s.page >= 0 && s.page_size > 0 &&
           s.primitive->texcoords1.size() == s.primitive->positions.size() &&
           s.primitive->indices.size() % 3 == 0;
}

}  // namespace

std::vector<SeamSample> find_seams(std::span<const SeamSurface> surfaces) {
    // Every usable primitive's positions in one list, welded together.
    std::vector<glm::vec3> positions;
    std::vector<std::size_t> offset(surfaces.size(), 0);
    glm::vec3 lo(std::numeric_limits<float>::max());
    glm::vec3 hi(std::numeric_limits<float>::lowest());
    for (std::size_t s = 0; s < surfaces.size(); ++s) {
        offset[s] = positions.size();
        if (!usable(surfaces[s])) {
            continue;
        }
        for (const glm::vec3& p : surfaces[s].primitive->positions) {
            positions.push_back(p);
            if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) {
                lo = glm::min(lo, p);
                hi = glm::max(hi, p);
            }
        }
    }
    if (positions.empty() || !(hi.x >= lo.x)) {
        return {};
    }
    const float extent = glm::length(hi - lo);
    const std::vector<std::uint32_t> id =
        scene::welded_ids(positions, std::isfinite(extent) ? 1e-5f * extent : 0.0f);

    std::vector<EdgeUse> edges;
    std::size_t corners = 0;
    for (const SeamSurface& surface : surfaces) {
        corners += usable(surface) ? surface.primitive->indices.size() : 0;
    }
    edges.reserve(corners);  // three uses a triangle, one per corner
    for (std::size_t s = 0; s < surfaces.size(); ++s) {
        if (!usable(surfaces[s])) {
            continue;
        }
        const scene::Primitive& primitive = *surfaces[s].primitive;
        for (std::size_t t = 0; t + 2 < primitive.indices.size(); t += 3) {
            std::array<std::uint32_t, 3> vertex{};
            std::array<std::uint32_t, 3> welded{};
            bool valid = true;
            for (std::size_t c = 0; c < 3; ++c) {
                vertex[c] = primitive.indices[t + c];
                valid = valid && vertex[c] < primitive.positions.size();
                if (valid) {
                    welded[c] = id[offset[s] + vertex[c]];
                }
            }
            if (!valid || welded[0] == welded[1] || welded[1] == welded[2] ||
                welded[2] == welded[0]) {
                continue;
            }
            const glm::vec3 cross =
                glm::cross(primitive.positions[vertex[1]] - primitive.positions[vertex[0]],
                           primitive.positions[vertex[2]] - primitive.positions[vertex[0]]);
            const float length = glm::length(cross);
            if (!(length > 0.0f) || !std::isfinite(length)) {
                continue;  // a degenerate triangle joins nothing
            }
            for (std::size_t e = 0; e < 3; ++e) {
                std::size_t a = e;
                std::size_t b = (e + 1) % 3;
                if (welded[a] > welded[b]) {
                    std::swap(a, b);
                }
                const std::uint64_t key = (static_cast<std::uint64_t>(welded[a]) << 32) |
                                          static_cast<std::uint64_t>(welded[b]);
                edges.push_back(
                    {key, static_cast<std::uint32_t>(s), vertex[a], vertex[b], cross / length});
            }
        }
    }

    std::sort(edges.begin(), edges.end(), [](const EdgeUse& x, const EdgeUse& y) {
        return std::tie(x.edge, x.side, x.low, x.high) < std::tie(y.edge, y.side, y.low, y.high);
    });
    std::vector<SeamSample> samples;
    for (std::size_t i = 0, next = 0; i < edges.size(); i = next) {
        next = i + 1;
        while (next < edges.size() && edges[next].edge == edges[i].edge) {
            ++next;
        }
        if (next - i != 2) {
            continue;  // a border, or a non-manifold edge: nothing on the other side to agree with
        }
        const std::array<EdgeUse, 2> uses{edges[i], edges[i + 1]};
        const SeamSurface& sa = surfaces[uses[0].side];
        const SeamSurface& sb = surfaces[uses[1].side];
        const float size_a = static_cast<float>(sa.page_size);
        const float size_b = static_cast<float>(sb.page_size);
        const glm::vec2 a0 = sa.primitive->texcoords1[uses[0].low] * size_a;
        const glm::vec2 a1 = sa.primitive->texcoords1[uses[0].high] * size_a;
        const glm::vec2 b0 = sb.primitive->texcoords1[uses[1].low] * size_b;
        const glm::vec2 b1 = sb.primitive->texcoords1[uses[1].high] * size_b;
        if (!finite(a0) || !finite(a1) || !finite(b0) || !finite(b1)) {
            continue;
        }
        if (sa.surface == sb.surface && glm::length(a0 - b0) < kSameCorner &&
            glm::length(a1 - b1) < kSameCorner) {
            continue;  // inside one chart: the bilinear lookup is already continuous
        }
        if (!same_quantity(sa, sb)) {
            continue;
        }
        const bool smooth =
            glm::dot(shading_normal(*sa.primitive, uses[0].low, uses[0].face_normal),
                     shading_normal(*sb.primitive, uses[1].low, uses[1].face_normal)) >=
                kSmoothCos &&
            glm::dot(shading_normal(*sa.primitive, uses[0].high, uses[0].face_normal),
                     shading_normal(*sb.primitive, uses[1].high, uses[1].face_normal)) >=
                kSmoothCos;
        if (!smooth) {
            continue;
        }
        // Two samples per texel of the longer side, so each texel the lookups read is pinned
        // by more than one; capped so a hostile UV spanning far past the page stays bounded.
        const float texels = std::max(glm::length(a1 - a0), glm::length(b1 - b0));
        const float cap = 8.0f * std::max(size_a, size_b);
        const int count = static_cast<int>(std::ceil(std::clamp(2.0f * texels, 1.0f, cap)));
        const glm::vec3 p0 = sa.primitive->positions[uses[0].low];
        const glm::vec3 p1 = sa.primitive->positions[uses[0].high];
        const float edge = glm::length(p1 - p0);
        const glm::vec3 along =
            edge > 0.0f && std::isfinite(edge) ? (p1 - p0) / edge : glm::vec3(0.0f);
        for (int k = 0; k < count; ++k) {
            const float t = (static_cast<float>(k) + 0.5f) / static_cast<float>(count);
            samples.push_back({sa.surface, sa.page, glm::mix(a0, a1, t), sb.surface, sb.page,
                               glm::mix(b0, b1, t), glm::mix(p0, p1, t), along});
        }
    }
    // Map iteration order is not fixed; the samples are, so two runs stitch alike.
    std::sort(samples.begin(), samples.end(), [](const SeamSample& x, const SeamSample& y) {
        return std::tie(x.page_a, x.point_a.y, x.point_a.x, x.page_b, x.point_b.y, x.point_b.x) <
               std::tie(y.page_a, y.point_a.y, y.point_a.x, y.page_b, y.point_b.y, y.point_b.x);
    });
    return samples;
}

double seam_mismatch(std::span<const SeamSample> samples, std::span<const IimPage> pages) {
    double difference = 0.0;
    double level = 0.0;
    const auto lookup = [&](std::int32_t page, const glm::vec2& point) {
        if (page < 0 || static_cast<std::size_t>(page) >= pages.size()) {
            return glm::vec3(0.0f);
        }
        const RadiancePage& current = pages[static_cast<std::size_t>(page)].current;
        const float size = static_cast<float>(std::max(current.size, 1));
        return current.sample(point / size);
    };
    for (const SeamSample& s : samples) {
        const glm::dvec3 a(lookup(s.page_a, s.point_a));
        const glm::dvec3 b(lookup(s.page_b, s.point_b));
        const glm::dvec3 d = a - b;
        const glm::dvec3 m = 0.5 * (a + b);
        difference += glm::dot(d, d);
        level += glm::dot(m, m);
    }
    return level > 0.0 && std::isfinite(difference) ? std::sqrt(difference / level) : 0.0;
}

}  // namespace luxel::lighting
