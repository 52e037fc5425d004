#include "luxel/ecs/observer.hpp"

#include "luxel/ecs/errors.hpp"

namespace luxel::ecs::detail {

void ObserverState::throw_reentrant_consume() {
    throw EcsError("luxel::ecs: Observer::consume called from inside its own callback");
}

}  // namespace luxel::ecs::detail
