#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "luxel/ecs/entity.hpp"
#include "luxel/ecs/hierarchy.hpp"
#include "luxel/ecs/observer.hpp"
#include "luxel/ecs/registry.hpp"
#include "luxel/ecs/transform.hpp"

namespace luxel::ecs {

/// Computes WorldTransform = parent's WorldTransform x Transform::matrix() for the entities whose
/// world may have changed, and only those.
///
/// What is dirty: an entity whose Transform was added, patched/replaced/marked updated or
/// removed, or whose Parent was set, changed or removed since the last update(); with it, its
/// whole subtree. The first update() treats everything as dirty (so a system created for a
/// populated registry catches up). Clean subtrees are not visited: a frame in which one leaf of
/// a 100,000-entity scene moved costs one matrix product.
///
/// Order and stack: dirty entities are sorted by depth, and each one's subtree is walked with an
/// explicit stack, parents before children; a subtree already walked in this update is skipped.
/// Nothing recurses, so a 10,000-deep chain costs 10,000 loop iterations and no stack.
///
/// Rules: an entity with a Transform gets a WorldTransform (emplaced on first update, removed when
/// its Transform is). An ancestor without a Transform counts as the identity. WorldTransform
/// changes are recorded (Updated, via the pool) only when the matrix actually changed, so an
/// observer of WorldTransform sees precisely what moved in the world.
///
/// Bound to one registry for life (it observes that registry's pools). Plug it into a pipeline:
///     TransformSystem transforms(registry);
///     pipeline.add(Phase::Transforms, "transforms",
///                  [&transforms](Registry& r, double) { transforms.update(r); });
class TransformSystem {
  public:
    explicit TransformSystem(Registry& registry);
    TransformSystem(const TransformSystem&) = delete;
    TransformSystem& operator=(const TransformSystem&) = delete;
    TransformSystem(TransformSystem&&) noexcept = default;
    TransformSystem& operator=(TransformSystem&&) noexcept = default;
    ~TransformSystem() = default;

    /// Brings every WorldTransform up to date. O(dirty entities x log + their subtrees' sizes).
    void update();
    /// update(), after checking that `registry` is the one this system was made for (throws
    /// EcsError otherwise): for game loops that hand each system the registry.
    void update(Registry& registry);

    /// How many entities the last update() visited (recomputed or checked): a measure of the
    /// work done, for tests and profiling.
    [[nodiscard]] std::size_t last_visit_count() const noexcept { return last_visit_count_; }

    [[nodiscard]] Registry& registry() const noexcept { return *registry_; }

  private:
    Registry* registry_;
    Observer<Transform> transform_changes_;
    Observer<Parent> parent_changes_;
    // Scratch kept between updates so a steady frame allocates nothing.
    std::vector<std::pair<std::uint32_t, Entity>> dirty_;
    std::vector<Entity> stack_;
    std::vector<std::uint32_t> visited_in_update_;  // per slot index: the update that last saw it
    std::uint32_t update_number_ = 0;
    std::size_t last_visit_count_ = 0;
};

}  // namespace luxel::ecs
