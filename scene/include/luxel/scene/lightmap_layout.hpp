#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

/// The light-map layout luxel-prep writes into a mesh node's `extras.luxel.lightmap`, and the
/// runtime reads back into LightmappedSurface components:
///
///     "lightmap": {
///       "texel_size": 0.05,             metres per texel edge
///       "page_size": 1024,              texels per page edge
///       "surfaces": [ {
///         "id": 7,                      unique within the scene
///         "primitive": 0,               the mesh primitive holding exactly this surface
///         "page": 0,                    every chart of a surface lies on this page
///         "rect": [x, y, w, h],         texel bounds of all its charts (padding excluded);
///                                       rects of different surfaces may overlap
///         "charts": [[x, y, w, h], ...],  charts (with their padding) never overlap: texel
///                                       ownership comes from the charts, not the rect
///         "area": 1.25,                 world area in m^2
///         "texels": 512,                texels covered by its charts
///         "texel_size": 0.4             optional: its own metres per texel edge, where not
///                                       the layout's (a surface no viewpoint sees)
///       }, ... ] }
///
/// A surface is the unit that owns a photon map, an AIM and an IIM: faces of one material
/// joined across edges flatter than the crease angle. luxel-prep gives each surface its own
/// primitive and each mesh node its own mesh, so light maps are per instance.
namespace luxel::scene {

struct TexelRect {
    int x = 0;
    int y = 0;
    int width = 0;
    int height = 0;

    friend bool operator==(const TexelRect&, const TexelRect&) = default;
};

struct LightmapSurface {
    int id = -1;
    int primitive = -1;
    int page = 0;
    TexelRect rect;
    std::vector<TexelRect> charts;
    double area = 0.0;
    std::int64_t texels = 0;
    /// Metres per texel edge of this surface where it differs from the layout's (a surface no
    /// viewpoint sees, given coarser texels by luxel-prep); 0: the layout's texel_size.
    double texel_size = 0.0;

    friend bool operator==(const LightmapSurface&, const LightmapSurface&) = default;
};

/// The largest light-map page edge, in texels. Page UVs are stored as floats; beyond 8192 texels
/// their rounding reaches a texel's thousandth, the margin charts keep from their rectangle's
/// border. luxel-prep writes no larger page, and the loader accepts none.
inline constexpr int kMaxLightmapPageSize = 8192;

struct LightmapLayout {
    float texel_size = 0.05f;
    int page_size = 1024;
    std::vector<LightmapSurface> surfaces;

    friend bool operator==(const LightmapLayout&, const LightmapLayout&) = default;
};

/// Reads `luxel_extras["lightmap"]` when present (nullopt otherwise). Throws luxel::Error
/// naming the field when it is malformed: wrong types, non-positive sizes, rectangles outside
/// the page, negative area or texel counts.
[[nodiscard]] std::optional<LightmapLayout> read_lightmap_layout(
    const nlohmann::json& luxel_extras);

/// The JSON object to store under extras.luxel.lightmap.
[[nodiscard]] nlohmann::json to_json(const LightmapLayout& layout);

}  // namespace luxel::scene
