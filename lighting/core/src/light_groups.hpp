#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <vector>

#include "luxel/ecs/registry.hpp"
#include "luxel/lighting/components.hpp"
#include "luxel/lighting/core/axis_box.hpp"
#include "luxel/lighting/core/light_source.hpp"
#include "luxel/lighting/core/path_segment_index.hpp"
#include "luxel/lighting/core/photon_map.hpp"
#include "luxel/lighting/core/ray_scene.hpp"
#include "luxel/lighting/core/selective_emitter.hpp"
#include "luxel/runtime/jobs.hpp"
#include "luxel/scene/components.hpp"

namespace luxel::lighting {

/// PhotonWorld's lights (docs/METHOD.md §4): each light entity's selective emitter and photon
/// groups in the photon map, the groups waiting for a retrace, and the two steps of selective
/// emission (probes, retraces). A light added, changed, moved or switched invalidates all its
/// groups; one switched off or removed clears them.
class LightGroups {
  public:
    LightGroups(const ecs::Registry& registry, PhotonMap& map, const SelectiveSettings& settings);
    ~LightGroups();
    LightGroups(const LightGroups&) = delete;
    LightGroups& operator=(const LightGroups&) = delete;

    /// Re-reads the entity's light component (removing it if it is no longer a light) and
    /// invalidates its groups; `scene` bounds directional lights' discs.
    void refresh(ecs::Entity entity, const BoundingSphere& scene);
    void remove(ecs::Entity entity);
    /// Refreshes every directional light not in `skip` (sorted) whose disc `scene` moves: their
    /// discs follow the scene's sphere. One whose sphere is unchanged keeps its photons (an
    /// object moving inside the level invalidates only the groups it crosses).
    void refresh_directional(std::span<const ecs::Entity> skip, const BoundingSphere& scene);
    /// The world-space triangles of the enabled SkyPortals, three vertices each: where the
    /// photons of skies and suns start from their next refresh on (empty: the scene's disc).
    void set_portals(std::vector<glm::vec3> triangles) { portals_ = std::move(triangles); }

    [[nodiscard]] bool contains(ecs::Entity entity) const { return lights_.contains(entity); }
    [[nodiscard]] std::size_t size() const { return lights_.size(); }
    /// The enabled lights' entities, in entity order.
    [[nodiscard]] std::vector<ecs::Entity> enabled_entities() const;
    /// The light an entity emits (its emitter's source); the entity must be a light.
    [[nodiscard]] const LightSource& source(ecs::Entity entity) const;
    /// The emitters of the enabled lights.
    [[nodiscard]] std::vector<const LightPhotons*> active() const;
    /// The light entity whose groups include global group `group`, or null_entity.
    [[nodiscard]] ecs::Entity light_of_group(std::uint32_t group) const;

    [[nodiscard]] const std::vector<std::uint32_t>& pending() const { return pending_; }
    /// The probes of `frame`: adds the groups whose paths diverge to pending().
    EmissionStats probe(std::uint64_t frame, const RayScene& scene,
                        std::span<const TraceMaterial> materials, JobSystem& jobs);
    /// Exact invalidation (docs/METHOD.md §4.5): the groups whose stored paths cross any of
    /// `boxes` (where geometry was or is now) go to the front of pending(), to be retraced
    /// before any other. Returns how many were not pending yet.
    std::size_t invalidate_crossing(std::span<const AxisBox> boxes);
    [[nodiscard]] const PathSegmentIndex& paths() const { return paths_; }
    /// Retraces up to `max_groups` pending groups (all when 0), oldest first.
    EmissionStats retrace_pending(const RayScene& scene, std::span<const TraceMaterial> materials,
                                  JobSystem& jobs, std::size_t max_groups);

  private:
    struct Record {
        std::unique_ptr<LightPhotons> photons;
        bool enabled = true;
        bool directional = false;
        BoundingSphere scene;  ///< the sphere its emitter was made with
    };
    struct PiecesCache {
        std::shared_ptr<const scene::Scene> source;
        int mesh = -1;
        std::shared_ptr<const EmissionPieces> pieces;  ///< null when uniform
        glm::vec3 uniform{0.0f};                       ///< the radiance when uniform
    };
    /// The emitter's EmissionPieces, made once per mesh.
    const PiecesCache& emission_pieces(ecs::Entity entity, const scene::MeshInstance& instance);
    /// An area light's radiance averaged over its area (LightSource::power).
    [[nodiscard]] static glm::vec3 mean_radiance(const LightSource& light);
    void add_pending(std::uint32_t group);
    void drop_pending(const LightPhotons& photons);
    /// Removes every stored hit and path of the light's groups (switched off or gone).
    void clear_photons(const LightPhotons& photons);

    const ecs::Registry& registry_;
    PhotonMap& map_;
    SelectiveSettings settings_;
    std::map<ecs::Entity, Record> lights_;
    std::map<ecs::Entity, PiecesCache> pieces_;
    std::vector<std::uint32_t> pending_;
    /// Per group, 1 while it is in pending_ because invalidate_crossing put it there: a moving
    /// object finds the same groups every frame, and these need no second look until they are
    /// retraced (or dropped), which clears the mark.
    std::vector<std::uint8_t> crossing_pending_;
    PathSegmentIndex paths_;
    std::uint32_t next_seed_ = 1;
    std::vector<glm::vec3> portals_;
};

}  // namespace luxel::lighting
