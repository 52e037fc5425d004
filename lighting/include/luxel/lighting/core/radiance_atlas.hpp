#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/scene/lightmap_layout.hpp"

/// Light-map pages of RGB float values: the AIM (radiance leaving each texel) that both gather
/// backends read, and the IIM pages the renderer samples. Page texel (x, y) covers
/// [x, x+1] x [y, y+1] in page-texel units; light-map UV u maps to u * size.
namespace luxel::lighting {

/// One page: size x size texels, row by row (y = 0 first), linear RGB.
struct RadiancePage {
    int size = 0;
    std::vector<glm::vec3> texels;
    /// Bumped whenever texels change, so a GPU copy knows when to upload.
    std::uint64_t version = 0;
    /// Texels written since the last take_dirty(): the rectangle to upload (empty: width 0).
    scene::TexelRect dirty;

    explicit RadiancePage(int page_size = 0);

    [[nodiscard]] glm::vec3& at(int x, int y) {
        return texels[static_cast<std::size_t>(y) * static_cast<std::size_t>(size) +
                      static_cast<std::size_t>(x)];
    }
    [[nodiscard]] const glm::vec3& at(int x, int y) const {
        return texels[static_cast<std::size_t>(y) * static_cast<std::size_t>(size) +
                      static_cast<std::size_t>(x)];
    }
    /// Grows the dirty rectangle over `rect` and bumps the version.
    void mark_dirty(const scene::TexelRect& rect);
    /// Returns and clears the dirty rectangle.
    scene::TexelRect take_dirty();
    /// Bilinear lookup at light-map UV `uv` (texel centres at (x + 0.5) / size), clamped to
    /// the page. Light-map charts carry padding texels filled by dilation, so a lookup near a
    /// chart border does not blend in unrelated charts.
    [[nodiscard]] glm::vec3 sample(const glm::vec2& uv) const;
};

/// The AIM of every light-mapped surface: pages plus which page each surface lives on.
/// Surfaces are numbered as the PhotonWorld numbers them (RayHit::surface).
struct RadianceAtlas {
    std::vector<RadiancePage> pages;
    std::vector<std::int32_t> surface_page;  ///< per surface; -1: no light map (reads as 0)

    /// Per surface: the radiance W/(m^2 sr) its front emits (an area light's emissive
    /// material times AreaLight::scale, 0 when switched off or not emissive); missing entries
    /// emit nothing. The pages hold what a surface reflects; the gathers see both, because the
    /// radiance leaving a surface is what it emits plus what it reflects. That is how an area
    /// light's direct light reaches the IIM (see IlluminationMaps).
    std::vector<glm::vec3> surface_emission;
    /// Radiance leaving the front of `surface` at light-map UV `uv`: the AIM (zero for
    /// surfaces without a page) plus the surface's emission.
    [[nodiscard]] glm::vec3 sample(std::int32_t surface, const glm::vec2& uv) const;
};

}  // namespace luxel::lighting
