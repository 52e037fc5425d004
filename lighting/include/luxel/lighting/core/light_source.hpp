#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/lighting/core/emission_pieces.hpp"
#include "luxel/lighting/core/sky_radiance.hpp"

/// Lights as the photon tracer sees them: world space, watts, and a mapping from QMC samples
/// to emitted photons.
namespace luxel::lighting {

enum class LightKind { Point, Spot, Directional, Area, Sky };

struct LightSource {
    LightKind kind = LightKind::Point;
    glm::vec3 position{0.0f};
    glm::vec3 direction{0.0f, 0.0f, -1.0f};  ///< unit; spot axis / directional travel direction
    /// Point and spot: radiant flux in W (spot: into its whole outer cone, before falloff).
    /// Directional: irradiance in W/m^2. Area: emitted radiance in W/(m^2 sr), the mean over
    /// its area when `pieces` vary it.
    glm::vec3 power{0.0f};
    float inner_cone = 0.3f;  ///< spot, radians
    float outer_cone = 0.5f;  ///< spot, radians
    /// Point and spot: the radius of the sphere that emits, metres (0: a point). The direct
    /// light's shadows use it; photons leave from `position`.
    float radius = 0.0f;
    /// Area lights: world-space triangles, three vertices each, emitting on their front side.
    std::vector<glm::vec3> triangles;
    /// Area lights: the radiance of each triangle's pieces (one per triangle in `triangles`'
    /// order), times `piece_scale`; null: `power` everywhere.
    std::shared_ptr<const EmissionPieces> pieces;
    float piece_scale = 1.0f;  ///< the AreaLight's scale, which the shared pieces leave out
    /// Sky: the radiance at infinity (null: black), times `sky_scale`.
    std::shared_ptr<const SkyRadiance> sky;
    float sky_scale = 1.0f;
    /// Sky and directional: the world-space triangles of the level's SkyPortals, three vertices
    /// each; photons start on them when there are any (empty: on the disc of the scene's
    /// sphere).
    std::vector<glm::vec3> portals;
};

/// The radiance a sky light sends from direction `towards_sky` (0 for other kinds).
[[nodiscard]] glm::vec3 sky_radiance(const LightSource& light, const glm::vec3& towards_sky);

/// The radiance W/(m^2 sr) an area light emits from a piece of a triangle (`power` without
/// pieces).
[[nodiscard]] glm::vec3 area_radiance(const LightSource& light, std::size_t triangle,
                                      std::uint32_t piece);

/// An area light's radiance integrated over its triangles: the sum of each triangle's area
/// times its pieces' mean radiance (pi times it is the light's flux, W), and the area summed
/// (m^2). Degenerate and non-finite triangles count for nothing.
struct AreaRadiance {
    glm::dvec3 radiance_times_area{0.0};
    double area = 0.0;
};
[[nodiscard]] AreaRadiance integrate_area_radiance(const LightSource& light);

/// One emitted photon.
struct EmittedPhoton {
    glm::vec3 origin{0.0f};
    glm::vec3 direction{0.0f, 0.0f, -1.0f};
    glm::vec3 power{0.0f};
    /// A sky or sun photon that starts on a portal: it carries light only if the sky is open from
    /// its origin back along -direction, which the tracer checks (trace_photon) before tracing it.
    bool from_portal = false;
};

/// The scene's bounding sphere: directional and sky lights emit from a disc that covers it.
struct BoundingSphere {
    glm::vec3 centre{0.0f};
    float radius = 1.0f;
};

/// Where a photon of a light at infinity (directional, sky) starts: a point on the disc of the
/// scene's bounding sphere facing `travel` (unit), moved 2R back so that it starts outside the
/// scene. u.x picks the radius (uniformly over the disc's area), u.y the angle.
[[nodiscard]] glm::vec3 scene_disc_origin(const BoundingSphere& scene, const glm::vec3& travel,
                                          const glm::dvec2& u);

/// Points on a set of triangles: the emitting surface of an area light. Without pieces, chosen
/// in proportion to area; with EmissionPieces, in proportion to each piece's area times its
/// radiance (channels summed), so the points follow the light's power and a dark piece is never
/// chosen. Shared by global and caustic photon emission and the reference.
class TriangleSampler {
  public:
    TriangleSampler() = default;
    /// `triangles` holds three world-space vertices per triangle (throws luxel::Error if not,
    /// or if `pieces` describes another number of triangles).
    explicit TriangleSampler(std::vector<glm::vec3> triangles,
                             std::shared_ptr<const EmissionPieces> pieces = nullptr);

    struct Sample {
        glm::vec3 point{0.0f};
        glm::vec3 normal{0.0f};  ///< unit normal of the emitting side (zero for a degenerate one)
        std::size_t triangle = 0;
        std::uint32_t piece = 0;
        /// Probability density of this point per m^2 of the light (0: nothing to sample).
        double density = 0.0;
    };
    /// A point: p.x picks the triangle (or piece) and, rescaled, joins p.y to place the point
    /// uniformly within it (folded into the triangle).
    [[nodiscard]] Sample sample(const glm::dvec2& p) const;
    /// The density per m^2 with which sample() picks a point of `piece` of `triangle`.
    [[nodiscard]] double density(std::size_t triangle, std::uint32_t piece) const;
    /// The barycentric (s, q) of a point on `triangle` (projected onto its plane) and the piece
    /// that holds it.
    [[nodiscard]] std::uint32_t piece_at(std::size_t triangle, const glm::vec3& point) const;
    [[nodiscard]] double area() const { return area_; }
    [[nodiscard]] std::size_t size() const { return normals_.size(); }
    [[nodiscard]] const std::vector<glm::vec3>& vertices() const { return vertices_; }
    [[nodiscard]] const std::vector<glm::vec3>& normals() const { return normals_; }

  private:
    std::vector<glm::vec3> vertices_;
    std::vector<glm::vec3> normals_;
    std::vector<double> triangle_area_;
    std::shared_ptr<const EmissionPieces> pieces_;
    // Cumulative area (or, with pieces, area x radiance per piece), normalised to 1.
    std::vector<double> cdf_;
    std::vector<std::uint32_t> piece_triangle_;  // with pieces: the triangle of each piece
    double area_ = 0.0;
    double weighted_area_ = 0.0;  // with pieces: sum of area x radiance
};

/// Maps QMC samples to photons for one light. Every photon of a light carries power
/// total_power() / photon_count (times the spot falloff at its direction), so the photons of a
/// light sum to its flux exactly; an area light with pieces emits by power instead, each photon
/// pi L / (density x photon_count), equal in every piece of one colour.
class PhotonEmitter {
  public:
    PhotonEmitter(LightSource light, const BoundingSphere& scene_bounds);

    /// Total flux leaving the light in W per channel (area: pi * L * area; directional:
    /// E * pi * R^2 over the scene disc; sky: pi * R^2 times its radiance integrated over the
    /// sphere; through portals: E times their area, and at most their area times half the sky's
    /// integral).
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
    TriangleSampler area_;     // area lights
    TriangleSampler portals_;  // a sky's portals
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
