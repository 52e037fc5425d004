#pragma once

#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

/// Caustic irradiance at pixel resolution (docs/METHOD.md §10.1): the texel-binned reference
/// averages a caustic over a light-map texel (5 cm on the caustics level), so a camera close to
/// a caustic would judge a method against a blocky picture. A footprint is the patch of surface
/// a pixel sees, taken as a disc of the same area in the surface's plane; every caustic photon
/// that lands in it adds its power, and the footprint's caustic irradiance is that power over the
/// disc's area: the caustic box-filtered over the pixel, as a camera integrates it.
namespace luxel::lighting::reference {

struct CausticFootprint {
    glm::vec3 centre{0.0f};
    glm::vec3 normal{0.0f, 1.0f, 0.0f};  ///< unit; the side the surface faces
    float radius = 0.0f;                 ///< metres, > 0
};

/// The disc of area `area` (m^2) a pixel sees at `centre` on a surface facing `normal`: area
/// from the pixel's solid angle, the distance and the angle of view (camera_footprint_area).
[[nodiscard]] CausticFootprint footprint_of_area(const glm::vec3& centre, const glm::vec3& normal,
                                                 double area);

/// The surface area a pixel subtending `pixel_solid_angle` (sr) sees at `distance` (m) on a
/// surface whose normal makes cos_theta with the view ray: distance^2 omega / cos_theta, with
/// cos_theta kept at least 0.05 (a grazing pixel sees a long sliver; past 87 degrees it is
/// bounded rather than infinite).
[[nodiscard]] double camera_footprint_area(double pixel_solid_angle, double distance,
                                           double cos_theta);

/// A set of footprints and the caustic flux each has collected. Photons are matched to the
/// footprints that hold them through hash grids, one per power-of-two class of radius, whose
/// cells are twice the class's largest radius: a disc lies in at most 8 cells of its class, and
/// a photon is looked up in one cell per class.
class CausticFootprints {
  public:
    /// Throws luxel::Error for a footprint whose centre or normal is not finite, whose normal
    /// is zero, or whose radius is not positive and finite.
    explicit CausticFootprints(std::vector<CausticFootprint> footprints);

    [[nodiscard]] std::size_t size() const { return footprints_.size(); }
    [[nodiscard]] const CausticFootprint& footprint(std::size_t i) const {
        return footprints_.at(i);
    }

    /// One photon's flux (W per channel) arriving at `position` on a surface facing `normal`:
    /// added to every footprint whose disc holds it (within the radius along the disc's plane,
    /// within a quarter radius of the plane, and on a surface facing the same way within 45
    /// degrees: a wall meeting the floor does not pour its caustic into the floor's pixels).
    void add(const glm::vec3& position, const glm::vec3& normal, const glm::dvec3& flux);

    /// Sum of the flux deposited in footprint i, and of its squares (for a standard error).
    [[nodiscard]] const glm::dvec3& flux(std::size_t i) const { return flux_.at(i); }
    [[nodiscard]] const glm::dvec3& flux_squares(std::size_t i) const {
        return flux_squares_.at(i);
    }
    /// pi r^2 of footprint i.
    [[nodiscard]] double area(std::size_t i) const;

  private:
    struct Level {
        float cell = 0.0f;
        std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells;
    };
    [[nodiscard]] static std::uint64_t cell_key(const glm::ivec3& cell);
    [[nodiscard]] bool holds(std::size_t i, const glm::vec3& position,
                             const glm::vec3& normal) const;

    std::vector<CausticFootprint> footprints_;
    std::vector<Level> levels_;
    std::vector<glm::dvec3> flux_;
    std::vector<glm::dvec3> flux_squares_;
};

}  // namespace luxel::lighting::reference
