#pragma once

#include <cstdint>
#include <deque>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include <memory>

#include "luxel/lighting/core/sky_radiance.hpp"
#include "luxel/scene/lightmap_layout.hpp"

/// Light-map pages of RGB float values: the AIM (radiance leaving each texel) that both gather
/// backends read, and the IIM pages the renderer samples. Page texel (x, y) covers
/// [x, x+1] x [y, y+1] in page-texel units; light-map UV u maps to u * size.
namespace luxel::lighting {

/// One change of a page: the texels a write touched, and the version it made.
struct PageChange {
    std::uint64_t version = 0;
    scene::TexelRect rect;
};

/// What changed in a page since a reader's version: nothing, a rectangle (the union of the
/// changes), or everything, when the reader is older than the page's log reaches back.
struct PageChanges {
    bool everything = false;
    scene::TexelRect rect;

    [[nodiscard]] bool any() const { return everything || (rect.width > 0 && rect.height > 0); }
};

/// One page: size x size texels, row by row (y = 0 first), linear RGB.
///
/// A page does not know who reads it. Each change bumps `version` and is logged with its
/// rectangle; a reader (a GPU copy, a tool's frame view) keeps the version it last read and
/// asks changes_since() for what to read again, so any number of readers can follow a page
/// without the writer clearing anything on their behalf.
struct RadiancePage {
    /// Changes kept: a reader more than this many changes behind reads the whole page again.
    static constexpr std::size_t kLogLength = 64;

    int size = 0;
    std::vector<glm::vec3> texels;
    /// Bumped by every mark_changed, so a reader knows it has something to read.
    std::uint64_t version = 0;
    /// The last kLogLength changes, oldest first.
    std::deque<PageChange> log;

    explicit RadiancePage(int page_size = 0);

    [[nodiscard]] glm::vec3& at(int x, int y) {
        return texels[static_cast<std::size_t>(y) * static_cast<std::size_t>(size) +
                      static_cast<std::size_t>(x)];
    }
    [[nodiscard]] const glm::vec3& at(int x, int y) const {
        return texels[static_cast<std::size_t>(y) * static_cast<std::size_t>(size) +
                      static_cast<std::size_t>(x)];
    }
    /// Records that the texels of `rect` were written: bumps the version and logs the change
    /// (an empty rectangle changes nothing).
    void mark_changed(const scene::TexelRect& rect);
    /// What changed after `reader_version` (a version this page had, 0 for a reader that has
    /// read nothing yet).
    [[nodiscard]] PageChanges changes_since(std::uint64_t reader_version) const;
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

    /// The enabled skies and their scales: what a gather ray that leaves the level sees, so the
    /// IIM holds the sky's direct light as it holds an area light's.
    struct Sky {
        std::shared_ptr<const SkyRadiance> radiance;
        float scale = 1.0f;
    };
    std::vector<Sky> skies;
    /// The radiance arriving from direction `towards_sky` from every sky (0 without one).
    [[nodiscard]] glm::vec3 sky(const glm::vec3& towards_sky) const;
};

}  // namespace luxel::lighting
