#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "luxel/lighting/core/illumination_settings.hpp"
#include "luxel/lighting/core/map_surface.hpp"
#include "luxel/lighting/core/photon_density.hpp"
#include "luxel/lighting/core/photon_world.hpp"
#include "luxel/lighting/core/surface_deltas.hpp"
#include "map_registry.hpp"

namespace luxel::lighting {

/// The maps' second stage, the AIM (docs/METHOD.md §5): which surfaces need a rebuild (never
/// built, or delta_f over the threshold), and the rebuild itself in slices from one kd-tree at a
/// time, with enclosure rays and dilation into the chart padding. It owns whether each surface's
/// AIM exists and the rebuild in progress; it writes the registry's AIM pages and consumes
/// delta_f in the maps' SurfaceDeltas.
class AimRebuilder {
  public:
    AimRebuilder(MapRegistry& registry, const PhotonWorld& world, SurfaceDeltas& deltas,
                 const IlluminationSettings& settings);
    ~AimRebuilder();
    AimRebuilder(const AimRebuilder&) = delete;
    AimRebuilder& operator=(const AimRebuilder&) = delete;

    /// Surfaces needing a rebuild, highest priority first (see IlluminationMaps::aim_requests).
    [[nodiscard]] std::vector<MapRequest> requests() const;
    /// The first of requests(), by one scan.
    [[nodiscard]] std::optional<std::uint32_t> next_surface() const;
    /// See IlluminationMaps::rebuild_aim.
    std::size_t rebuild(std::uint32_t surface, std::size_t max_texels);

    /// Whether every surface holding photons has had its first AIM (gather passes wait).
    [[nodiscard]] bool ready() const;
    /// Whether no AIM needs rebuilding.
    [[nodiscard]] bool current() const;
    /// Rebuilds completed since construction (a gather pass compares it at its start and end to
    /// know whether an AIM changed under it).
    [[nodiscard]] std::uint64_t rebuilds() const { return rebuilds_; }
    [[nodiscard]] std::uint64_t texels() const { return texels_; }
    [[nodiscard]] std::uint64_t enclosed_texels() const { return enclosed_texels_; }

  private:
    struct RebuildState;

    [[nodiscard]] bool built(std::uint32_t s) const { return s < built_.size() && built_[s]; }
    /// Whether surface `s` needs a rebuild: never built, in progress, or delta_f over the
    /// threshold.
    [[nodiscard]] bool needs_rebuild(std::uint32_t s) const;
    /// Its place in requests(), given needs_rebuild(s).
    [[nodiscard]] double priority(std::uint32_t s) const;
    /// Whether every enclosure ray from the texel is blocked within `ray_length` metres.
    [[nodiscard]] bool enclosed(const GatherTexel& texel, float ray_length) const;
    /// Fills the padding texels around `surface`'s texels on `page` with the mean of their
    /// owned neighbours, so bilinear lookups at a chart's border do not fetch black.
    void dilate(std::uint32_t surface, RadiancePage& page) const;

    MapRegistry& registry_;
    const PhotonWorld& world_;
    SurfaceDeltas& deltas_;
    const IlluminationSettings& settings_;
    std::vector<bool> built_;  ///< by surface; surfaces past the end have no AIM yet
    std::unique_ptr<RebuildState> rebuild_;
    std::uint64_t rebuilds_ = 0;
    std::uint64_t texels_ = 0;
    std::uint64_t enclosed_texels_ = 0;
};

}  // namespace luxel::lighting
