#pragma once

#include <cstddef>
#include <cstdint>

/// luxel-prep: the offline asset-preparation step. It splits every mesh into surfaces (the unit
/// that owns a photon map, an AIM and an IIM), gives each surface a light-map parameterization
/// at a uniform texel size, packs the charts into light-map pages and writes the result back as
/// glTF with TEXCOORD_1 and the surface table of scene/lightmap_layout.hpp.
namespace luxel::prep {

/// Accessors every written surface primitive has at least: POSITION, NORMAL, TEXCOORD_1 and
/// its indices (TEXCOORD_0 where the source has one), each in a bufferView of its own.
inline constexpr std::uint64_t kAccessorsPerSurface = 4;

/// The largest --texel-budget: far above what any loader allows (2^40 texels).
inline constexpr std::uint64_t kMaxTexelBudget = std::uint64_t{1} << 40;

struct PrepOptions {
    /// World size of one texel edge, in metres.
    double texel_size = 0.05;
    /// A node whose width (the middle extent of its world box) holds fewer texels than this
    /// gets finer texels, down to an eighth of texel_size (prep/texel_density.hpp); 0: off.
    int min_texels_across = 4;
    /// Texels the whole level may have (area over texel size squared, before padding): above
    /// it every node's texels grow by one factor. 0: no budget.
    std::uint64_t texel_budget = 0;
    /// Surfaces no viewpoint can see (the outside of a closed level, faces pressed against
    /// other geometry: prep/hidden_faces.hpp) get texels this many times larger; 1: off.
    double hidden_texel_scale = 8.0;
    /// Faces of one material whose normals differ by less than this share a surface
    /// (docs/METHOD.md §3.1: the shared edge is "connected").
    double crease_degrees = 45.0;
    /// Texels of gutter around every chart, on every side, owned by that chart alone: bilinear
    /// filtering at a chart's edge then reads only the chart's own (dilated) texels.
    int padding = 1;
    /// Texels per page edge; 0 picks the size automatically (see auto_page_limit).
    int page_size = 0;
    /// Largest page the automatic choice considers. Scenes that do not fit one such page get
    /// several pages of (about) this size.
    int auto_page_limit = 2048;
    /// A surface is split along chart seams (or a chart cut in pieces) when its world area
    /// exceeds this many texels of texel_size: one surface is one unit of lighting work (an AIM
    /// rebuild, a photon map), and the scheduler needs those units small enough to fit a frame.
    double surface_texel_budget = 1024.0;
    /// Bound on every triangle's area stretch: world area per texel within [1/s, s] times
    /// texel_size^2.
    double max_stretch = 1.5;
    /// Light-map specular materials too (mirrors and glass store no photons, so by default
    /// their primitives are passed through without a light map).
    bool lightmap_specular = false;
    /// Worker threads (0: every hardware thread). The output does not depend on it.
    int threads = 0;
    /// Upper bound on the texels a scene may ask for, checked on the surfaces' area, on the
    /// padded charts and on the packed pages: the loaders' lightmap-texels limit (luxel-prep
    /// sets it from `--limit lightmap-texels`), so luxel-prep never writes a level they refuse;
    /// beyond it luxel-prep stops with an error naming --texel-size.
    std::size_t max_total_texels = std::size_t{1} << 23;  // scene::LoadOptions default
    /// Triangles luxel-prep copies, every mesh node's triangles once per node (`--limit
    /// prep-triangles`), checked before any copy is made.
    std::uint64_t max_triangles = std::uint64_t{1} << 22;
    /// Accessors the written level may hold: the loaders' `elements` limit. Every surface is a
    /// primitive of at least kAccessorsPerSurface, checked before the charts are packed.
    std::uint64_t max_accessors = std::uint64_t{1} << 20;
};

/// Throws luxel::Error naming the command-line flag of the first invalid option.
void validate(const PrepOptions& options);

}  // namespace luxel::prep
