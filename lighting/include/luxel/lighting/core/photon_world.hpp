#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <vector>

#include "luxel/ecs/observer.hpp"
#include "luxel/ecs/registry.hpp"
#include "luxel/ecs/transform.hpp"
#include "luxel/lighting/components.hpp"
#include "luxel/lighting/core/axis_box.hpp"
#include "luxel/lighting/core/caustic_photons.hpp"
#include "luxel/lighting/core/photon_map.hpp"
#include "luxel/lighting/core/ray_scene.hpp"
#include "luxel/lighting/core/selective_emitter.hpp"
#include "luxel/lighting/sky_portal.hpp"
#include "luxel/runtime/jobs.hpp"

namespace luxel::lighting {

class PhotonGeometry;
class LightGroups;
class CausticLists;

struct PhotonWorldSettings {
    SelectiveSettings selective;
    /// Until luxel-prep has run, a static mesh without a light-map layout gets one surface per
    /// primitive, so photons are stored (without light-map UVs) and tests and tools work on
    /// unprepared levels. Off: such meshes only reflect photons.
    bool implicit_surfaces = true;
    /// Caustic photons: photons_per_pair for every (caustic generator, enabled light) pair,
    /// retraced in `slices` slices. photons_per_pair = 0 turns caustics off.
    CausticSettings caustics;
};

/// One light-mapped surface as the photon engine knows it.
struct SurfaceInfo {
    ecs::Entity entity;
    int primitive = -1;
    int layout_id = -1;  ///< the layout's surface id; -1 for implicit surfaces
};

/// The caustic photons of one (generator, light) pair.
struct CausticPair {
    ecs::Entity generator;
    ecs::Entity light;
    CausticPhotonList photons;
};

/// Counters of one PhotonWorld::update_caustics.
struct CausticFrameStats {
    std::uint32_t slices_retraced = 0;  ///< one per list that needed it
    std::uint32_t slices_refined = 0;   ///< one per current list still refining
    CausticTraceCounters trace;
};

/// Where the geometry changed in one sync: the world-space box of an object where it was or
/// where it is now (a move gives both, an object added its new box, one removed its old box).
/// The maps re-examine what they decided from the geometry there (docs/METHOD.md §6.8).
using GeometryChange = AxisBox;

/// What the last PhotonWorld::sync() took in.
struct PhotonSyncStats {
    std::uint32_t objects_moved = 0;     ///< mesh entities whose transform changed
    std::uint32_t meshes_changed = 0;    ///< mesh entities added, removed or replaced
    std::uint32_t lights_refreshed = 0;  ///< lights added, changed, moved or removed
    /// Groups whose stored paths cross where geometry changed, newly queued for a retrace
    /// (exact invalidation; SelectiveSettings::exact_invalidation).
    std::uint32_t groups_invalidated = 0;
};

/// What the caustic lists hold now (for the scheduler and the HUD).
struct CausticTotals {
    std::size_t lists = 0;
    std::size_t stored = 0;  ///< caustic photons stored
    std::size_t bytes = 0;   ///< photons and bookkeeping
};

/// The photon side of the lighting system, fed by the ECS: it mirrors MeshInstance entities
/// into a RayScene (Dynamic ones as instances), lights into selective emitters, and keeps the
/// PhotonMap current. It learns what changed only from observers (WorldTransform, MeshInstance,
/// CausticGenerator and the light components), never by scanning the registry.
///
/// Caustics: every entity with a CausticGenerator and a MeshInstance gets one CausticPhotonList
/// per enabled light (no generator: no list, nothing traced). The generator's specular
/// primitives take their optics from the component (transmission 0: a mirror with Schlick F0 =
/// tint; otherwise glass of index `ior` whose refracted photons are scaled by
/// tint * transmission), for global and caustic photons alike. Any geometry added, removed or
/// moved invalidates every list (receivers and occluders anywhere can change a caustic); a
/// light change invalidates its lists, a generator change its own.
class PhotonWorld {
  public:
    PhotonWorld(ecs::Registry& registry, PhotonWorldSettings settings = {});
    ~PhotonWorld();
    PhotonWorld(const PhotonWorld&) = delete;
    PhotonWorld& operator=(const PhotonWorld&) = delete;

    /// Applies the ECS changes since the last call: geometry added, removed or moved, lights
    /// added, removed, changed, switched or moved (each of those invalidates all its groups).
    /// Run after the TransformSystem.
    void sync();

