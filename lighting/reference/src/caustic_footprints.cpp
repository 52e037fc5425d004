#include "luxel/lighting/reference/caustic_footprints.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/constants.hpp>

#include "luxel/runtime/error.hpp"

namespace luxel::lighting::reference {
namespace {

/// Footprints within a quarter of their radius of the photon's plane hold it: a pixel's disc
/// on a curved surface (radius R) leaves the surface by r^2 / 2R, a quarter radius where R = 2r.
constexpr float kPlaneTolerance = 0.25f;
/// The photon's surface faces the footprint's way within 45 degrees.
constexpr float kMinFacing = 0.7071f;

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

glm::ivec3 cell_of(const glm::vec3& p, float cell) {
    return glm::ivec3(glm::floor(p / cell));
}

}  // namespace

double camera_footprint_area(double pixel_solid_angle, double distance, double cos_theta) {
    return distance * distance * pixel_solid_angle / std::max(std::abs(cos_theta), 0.05);
}

CausticFootprint footprint_of_area(const glm::vec3& centre, const glm::vec3& normal, double area) {
    return {centre, normal, static_cast<float>(std::sqrt(std::max(area, 0.0) / glm::pi<double>()))};
}

CausticFootprints::CausticFootprints(std::vector<CausticFootprint> footprints)
    : footprints_(std::move(footprints)),
      flux_(footprints_.size(), glm::dvec3(0.0)),
      flux_squares_(footprints_.size(), glm::dvec3(0.0)) {
    float smallest = 0.0f;
    for (std::size_t i = 0; i < footprints_.size(); ++i) {
        CausticFootprint& f = footprints_[i];
        const float length = finite(f.normal) ? glm::length(f.normal) : 0.0f;
        if (!finite(f.centre) || !(length > 0.0f) || !std::isfinite(f.radius) ||
            !(f.radius > 0.0f)) {
            throw Error("CausticFootprints: footprint " + std::to_string(i) +
                        " needs a finite centre, a non-zero normal and a positive radius");
        }
        f.normal /= length;
        smallest = i == 0 ? f.radius : std::min(smallest, f.radius);
    }
    // Class L holds radii in (smallest 2^(L-1), smallest 2^L]; cells twice the class's largest.
    for (std::size_t i = 0; i < footprints_.size(); ++i) {
        const CausticFootprint& f = footprints_[i];
        const auto level = static_cast<std::size_t>(
            std::max(0.0f, std::ceil(std::log2(f.radius / smallest) - 1e-6f)));
        if (level >= levels_.size()) {
            levels_.resize(level + 1);
            for (std::size_t l = 0; l < levels_.size(); ++l) {
                levels_[l].cell = 2.0f * smallest * std::exp2(static_cast<float>(l));
            }
        }
        Level& grid = levels_[level];
        const glm::ivec3 lo = cell_of(f.centre - glm::vec3(f.radius), grid.cell);
        const glm::ivec3 hi = cell_of(f.centre + glm::vec3(f.radius), grid.cell);
        for (int z = lo.z; z <= hi.z; ++z) {
            for (int y = lo.y; y <= hi.y; ++y) {
                for (int x = lo.x; x <= hi.x; ++x) {
                    grid.cells[cell_key({x, y, z})].push_back(static_cast<std::uint32_t>(i));
                }
            }
        }
    }
}

std::uint64_t CausticFootprints::cell_key(const glm::ivec3& cell) {
    // 21 bits a coordinate: cells a few millimetres wide cover kilometres before they wrap,
    // and a wrapped key only costs a disc test that fails.
    constexpr std::uint64_t kMask = (1u << 21) - 1;
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(cell.x)) & kMask) |
           ((static_cast<std::uint64_t>(static_cast<std::uint32_t>(cell.y)) & kMask) << 21) |
           ((static_cast<std::uint64_t>(static_cast<std::uint32_t>(cell.z)) & kMask) << 42);
}

bool CausticFootprints::holds(std::size_t i, const glm::vec3& position,
                              const glm::vec3& normal) const {
    const CausticFootprint& f = footprints_[i];
    if (glm::dot(f.normal, normal) < kMinFacing) {
        return false;
    }
    const glm::vec3 offset = position - f.centre;
    const float height = glm::dot(offset, f.normal);
    if (std::abs(height) > kPlaneTolerance * f.radius) {
        return false;
    }
    const glm::vec3 along = offset - height * f.normal;
    return glm::dot(along, along) <= f.radius * f.radius;
}

void CausticFootprints::add(const glm::vec3& position, const glm::vec3& normal,
                            const glm::dvec3& flux) {
    if (!finite(position) || !finite(normal)) {
        return;
    }
    for (const Level& grid : levels_) {
        const auto found = grid.cells.find(cell_key(cell_of(position, grid.cell)));
        if (found == grid.cells.end()) {
            continue;
        }
        for (const std::uint32_t i : found->second) {
            if (holds(i, position, normal)) {
                flux_[i] += flux;
                flux_squares_[i] += flux * flux;
            }
        }
    }
}

double CausticFootprints::area(std::size_t i) const {
    const double r = footprints_.at(i).radius;
    return glm::pi<double>() * r * r;
}

}  // namespace luxel::lighting::reference
