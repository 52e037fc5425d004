#include "luxel/lighting/core/emission_pieces.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "luxel/runtime/error.hpp"
#include "luxel/scene/texture_mean.hpp"

namespace luxel::lighting {
namespace {

/// Pieces before row j of a level-n triangle: rows hold 2 (n - r) - 1 pieces each.
std::uint32_t row_offset(std::uint32_t n, std::uint32_t j) {
    return j * (2 * n - j);
}

/// The level that cuts a triangle covering `texels` texel squares into pieces of about one.
double wanted_level(double texels) {
    return std::clamp(std::ceil(std::sqrt(std::max(texels, 0.0))), 1.0,
                      static_cast<double>(EmissionPieces::kMaxLevel));
}

}  // namespace

void EmissionPieces::add(std::uint32_t level, const std::vector<glm::vec3>& radiance) {
    if (level == 0 || static_cast<std::size_t>(level) * level != radiance.size()) {
        throw Error("EmissionPieces: a level-" + std::to_string(level) + " triangle needs " +
                    std::to_string(static_cast<std::size_t>(level) * level) + " pieces, not " +
                    std::to_string(radiance.size()));
    }
    level_.push_back(level);
    first_.push_back(radiance_.size());
    radiance_.insert(radiance_.end(), radiance.begin(), radiance.end());
}

bool EmissionPieces::uniform() const {
    return std::all_of(radiance_.begin(), radiance_.end(),
                       [&](const glm::vec3& r) { return r == radiance_.front(); });
}

std::uint32_t EmissionPieces::piece_at(std::uint32_t level, glm::dvec2 sq) {
    const double n = static_cast<double>(std::max<std::uint32_t>(level, 1));
    double s = std::isfinite(sq.x) ? std::clamp(sq.x, 0.0, 1.0) : 0.0;
    double q = std::isfinite(sq.y) ? std::clamp(sq.y, 0.0, 1.0) : 0.0;
    if (s + q > 1.0) {
        const double over = s + q;
        s /= over;
        q /= over;
    }
    const auto last = static_cast<double>(level - 1);
    const double j = std::min(std::floor(q * n), last);
    const double i = std::min(std::floor(s * n), last - j);
    const bool upper = (s * n - i) + (q * n - j) > 1.0 && i + j < last;
    const auto ui = static_cast<std::uint32_t>(i);
    const auto uj = static_cast<std::uint32_t>(j);
    return row_offset(level, uj) + 2 * ui + (upper ? 1u : 0u);
}

std::array<glm::dvec2, 3> EmissionPieces::corners(std::uint32_t level, std::uint32_t piece) {
    const std::uint32_t n = std::max<std::uint32_t>(level, 1);
    std::uint32_t j = 0;
    while (j + 1 < n && row_offset(n, j + 1) <= piece) {
        ++j;
    }
    const std::uint32_t within = piece - row_offset(n, j);
    const double i = within / 2;
    const double dj = j;
    const double scale = 1.0 / n;
    if (within % 2 == 0) {
        return {glm::dvec2(i, dj) * scale, glm::dvec2(i + 1, dj) * scale,
                glm::dvec2(i, dj + 1) * scale};
    }
    return {glm::dvec2(i + 1, dj + 1) * scale, glm::dvec2(i, dj + 1) * scale,
            glm::dvec2(i + 1, dj) * scale};
}

EmissionPieces EmissionPieces::of_mesh(const scene::Scene& scene, const scene::Mesh& mesh) {
    struct Part {
        const scene::Primitive* primitive;
        const scene::Material* material;
        const scene::LinearImage* texels;
    };
    // Each image decoded once: a mesh's primitives often share one emissive texture, and a
    // large one takes tens of milliseconds to decode. The map's nodes do not move.
    const scene::LinearImage none;
    std::map<int, scene::LinearImage> decoded;
    std::vector<Part> parts;
    std::vector<std::uint32_t> levels;  // wanted, per emissive triangle in order
    for (const scene::Primitive& primitive : mesh.primitives) {
        if (primitive.material < 0) {
            continue;
        }
        const scene::Material& material =
            scene.materials.at(static_cast<std::size_t>(primitive.material));
        if (!material.is_emissive()) {
            continue;
        }
        Part part{&primitive, &material, &none};
        if (material.emissive_image >= 0 &&
            primitive.texcoords0.size() == primitive.positions.size()) {
            auto found = decoded.find(material.emissive_image);
            if (found == decoded.end()) {
                found =
                    decoded
                        .emplace(material.emissive_image, scene::emissive_texels(scene, material))
                        .first;
            }
            part.texels = &found->second;
        }
        const auto size = glm::dvec2(part.texels->width(), part.texels->height());
        for (std::size_t t = 0; t < primitive.triangle_count(); ++t) {
            double texels = 0.0;
            if (!part.texels->empty()) {
                const glm::dvec2 a = glm::dvec2(primitive.texcoords0[primitive.indices[3 * t]]);
                const glm::dvec2 b = glm::dvec2(primitive.texcoords0[primitive.indices[3 * t + 1]]);
                const glm::dvec2 c = glm::dvec2(primitive.texcoords0[primitive.indices[3 * t + 2]]);
                const glm::dvec2 e1 = (b - a) * size;
                const glm::dvec2 e2 = (c - a) * size;
                texels = 0.5 * std::abs(e1.x * e2.y - e1.y * e2.x);
                if (!std::isfinite(texels)) {
                    texels = 0.0;
                }
            }
            levels.push_back(static_cast<std::uint32_t>(wanted_level(texels)));
        }
        parts.push_back(std::move(part));
    }
    // Over kMaxPieces the finest triangles are cut less: the largest cap on the level that
    // keeps the sum of level^2 within it (one piece per triangle at least, whatever it costs).
    const auto total_at = [&levels](std::uint32_t cap) {
        std::size_t total = 0;
        for (const std::uint32_t level : levels) {
            const std::size_t n = std::min(level, cap);
            total += n * n;
        }
        return total;
    };
    std::uint32_t cap = kMaxLevel;
    while (cap > 1 && total_at(cap) > kMaxPieces) {
        cap = std::max<std::uint32_t>(1, cap * 3 / 4);
    }
    // Each piece's mean gets its share of the work budget (scene/texture_mean.hpp).
    const std::int64_t budget = scene::texels_per_triangle(total_at(cap));
    EmissionPieces pieces;
    std::size_t next = 0;
    std::vector<glm::vec3> radiance;
    for (const Part& part : parts) {
        const scene::Primitive& primitive = *part.primitive;
        const glm::vec3 factor = part.material->emitted_radiance();
        for (std::size_t t = 0; t < primitive.triangle_count(); ++t) {
            const std::uint32_t level = std::min(levels[next++], cap);
            if (part.texels->empty()) {
                pieces.add(1, {factor});
                continue;
            }
            const glm::dvec2 a = glm::dvec2(primitive.texcoords0[primitive.indices[3 * t]]);
            const glm::dvec2 b = glm::dvec2(primitive.texcoords0[primitive.indices[3 * t + 1]]);
            const glm::dvec2 c = glm::dvec2(primitive.texcoords0[primitive.indices[3 * t + 2]]);
            radiance.assign(static_cast<std::size_t>(level) * level, glm::vec3(0.0f));
            for (std::uint32_t k = 0; k < radiance.size(); ++k) {
                const auto sq = corners(level, k);
                const auto uv = [&](const glm::dvec2& p) {
                    return a + p.x * (b - a) + p.y * (c - a);
                };
                radiance[k] = factor * scene::mean_over_uv_triangle(*part.texels, uv(sq[0]),
                                                                    uv(sq[1]), uv(sq[2]), budget);
            }
            pieces.add(level, radiance);
        }
    }
    return pieces;
}

}  // namespace luxel::lighting
