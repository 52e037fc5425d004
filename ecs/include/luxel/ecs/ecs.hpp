#pragma once

/// Everything in luxel's entity-component-system, for convenience. Each header documents its
/// part: registry.hpp (entities, components, views, observers, hooks), hierarchy.hpp and
/// transform_system.hpp (the transform hierarchy), pipeline.hpp (system ordering).

#include "luxel/ecs/context.hpp"
#include "luxel/ecs/entity.hpp"
#include "luxel/ecs/errors.hpp"
#include "luxel/ecs/hierarchy.hpp"
#include "luxel/ecs/observer.hpp"
#include "luxel/ecs/registry.hpp"
#include "luxel/ecs/signal.hpp"
#include "luxel/ecs/sparse_set.hpp"
#include "luxel/ecs/storage.hpp"
#include "luxel/ecs/transform.hpp"
#include "luxel/ecs/transform_system.hpp"
#include "luxel/ecs/type_id.hpp"
#include "luxel/ecs/view.hpp"
