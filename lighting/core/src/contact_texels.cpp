#include "contact_texels.hpp"

#include <algorithm>
#include <array>
#include <optional>
#include <unordered_map>

#include "luxel/runtime/jobs.hpp"

namespace luxel::lighting {

ContactTexels::Surface& ContactTexels::surface(std::uint32_t s, std::size_t texel_count) {
    if (surfaces_.size() <= s) {
        surfaces_.resize(static_cast<std::size_t>(s) + 1);
    }
    Surface& out = surfaces_[s];
    out.cover.resize(texel_count, TexelCover::Open);
    if (!out.points.empty()) {
        out.points.resize(texel_count, glm::vec3(0.0f));
    }
    return out;
}

void ContactTexels::record(std::uint32_t s, std::size_t texel_count,
                           std::span<const std::uint32_t> indices,
                           std::span<const std::uint8_t> enclosed) {
    Surface& out = surface(s, texel_count);
    const std::size_t count = std::min(indices.size(), enclosed.size());
    for (std::size_t k = 0; k < count; ++k) {
        if (indices[k] < texel_count) {
            out.cover[indices[k]] = enclosed[k] != 0 ? TexelCover::Enclosed : TexelCover::Open;
        }
    }
}

void ContactTexels::find_edges(std::uint32_t s, const MapSurface& mapped,
                               std::span<const std::uint32_t> indices,
                               std::span<const GatherTexel> world, const EnclosedTest& is_enclosed,
                               JobSystem* jobs) {
    const std::vector<SurfaceTexel>& texels = mapped.texels.texels;
    Surface& out = surface(s, texels.size());
    const std::size_t count = std::min(indices.size(), world.size());
    // The texels to look at, reset to Enclosed. Most surfaces have none: nothing more is made.
    std::vector<std::size_t> enclosed;
    for (std::size_t k = 0; k < count; ++k) {
        const std::uint32_t i = indices[k];
        if (i < texels.size() && out.cover[i] != TexelCover::Open) {
            out.cover[i] = TexelCover::Enclosed;
            enclosed.push_back(k);
        }
    }
    if (enclosed.empty()) {
        return;
    }
    // The surface's texels by page position: the neighbours on the page are the neighbours on
    // the surface within a chart (a texel across a chart seam is another chart's, and its
    // centre may be far away: only the 8 around on the page are looked at, and only those of
    // this surface). A map, not a grid over the surface's bounds: charts spread over a large
    // page would make that grid the page's size.
    const auto key = [](std::int64_t x, std::int64_t y) { return (y << 32) ^ (x & 0xFFFFFFFF); };
    std::unordered_map<std::int64_t, std::uint32_t> at;
    at.reserve(texels.size());
    for (std::size_t i = 0; i < texels.size(); ++i) {
        at.emplace(key(texels[i].x, texels[i].y), static_cast<std::uint32_t>(i));
    }
    const auto neighbour = [&](const SurfaceTexel& t, int dx, int dy) -> std::int32_t {
        const auto found =
            at.find(key(static_cast<std::int64_t>(t.x) + dx, static_cast<std::int64_t>(t.y) + dy));
        return found == at.end() ? -1 : static_cast<std::int32_t>(found->second);
    };
    struct Candidate {
        float distance;
        std::uint32_t towards;
        float fraction;
    };
    constexpr std::array<float, 4> kFractions = {0.25f, 0.5f, 0.75f, 1.0f};
    // Each one's search in parallel (it reads only which texels are Open, which the searches do
    // not change), then the results.
    std::vector<std::optional<glm::vec3>> found(enclosed.size());
    const auto search = [&](std::size_t e) {
        const std::size_t k = enclosed[e];
        const std::uint32_t i = indices[k];
        std::vector<Candidate> candidates;
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
                const std::int32_t n = neighbour(texels[i], dx, dy);
                if ((dx == 0 && dy == 0) || n < 0 ||
                    out.cover[static_cast<std::size_t>(n)] != TexelCover::Open) {
                    continue;
                }
                const float span =
                    glm::distance(texels[i].position, texels[static_cast<std::size_t>(n)].position);
                for (const float f : kFractions) {
                    candidates.push_back({f * span, static_cast<std::uint32_t>(n), f});
                }
            }
        }
        std::sort(candidates.begin(), candidates.end(),
                  [](const Candidate& a, const Candidate& b) { return a.distance < b.distance; });
        for (const Candidate& c : candidates) {
            const glm::vec3 local =
                glm::mix(texels[i].position, texels[c.towards].position, c.fraction);
            const glm::vec3 point = glm::vec3(mapped.to_world * glm::vec4(local, 1.0f));
            // The neighbour's own centre was found open by the rebuild: no second test.
            if (c.fraction >= 1.0f || !is_enclosed(point, world[k].normal)) {
                found[e] = local;
                return;
            }
        }
    };
    if (jobs != nullptr && enclosed.size() > 1) {
        jobs->parallel_for(0, enclosed.size(), search);
    } else {
        for (std::size_t e = 0; e < enclosed.size(); ++e) {
            search(e);
        }
    }
    for (std::size_t e = 0; e < enclosed.size(); ++e) {
        if (found[e]) {
            const std::uint32_t i = indices[enclosed[e]];
            out.cover[i] = TexelCover::Edge;
            out.points.resize(texels.size(), glm::vec3(0.0f));
            out.points[i] = *found[e];
            ++edges_found_;
        }
    }
}

std::span<const TexelCover> ContactTexels::cover(std::uint32_t s) const {
    return s < surfaces_.size() ? std::span<const TexelCover>(surfaces_[s].cover)
                                : std::span<const TexelCover>();
}

std::span<const glm::vec3> ContactTexels::gather_points(std::uint32_t s) const {
    return s < surfaces_.size() ? std::span<const glm::vec3>(surfaces_[s].points)
                                : std::span<const glm::vec3>();
}

}  // namespace luxel::lighting
