#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

/// Lights as the photon tracer sees them: world space, watts, and a mapping from QMC samples
/// to emitted photons.
namespace luxel::lighting {

enum class LightKind { Point, Spot, Directional, Area };

struct LightSource {
    LightKind kind = LightKind::Point;
    glm::vec3 position{0.0f};
    glm::vec3 direction{0.0f, 0.0f, -1.0f};  ///< unit; spot axis / directional travel direction
    /// Point and spot: radiant flux in W (spot: into its whole outer cone, before falloff).
    /// Directional: irradiance in W/m^2. Area: emitted radiance in W/(m^2 sr).
    glm::vec3 power{0.0f};
    float inner_cone = 0.3f;  ///< spot, radians
    float outer_cone = 0.5f;  ///< spot, radians
    /// Area lights: world-space triangles, three vertices each, emitting on their front side.
    std::vector<glm::vec3> triangles;
};

/// One emitted photon.
struct EmittedPhoton {
    glm::vec3 origin{0.0f};
    glm::vec3 direction{0.0f, 0.0f, -1.0f};
    glm::vec3 power{0.0f};
};

/// The scene's bounding sphere: directional lights emit from a disc that covers it.
struct BoundingSphere {
    glm::vec3 centre{0.0f};
    float radius = 1.0f;
};

/// Points on a set of triangles chosen in proportion to area: the emitting surface of an area
/// light. Shared by global and caustic photon emission.
class TriangleSampler {
  public:
    TriangleSampler() = default;
    /// `triangles` holds three world-space vertices per triangle (throws luxel::Error if not).
    explicit TriangleSampler(std::vector<glm::vec3> triangles);

    struct Sample {
        glm::vec3 point{0.0f};
        glm::vec3 normal{0.0f};  ///< unit normal of the emitting side (zero for a degenerate one)
        std::size_t triangle = 0;
    };
    /// A point uniformly distributed over the total area: p.x picks the triangle by area and,
    /// rescaled, joins p.y to place the point (folded into the triangle).
    [[nodiscard]] Sample sample(const glm::dvec2& p) const;
    [[nodiscard]] double area() const { return area_; }
    [[nodiscard]] std::size_t size() const { return normals_.size(); }
    [[nodiscard]] const std::vector<glm::vec3>& vertices() const { return vertices_; }
    [[nodiscard]] const std::vector<glm::vec3>& normals() const { return normals_; }

  private:
    std::vector<glm::vec3> vertices_;
    std::vector<glm::vec3> normals_;
    std::vector<double> cdf_;  // cumulative area, normalised to 1
    double area_ = 0.0;
};

/// Maps QMC samples to photons for one light. Every photon of a light carries power
/// total_power() / photon_count (times the spot falloff at its direction), so the photons of a
/// light sum to its flux exactly.
class PhotonEmitter {
  public:
    PhotonEmitter(LightSource light, const BoundingSphere& scene_bounds);

    /// Total flux leaving the light in W per channel (area: pi * L * area; directional:
    /// E * pi * R^2 over the scene disc).
    [[nodiscard]] glm::vec3 total_power() const { return total_power_; }
    [[nodiscard]] const LightSource& light() const { return light_; }

    /// The photon for direction sample `d` (bases 2 and 3: this pair defines the groups) and
    /// position sample `p` (bases 5 and 7), one of `photon_count` photons.
    [[nodiscard]] EmittedPhoton emit(const glm::dvec2& d, const glm::dvec2& p,
                                     std::uint64_t photon_count) const;

  private:
    LightSource light_;
    BoundingSphere bounds_;
    glm::vec3 total_power_{0.0f};
    TriangleSampler area_;  // area lights
};

/// An orthonormal basis around n: (tangent, bitangent, n).
void orthonormal_basis(const glm::vec3& n, glm::vec3& tangent, glm::vec3& bitangent);

/// A cosine-distributed direction around n from a 2D sample in [0,1)^2.
[[nodiscard]] glm::vec3 cosine_direction(const glm::vec3& n, const glm::dvec2& u);

/// A spot light's falloff for a direction at cosine `cos_axis` from its axis: 1 inside the inner
/// cone, 0 outside the outer, smoothstep between (a hard edge when the cones coincide). One
/// definition for the photon and caustic emitters and the reference, so their estimates of one
/// light agree.
[[nodiscard]] float spot_falloff(double cos_outer, double cos_inner, double cos_axis);
/// The same for a spot LightSource (its inner cone clamped to the outer).
[[nodiscard]] float spot_falloff(const LightSource& light, double cos_axis);

}  // namespace luxel::lighting
