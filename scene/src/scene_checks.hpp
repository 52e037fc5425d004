#pragma once

// What scene.cpp and scene_transforms.cpp share: Scene::validate's helpers and the transform
// checks it calls.

#include <cstddef>
#include <string>

#include "luxel/runtime/error.hpp"
#include "luxel/scene/scene.hpp"

namespace luxel::scene::detail {

inline std::string quoted_name(const std::string& name) {
    return name.empty() ? "" : " '" + name + "'";
}

[[noreturn]] inline void invalid(const std::string& what) {
    throw Error("invalid scene: " + what);
}

inline bool in_range(int index, std::size_t size) {
    return index >= 0 && static_cast<std::size_t>(index) < size;
}

/// Every node's world scale and distance from the origin, over every pose, within 1e6; a camera's
/// world transform invertible.
void validate_transform_bounds(const Scene& scene);

/// Skins (joints distinct and in range, one finite inverse bind matrix per joint), every
/// primitive's joints and weights (one per vertex, weights at least 0 summing to 1), and every
/// skinned node's mesh (joints and weights present, each joint index within its skin).
void validate_skins(const Scene& scene);

/// Whether an inverse bind matrix is finite and within the bounds a node's transform has: its
/// axes at most 1e6 long and its translation at most 1e6 m (so no skinned vertex overflows).
[[nodiscard]] bool inverse_bind_within_bounds(const glm::mat4& matrix);

/// Every moving mesh's world scale, over every pose, at least 1e-9.
void validate_instance_scales(const Scene& scene);

}  // namespace luxel::scene::detail
