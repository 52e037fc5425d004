#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/lighting/core/gather.hpp"
#include "luxel/lighting/core/map_surface.hpp"

namespace luxel {
class JobSystem;
}

namespace luxel::lighting {

/// Where a texel's centre lies against objects resting on its surface (docs/METHOD.md §6.12).
enum class TexelCover : std::uint8_t {
    Open = 0,      ///< light reaches it: gathered at its centre
    Enclosed = 1,  ///< under an object, a texel or more from the open surface
    /// Under an object's edge: its centre is enclosed, but the open surface lies within a
    /// texel, and a bilinear lookup beside the object reads it. It is gathered at the nearest
    /// open point towards its open neighbours, the light a player sees along the object's base.
    Edge = 2,
};

/// The texels the AIM found enclosed, and for those under an object's edge the point they are
/// gathered at. Gathered at its centre, an edge texel held the object's unlit inside, and the
/// renderer's bilinear lookup beside the object blended it in: a black notch along the base of
/// cornell's cube wherever its edge crossed a floor texel's centre. Filling it with its open
/// neighbours' light instead (a dilation) made the strip along the base 10-13% too bright
/// against luxel-ref, since those neighbours lie further from the object and see more of the
/// room; the gather at the open point by the edge sees what is there.
class ContactTexels {
  public:
    /// Whether a point of a surface (world space, with its unit normal) is enclosed: the AIM's
    /// own test (AimRebuilder::enclosed).
    using EnclosedTest = std::function<bool(const glm::vec3& position, const glm::vec3& normal)>;

    /// Records a rebuild's verdicts: texel `indices[k]` of surface `s` (of `texel_count`) is
    /// enclosed where `enclosed[k]` is non-zero. A texel recorded enclosed is Enclosed until
    /// find_edges() looks at it.
    void record(std::uint32_t s, std::size_t texel_count, std::span<const std::uint32_t> indices,
                std::span<const std::uint8_t> enclosed);
    /// Once a rebuild of surface `s` has placed every texel of `indices` (world-space copies
    /// in `world`, same order): each enclosed one with an open neighbour on the page (of the 8
    /// around it) becomes Edge, with the nearest point towards those neighbours (a quarter,
    /// half, three quarters of the way, or the neighbour's own centre) that `is_enclosed` finds
    /// open. Up to 8 x 3 tests of 9 rays per edge texel, none for open ones; with `jobs`, the
    /// texels are searched in parallel.
    void find_edges(std::uint32_t s, const MapSurface& mapped,
                    std::span<const std::uint32_t> indices, std::span<const GatherTexel> world,
                    const EnclosedTest& is_enclosed, JobSystem* jobs = nullptr);

    /// Per texel of surface `s`, its cover; empty before its first rebuild.
    [[nodiscard]] std::span<const TexelCover> cover(std::uint32_t s) const;
    /// Per texel of surface `s`, where an Edge texel is gathered, in the mesh's own frame
    /// (meaningful for Edge texels only); empty until the surface has had one.
    [[nodiscard]] std::span<const glm::vec3> gather_points(std::uint32_t s) const;
    /// Edge texels found since construction, counted at each rebuild that found them
    /// (MapCounters::edge_texels).
    [[nodiscard]] std::uint64_t edges_found() const { return edges_found_; }

  private:
    struct Surface {
        std::vector<TexelCover> cover;
        std::vector<glm::vec3> points;
    };
    Surface& surface(std::uint32_t s, std::size_t texel_count);

    std::vector<Surface> surfaces_;
    std::uint64_t edges_found_ = 0;
};

}  // namespace luxel::lighting
