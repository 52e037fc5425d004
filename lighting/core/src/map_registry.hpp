#pragma once

#include <cstdint>
#include <map>
#include <span>
#include <utility>
#include <vector>

#include "luxel/ecs/observer.hpp"
#include "luxel/ecs/registry.hpp"
#include "luxel/ecs/transform.hpp"
#include "luxel/lighting/components.hpp"
#include "luxel/lighting/core/gather.hpp"
#include "luxel/lighting/core/iim_page.hpp"
#include "luxel/lighting/core/light_map_seams.hpp"
#include "luxel/lighting/core/map_surface.hpp"
#include "luxel/lighting/core/photon_world.hpp"
#include "luxel/lighting/core/radiance_atlas.hpp"

namespace luxel::lighting {

/// The maps' first stage (docs/METHOD.md §5.1): the surfaces the photon world stores photons on,
/// each with its texels, footprint, material and transform; the pages they live on (AIM and IIM
/// alike) and which surface owns each page texel; and the emission table the gathers read. It
/// follows the ECS through observers (moves, AreaLight changes) and owns nothing of the AIM
/// rebuild or the gather passes, which write the pages it holds.
class MapRegistry {
  public:
    MapRegistry(ecs::Registry& registry, const PhotonWorld& world);

    /// Takes in surfaces the photon world added, transforms of entities that moved and area
    /// lights that changed.
    void sync();

    [[nodiscard]] std::span<const MapSurface> surfaces() const { return surfaces_; }
    [[nodiscard]] const MapSurface& surface(std::uint32_t s) const { return surfaces_.at(s); }
    /// Whether surface `s` has texels and its entity still exists.
    [[nodiscard]] bool live(std::uint32_t s) const;
    /// The page surface `s` lives on; -1 when it has no light map.
    [[nodiscard]] std::int32_t page_of(std::uint32_t s) const { return aim_.surface_page.at(s); }
    /// The surface that owns texel (x, y) of page `page` (-1: padding or unused).
    [[nodiscard]] std::int32_t owner(std::int32_t page, int x, int y) const;

    [[nodiscard]] const RadianceAtlas& aim() const { return aim_; }
    /// The AIM rebuild writes the pages, never the surface table.
    [[nodiscard]] RadiancePage& aim_page(std::int32_t page) {
        return aim_.pages.at(static_cast<std::size_t>(page));
    }
    [[nodiscard]] std::span<const IimPage> iim_pages() const { return iim_pages_; }
    /// The gather passes write the pages (and tests that play the gatherer).
    [[nodiscard]] std::span<IimPage> iim_pages() { return iim_pages_; }

    /// Bumped whenever a surface's emission changes (an area light switched, rescaled, added).
    [[nodiscard]] std::uint64_t emission_version() const { return emission_version_; }
    /// The world-space texel centres of a surface (what its AIM rebuild and gathers start from).
    [[nodiscard]] std::vector<GatherTexel> world_texels(std::uint32_t surface) const;
    /// The world-space centres of some of a surface's texels (by index), in that order: a
    /// gather unit of 20 texels transforms its 20, not the surface's thousands.
    [[nodiscard]] std::vector<GatherTexel> world_texels(
        std::uint32_t surface, std::span<const std::uint32_t> indices) const;

    /// Where the geometry changed near a surface in the last sync(): the photon world's change
    /// box grown by its own half-diagonal (an object changes the indirect light within about its
    /// own size of it: the floor under a crate, the wall beside it), and the surfaces whose
    /// texels' box meets it. Empty when nothing moved, appeared or went away.
    struct NearbyChange {
        std::uint32_t surface = 0;
        GeometryChange region;
        /// The change's own box (where the object was, or is), before growing.
        GeometryChange box;
        /// The surface's texels inside `region` (indices into its texels), found once for the
        /// local gather passes and the local AIM rebuilds that both mark them.
        std::vector<std::uint32_t> texels;
    };
    [[nodiscard]] const std::vector<NearbyChange>& nearby_changes() const {
        return nearby_changes_;
    }
    /// Per object with light-map seams (find_seams over its surfaces, found when they were
    /// added), the samples along them; objects are appended, never changed.
    [[nodiscard]] std::span<const std::vector<SeamSample>> seams() const { return seams_; }
    /// Whether the surface's own transform changed in the last sync() (it belongs to an object
    /// that moved).
    [[nodiscard]] bool moved_in_last_sync(std::uint32_t surface) const {
        return surface < moved_.size() && moved_[surface] != 0;
    }

  private:
    void add_surface(std::uint32_t surface);
    /// Finds the seams among the surfaces of each entity in `added` (surface indices).
    void find_object_seams(std::span<const std::uint32_t> added);
    void refresh_transform(std::uint32_t surface);
    /// Sets aim_.surface_emission[surface] from its material and its entity's AreaLight;
    /// returns whether it changed.
    bool refresh_emission(std::uint32_t surface);
    /// Sets aim_.skies from the enabled SkyLights; returns whether they changed.
    bool refresh_skies();
    std::int32_t page_index(const scene::Scene* source, int page, int page_size);
    /// The indices of `surface`'s texels inside `region` (world space).
    [[nodiscard]] std::vector<std::uint32_t> texels_inside(std::uint32_t surface,
                                                           const GeometryChange& region) const;
    /// Collects nearby_changes_ from the photon world's geometry changes.
    void find_nearby_changes();

    ecs::Registry& registry_;
    const PhotonWorld& world_;
    RadianceAtlas aim_;
    std::vector<IimPage> iim_pages_;
    /// Per page texel, the surface that owns it (-1: padding or unused).
    std::vector<std::vector<std::int32_t>> owners_;
    std::vector<MapSurface> surfaces_;
    /// Per surface, the box of its texel centres in object space, and where it lies in the
    /// world (refreshed with the transform).
    std::vector<AxisBox> local_boxes_;
    std::vector<AxisBox> surface_boxes_;
    /// The surfaces with texels, ascending: the only ones a change can be near (live()), so
    /// a level of many meshes without light maps costs find_nearby_changes nothing per pair.
    std::vector<std::uint32_t> mapped_surfaces_;
    std::vector<NearbyChange> nearby_changes_;
    std::vector<std::vector<SeamSample>> seams_;
    std::vector<std::uint8_t> moved_;  ///< by surface, in the last sync()
    std::map<std::pair<const scene::Scene*, int>, std::int32_t> pages_;
    std::map<ecs::Entity, std::vector<std::uint32_t>> surfaces_of_;
    ecs::Observer<ecs::WorldTransform> moves_;
    ecs::Observer<AreaLight> area_changes_;
    ecs::Observer<SkyLight> sky_changes_;
    std::uint64_t emission_version_ = 0;
};

}  // namespace luxel::lighting
