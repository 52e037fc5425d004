#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "contact_texels.hpp"
#include "luxel/lighting/core/illumination_settings.hpp"
#include "luxel/lighting/core/map_surface.hpp"
#include "luxel/lighting/core/photon_density.hpp"
#include "luxel/lighting/core/photon_world.hpp"
#include "luxel/lighting/core/surface_deltas.hpp"
#include "luxel/runtime/jobs.hpp"
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

    /// Marks, on every built AIM, the texels next to where geometry changed in the registry's
    /// last sync (MapRegistry::nearby_changes) for a local rebuild: what the AIM decided from
    /// the old geometry (a texel found enclosed under an object, a density estimate beside it)
    /// is looked at again, not kept until the photons' change passes aim_threshold, which an
    /// object small beside its floor may never make it do.
    void sync();
    /// Surfaces needing a rebuild, highest priority first (see IlluminationMaps::aim_requests).
    [[nodiscard]] std::vector<MapRequest> requests() const;
    /// The first of requests(), by one scan.
    [[nodiscard]] std::optional<std::uint32_t> next_surface() const;
    /// See IlluminationMaps::rebuild_aim.
    std::size_t rebuild(std::uint32_t surface, std::size_t max_texels, JobSystem* jobs = nullptr);

    /// Whether every surface holding photons has had its first AIM (gather passes wait).
    [[nodiscard]] bool ready() const;
    /// Whether no AIM needs rebuilding.
    [[nodiscard]] bool current() const;
    /// Full rebuilds completed since construction (a gather pass compares it at its start and
    /// end to know whether an AIM changed under it; a local rebuild changes an AIM only next to
    /// a change, whose texels the gather passes gather again after it anyway).
    [[nodiscard]] std::uint64_t rebuilds() const { return rebuilds_; }
    /// The syncs that brought geometry changes next to a built AIM, counted from 1.
    [[nodiscard]] std::uint64_t change_serial() const { return change_serial_; }
    /// Whether the last sync() marked texels (change_serial() is then that sync's).
    [[nodiscard]] bool marked_in_last_sync() const { return marked_in_last_sync_; }
    /// Every AIM texel marked by the changes up to this serial has been rebuilt since: a local
    /// gather pass for those changes run after it reads AIMs of the new geometry.
    [[nodiscard]] std::uint64_t local_current_through() const;
    [[nodiscard]] std::uint64_t texels() const { return texels_; }
    [[nodiscard]] std::uint64_t enclosed_texels() const { return enclosed_texels_; }
    /// Which texels were found enclosed, and where those under an object's edge are gathered
    /// (the gather passes read it).
    [[nodiscard]] const ContactTexels& contacts() const { return contacts_; }

  private:
    struct RebuildState;

    [[nodiscard]] bool built(std::uint32_t s) const { return s < built_.size() && built_[s]; }
    /// Texels of one surface waiting for a local rebuild.
    struct LocalMarks {
        std::vector<std::uint8_t> marked;  ///< by texel
        std::vector<std::uint32_t> texels;
        std::uint64_t first_serial = 0;  ///< the change that marked the oldest of them
        std::uint64_t first_sync = 0;    ///< the sync() that did
    };
    [[nodiscard]] bool has_marks(std::uint32_t s) const {
        return s < marks_.size() && !marks_[s].texels.empty();
    }
    /// Whether `s`'s marks are due for a local rebuild: the retraces the change queued are
    /// done, or waited for long enough.
    [[nodiscard]] bool marks_due(std::uint32_t s) const;
    /// Marks some of `s`'s texels (MapRegistry::NearbyChange::texels).
    void mark(std::uint32_t s, std::span<const std::uint32_t> texels);
    /// Whether surface `s` needs a full rebuild: never built, one in progress, or delta_f over
    /// the threshold.
    [[nodiscard]] bool needs_full_rebuild(std::uint32_t s) const;
    /// needs_full_rebuild, or a local rebuild in progress or waiting (texels marked).
    [[nodiscard]] bool needs_rebuild(std::uint32_t s) const;
    /// Its place in requests(), given needs_rebuild(s).
    [[nodiscard]] double priority(std::uint32_t s) const;
    /// Starts `surface`'s rebuild: its kd-tree, and the texels to place (all of them, or the
    /// marked ones for a local rebuild).
    void start(std::uint32_t surface);
    /// Whether the texel's hemisphere is closed: all but two enclosure rays blocked within
    /// `ray_length` metres, or the texel inside a closed object (met from behind).
    [[nodiscard]] bool enclosed(const GatherTexel& texel, float ray_length) const;
    /// Fills the padding texels around `surface`'s texels on `page` with the mean of their
    /// owned neighbours, so bilinear lookups at a chart's border do not fetch black.
    void dilate(std::uint32_t surface, RadiancePage& page) const;
    /// A rebuild's last slice: its enclosed texels under an object's edge (ContactTexels).
    void find_edges(const RebuildState& rebuild, float ray_length, JobSystem* jobs);
    /// A full rebuild's last slice (aim_keeps_power): the surface's scale from its photons'
    /// power over the integral of its estimates, applied to the texels placed under the old one.
    void keep_power(const RebuildState& rebuild, RadiancePage& page);
    /// The scale a surface's estimates are placed with (1 until a full rebuild sets it).
    [[nodiscard]] double power_scale(std::uint32_t s) const {
        return s < power_scales_.size() ? power_scales_[s] : 1.0;
    }

    MapRegistry& registry_;
    const PhotonWorld& world_;
    SurfaceDeltas& deltas_;
    const IlluminationSettings& settings_;
    std::vector<bool> built_;  ///< by surface; surfaces past the end have no AIM yet
    std::unique_ptr<RebuildState> rebuild_;
    /// A full rebuild a local one interrupted (never more than one: a local rebuild is not
    /// paused, and a full one pauses only when none is paused already).
    std::unique_ptr<RebuildState> paused_;
    std::vector<LocalMarks> marks_;  ///< by surface
    std::vector<double> power_scales_;  ///< by surface, see power_scale()
    std::uint64_t change_serial_ = 0;
    bool marked_in_last_sync_ = false;
    std::uint64_t syncs_ = 0;
    /// A local rebuild completed since the last full one started: full rebuilds go first.
    bool full_turn_ = false;
    /// Sorted: the groups pending when texels were marked and not retraced since.
    std::vector<std::uint32_t> awaited_groups_;
    std::uint64_t rebuilds_ = 0;
    std::uint64_t texels_ = 0;
    std::uint64_t enclosed_texels_ = 0;
    ContactTexels contacts_;
};

}  // namespace luxel::lighting
