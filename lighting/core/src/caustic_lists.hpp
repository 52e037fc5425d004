#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <vector>

#include "light_groups.hpp"
#include "luxel/lighting/core/caustic_photons.hpp"
#include "luxel/lighting/core/photon_world.hpp"
#include "photon_geometry.hpp"

namespace luxel::lighting {

/// PhotonWorld's caustics (docs/METHOD.md §7): the caustic generators with the spheres their
/// photons are aimed at, and one CausticPhotonList per (generator, enabled light) pair, ordered
/// by (generator, light). A list is re-aimed (and so retraced) when it is new, when geometry
/// changed where its photons' paths go (CausticPhotonList::paths_meet), when its light or
/// generator was touched or moved, or when a sibling generator its rays may cross came, went or
/// moved.
class CausticLists {
  public:
    explicit CausticLists(const CausticSettings& settings) : settings_(settings) {}

    void add_generator(ecs::Entity entity);
    void remove_generator(ecs::Entity entity);
    [[nodiscard]] std::size_t generator_count() const { return generators_.size(); }

    /// Brings the pairs up to date with the generators' geometry and the enabled lights.
    /// `lights_touched` and `generators_touched` are sorted.
    void sync(const PhotonGeometry& geometry, const LightGroups& lights,
              std::span<const ecs::Entity> lights_touched,
              std::span<const ecs::Entity> generators_touched,
              std::span<const GeometryChange> changes);
    /// Retraces one slice of every list that needs it, all lists together in one parallel pass.
    CausticFrameStats update(std::uint64_t frame, const PhotonGeometry& geometry, JobSystem& jobs);

    [[nodiscard]] std::span<const CausticPair> pairs() const { return pairs_; }
    [[nodiscard]] CausticTotals totals() const;
    [[nodiscard]] bool pending() const;
    /// Whether some list is catching up after a change (CausticPhotonList::catching_up).
    [[nodiscard]] bool catching_up() const;
    /// Whether some list, current, may trace a further generation (progressive caustics).
    [[nodiscard]] bool refining() const;
    /// PhotonWorld::trace_caustic_unit.
    CausticFrameStats trace_unit(const PhotonGeometry& geometry, std::uint32_t max_photons,
                                 bool refine, JobSystem& jobs);
    /// PhotonWorld::caustic_photons_left.
    [[nodiscard]] std::uint64_t photons_left(bool refine) const;

  private:
    /// A caustic generator's bounding sphere, which its caustic photons are aimed at.
    struct GeneratorRecord {
        ObjectId object = kNoObject;  ///< the object local_sphere was computed for
        BoundingSphere local_sphere;  ///< around the object's vertices, in its mesh's frame
        BoundingSphere world_sphere;
        bool moved = false;  ///< world_sphere changed in the last sync
    };
    void update_spheres(const PhotonGeometry& geometry);
    /// Sets every list's generation limit from CausticSettings::refinement_photons, shared in
    /// proportion to the power each pair's light sends toward its generator.
    void share_refinement();
    /// Sizes each pair's list by CausticSettings::max_photons: a list whose share moved by more
    /// than a quarter (or back to photons_per_pair) is replaced by one of its new size, with its
    /// seed and emitter, to be traced afresh.
    void apportion_photons();
    /// Gives each pair's emitter the spheres of its light's other emitting pairs and sets it
    /// on the list where it is new (`aimed`: the re-aimed emitters, none where a pair kept its
    /// own) or where its siblings changed.
    void set_siblings(const std::vector<std::optional<CausticEmitter>>& aimed,
                      const AxisBox& path_region);
    /// Rebuilds the pair vector for the pairs in `wanted` (merging, so surviving lists keep
    /// their photons); returns which pairs are new.
    std::vector<std::uint8_t> merge_pairs(
        const std::vector<std::pair<ecs::Entity, ecs::Entity>>& wanted);

    CausticSettings settings_;
    std::map<ecs::Entity, GeneratorRecord> generators_;
    std::vector<CausticPair> pairs_;  ///< sorted by (generator, light)
    std::uint32_t next_seed_ = 1;
    std::size_t unit_cursor_ = 0;  ///< the list trace_unit tries first
};

}  // namespace luxel::lighting
