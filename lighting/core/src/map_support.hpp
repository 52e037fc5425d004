#pragma once

#include <cmath>
#include <limits>

#include <glm/glm.hpp>

// Small guards the maps' stages share (MapRegistry, AimRebuilder, IimGatherPasses).
namespace luxel::lighting::map_support {

inline bool finite_vector(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// A value fit for a light map: finite and non-negative per channel.
inline glm::vec3 sanitized(const glm::vec3& v) {
    return finite_vector(v) ? glm::max(v, glm::vec3(0.0f)) : glm::vec3(0.0f);
}

/// A relative delta, guarded: a surface holding nothing has changed "completely" when anything
/// arrived, and not at all otherwise.
inline double relative(double delta, double stored) {
    if (stored > 0.0) {
        return delta / stored;
    }
    return delta > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
}

inline double safe_area(double area) {
    return area > 1e-12 ? area : 1e-12;
}

}  // namespace luxel::lighting::map_support