    /// Caustics: retraces one slice of every list that needs it (see CausticPhotonList for
    /// which slice), all lists together in one parallel pass.
    CausticFrameStats update_caustics(std::uint64_t frame, JobSystem& jobs);
    /// The caustic lists, ordered by (generator, light). The span and references into it stay
    /// valid until a sync() that adds or removes a pair (a generator or light coming, going or
    /// being switched).
    [[nodiscard]] std::span<const CausticPair> caustics() const;
    [[nodiscard]] CausticTotals caustic_totals() const;
    /// Whether some caustic list has slices waiting for a retrace.
    [[nodiscard]] bool caustics_pending() const;
    /// Whether some caustic list is catching up after a change to a settled scene
    /// (CausticPhotonList::catching_up): the lighting system gives caustics a larger share then.
    [[nodiscard]] bool caustics_catching_up() const;
    /// Whether some current caustic list may trace a further generation (progressive
    /// caustics, CausticSettings::refinement_photons): work for a still frame's spare budget.
    [[nodiscard]] bool caustics_refining() const;
    /// One unit of caustic work for the scheduler: `max_photons` photons of the lists' slices
    /// (CausticPhotonList::trace_part), the lists taken in turn, those that need a retrace
    /// before (when `refine`) those still refining; a list keeps the turn until its slice is
    /// complete, so slices land as soon as they can, and a unit goes on to the next list's
    /// slice until its photons are spent.
    CausticFrameStats trace_caustic_unit(std::uint32_t max_photons, bool refine, JobSystem& jobs);
    /// The photons the lists' current slices have left (each list's slice in progress or next
    /// one; refinement slices only when `refine`, and then all a catching-up list needs to
    /// catch up): what the caustic units are sized by.
    [[nodiscard]] std::uint64_t caustic_photons_left(bool refine) const;
    [[nodiscard]] const PhotonSyncStats& last_sync() const { return last_sync_; }
    /// The boxes where geometry changed in the last sync() (empty when nothing moved).
    [[nodiscard]] const std::vector<GeometryChange>& geometry_changes() const;
    /// Counts for the FeaturePlan: lights (enabled or not), caustic generators, and mesh
    /// objects that may move.
    [[nodiscard]] std::size_t light_count() const;
    [[nodiscard]] std::size_t generator_count() const;
    [[nodiscard]] std::size_t dynamic_object_count() const;

    /// Groups waiting for a retrace (invalidated by probes or by light changes).
    [[nodiscard]] const std::vector<std::uint32_t>& pending_groups() const;
    /// Selective emission, in the two steps the LightingSystem schedules as separate units:
    /// the probes of `frame` (photon frame mod M of every group of every enabled light), which
    /// add the groups whose paths diverge to pending_groups() ...
    EmissionStats probe(std::uint64_t frame, JobSystem& jobs);
    /// ... and the retrace of up to `max_groups` pending groups (all when 0), oldest first.
    EmissionStats retrace_pending(JobSystem& jobs, std::size_t max_groups = 0);

    [[nodiscard]] const RayScene& ray_scene() const;
    /// The photon world is the map's writer; readers keep their own positions in its change
    /// counts (SurfaceDeltas). The mutable overload is for tests that play the tracer.
    [[nodiscard]] const PhotonMap& photon_map() const { return *map_; }
    /// The stored paths' segments, for exact invalidation (empty when it is off).
    [[nodiscard]] const PathSegmentIndex& paths() const;
    [[nodiscard]] PhotonMap& photon_map() { return *map_; }
    [[nodiscard]] const std::vector<SurfaceInfo>& surfaces() const;
    [[nodiscard]] const std::vector<TraceMaterial>& materials() const;
    /// The registry the world mirrors.
    [[nodiscard]] const ecs::Registry& registry() const { return registry_; }
    /// Every mesh entity in the ray scene and its object there: the object's vertices and
    /// triangles are the entity's MeshInstance primitives concatenated in order, so a caller
    /// can keep per-vertex data of its own (the reference's texture coordinates).
    [[nodiscard]] const std::map<ecs::Entity, ObjectId>& mesh_objects() const;
    /// The light entity whose groups include global group `group`, or null_entity.
    [[nodiscard]] ecs::Entity light_of_group(std::uint32_t group) const;
    /// The emitters of the enabled lights.
    [[nodiscard]] std::vector<const LightPhotons*> active_lights() const;

  private:
    // sync()'s steps, in order; each adds the entities whose lights it may have touched.
    void sync_meshes(std::vector<ecs::Entity>& light_touched,
                     std::vector<ecs::Entity>& meshes_added);
    void sync_generators(const std::vector<ecs::Entity>& meshes_added,
                         std::vector<ecs::Entity>& generators_touched);
    void sync_moves(std::vector<ecs::Entity>& light_touched);
    void touch_lights_if_portals_changed(std::vector<ecs::Entity>& light_touched);
    void sync_lights(std::vector<ecs::Entity>& light_touched);

    ecs::Registry& registry_;
    PhotonWorldSettings settings_;
    std::unique_ptr<PhotonMap> map_;
    /// Its three parts, each with its own state: the geometry mirrored into the ray scene, the
    /// lights with their photon groups, the caustic lists. PhotonWorld holds the observers and
    /// runs sync() across them.
    std::unique_ptr<PhotonGeometry> geometry_;
    std::unique_ptr<LightGroups> lights_;
    std::unique_ptr<CausticLists> caustics_;
    PhotonSyncStats last_sync_;

    ecs::Observer<scene::MeshInstance> mesh_changes_;
    ecs::Observer<ecs::WorldTransform> moves_;
    ecs::Observer<PointLight> point_changes_;
    ecs::Observer<SpotLight> spot_changes_;
    ecs::Observer<DirectionalLight> directional_changes_;
    ecs::Observer<AreaLight> area_changes_;
    ecs::Observer<SkyLight> sky_changes_;
    ecs::Observer<SkyPortal> portal_changes_;  // any change re-emits every sky's photons
    ecs::Observer<CausticGenerator> generator_changes_;
};

}  // namespace luxel::lighting
