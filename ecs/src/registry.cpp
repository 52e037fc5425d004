#include "luxel/ecs/registry.hpp"

namespace luxel::ecs {

Registry::Registry() = default;

Registry::~Registry() = default;

Entity Registry::create() {
    if (!free_slots_.empty()) {
        const std::uint32_t index = free_slots_.back();
        free_slots_.pop_back();
        Slot& slot = slots_[index];
        slot.alive = true;
        ++alive_;
        return Entity(index, slot.generation);
    }
    if (slots_.size() > Entity::max_index) {
        throw CapacityError("luxel::ecs: the registry holds the maximum of " +
                            std::to_string(Entity::max_index + 1) + " entity slots");
    }
    slots_.push_back(Slot{0, true, false});
    ++alive_;
    return Entity(static_cast<std::uint32_t>(slots_.size() - 1), 0);
}

void Registry::destroy(Entity entity) {
    check_valid(entity, "destroy");
    const std::uint32_t index = entity.index();
    if (slots_[index].dying) {
        return;  // a hook of this very destruction asked again
    }
    slots_[index].dying = true;
    on_destroy_entity_.emit(*this, entity);
    // Index loop, re-reading the size: a hook may create a pool (a first emplace of some type on
    // another entity), which appends to storages_.
    for (std::size_t i = 0; i < storages_.size(); ++i) {
        if (storages_[i]) {
            storages_[i]->remove(entity);
        }
    }
    // slots_ may have grown meanwhile (hooks may create entities): index afresh.
    Slot& slot = slots_[index];
    slot.alive = false;
    slot.dying = false;
    --alive_;
    if (slot.generation < Entity::max_generation) {
        ++slot.generation;
        free_slots_.push_back(index);
    }
    // else: retired. Its every handle stays stale forever rather than wrapping around to a
    // generation that an old handle might still carry.
}

void Registry::clear() {
    for (std::uint32_t index = 0; index < slots_.size(); ++index) {
        if (slots_[index].alive) {
            destroy(Entity(index, slots_[index].generation));
        }
    }
}

void Registry::check_valid_for_emplace(Entity entity) const {
    check_valid(entity, "emplace");
    if (slots_[entity.index()].dying) {
        throw EcsError("luxel::ecs: cannot add a component to entity " + to_string(entity) +
                       " while it is being destroyed");
    }
}

}  // namespace luxel::ecs
