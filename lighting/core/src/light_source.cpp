#include "luxel/lighting/core/light_source.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/constants.hpp>

#include "luxel/lighting/core/ray_scene.hpp"
#include "luxel/runtime/error.hpp"

namespace luxel::lighting {
namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

/// A direction inside the cone of half angle `angle` around `axis`, uniform in solid angle.
glm::vec3 cone_direction(const glm::vec3& axis, float angle, const glm::dvec2& u) {
    const double cos_max = std::cos(static_cast<double>(angle));
    const double cos_theta = 1.0 - u.x * (1.0 - cos_max);
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    const double phi = kTwoPi * u.y;
    glm::vec3 t;
    glm::vec3 b;
    orthonormal_basis(axis, t, b);
    return glm::normalize(static_cast<float>(sin_theta * std::cos(phi)) * t +
                          static_cast<float>(sin_theta * std::sin(phi)) * b +
                          static_cast<float>(cos_theta) * axis);
}

/// Where a photon leaving a portal at `at` along `direction` starts: a step off the portal's
/// plane on the side it travels to (along the normal: along a grazing direction the step would
/// round away), so that a pane or shutter in that plane lies behind it, where the tracer's look
/// back at the sky finds it.
glm::vec3 off_portal(const TriangleSampler::Sample& at, const glm::vec3& direction) {
    return offset_ray_origin(at.point, at.normal,
                             glm::dot(direction, at.normal) >= 0.0f ? 1.0f : -1.0f);
}

/// A sky photon through the portals: `p` places it on a portal, uniformly by area, and `d` picks
/// the direction it arrives from by one of two strategies, each with probability 1/2: the sky's
/// own distribution (its bright regions: the sun's aureole, an HDR map's lamps) or |cos| about
/// the portal on a side chosen at random (every direction through the opening, where most sky
/// samples would miss it). It carries L |cos| A / (pdf N) with pdf the mixture of the two
/// densities (one-sample MIS, balance heuristic), which bounds it by 4 pi L A / N whatever the
/// sky. Which side is the room's need not be known: a photon sent outwards is blocked behind
/// it by the room itself, which trace_photon checks (EmittedPhoton::from_portal).
EmittedPhoton portal_photon(const LightSource& light, const TriangleSampler& portals,
                            const glm::dvec2& d, const glm::dvec2& p, std::uint64_t photon_count) {
    EmittedPhoton photon;
    photon.power = glm::vec3(0.0f);
    photon.from_portal = true;
    const TriangleSampler::Sample at = portals.sample(p);
    if (light.sky == nullptr || !(at.density > 0.0)) {
        return photon;
    }
    glm::vec3 towards_sky;
    if (d.x < 0.5) {
        towards_sky = light.sky->sample({2.0 * d.x, d.y}).direction;
    } else {
        const double u = 2.0 * d.x - 1.0;
        const bool front = u < 0.5;
        const glm::dvec2 c(front ? 2.0 * u : 2.0 * u - 1.0, d.y);
        towards_sky = -cosine_direction(front ? at.normal : -at.normal, c);
    }
    const double cos_theta = std::abs(static_cast<double>(glm::dot(towards_sky, at.normal)));
    const double pdf = 0.5 * light.sky->pdf(towards_sky) + 0.5 * cos_theta / kTwoPi;
    const double weight = at.density * pdf * static_cast<double>(photon_count);
    photon.direction = -towards_sky;
    photon.origin = off_portal(at, photon.direction);
    if (!(weight > 0.0) || !(cos_theta > 0.0)) {
        return photon;
    }
    photon.power = glm::vec3(glm::dvec3(light.sky->radiance(towards_sky)) *
                             (static_cast<double>(light.sky_scale) * cos_theta / weight));
    return photon;
}

/// A sun's photon through the portals: `d` places it on a portal, uniformly by area; it travels
/// the sun's direction and carries E |cos| A / N (the irradiance through the opening). As for
/// the sky, one sent through the portal's back is blocked by the room behind it.
EmittedPhoton portal_beam(const LightSource& light, const TriangleSampler& portals,
                          const glm::dvec2& d, std::uint64_t photon_count) {
    EmittedPhoton photon;
    photon.power = glm::vec3(0.0f);
    photon.from_portal = true;
    photon.direction = light.direction;
    const TriangleSampler::Sample at = portals.sample(d);
    const double cos_theta = std::abs(static_cast<double>(glm::dot(light.direction, at.normal)));
    const double weight = at.density * static_cast<double>(photon_count);
    photon.origin = off_portal(at, photon.direction);
    if (!(weight > 0.0) || !(cos_theta > 0.0)) {
        return photon;
    }
    photon.power = glm::vec3(glm::dvec3(light.power) * (cos_theta / weight));
    return photon;
}

}  // namespace

glm::vec3 area_radiance(const LightSource& light, std::size_t triangle, std::uint32_t piece) {
    if (light.pieces == nullptr || triangle >= light.pieces->triangle_count() ||
        piece >= light.pieces->level(triangle) * light.pieces->level(triangle)) {
        return light.power;
    }
    return light.pieces->radiance(triangle, piece) * light.piece_scale;
}

glm::vec3 sky_radiance(const LightSource& light, const glm::vec3& towards_sky) {
    if (light.kind != LightKind::Sky || light.sky == nullptr) {
        return glm::vec3(0.0f);
    }
    return light.sky->radiance(towards_sky) * light.sky_scale;
}

AreaRadiance integrate_area_radiance(const LightSource& light) {
    AreaRadiance out;
    for (std::size_t t = 0; 3 * t + 2 < light.triangles.size(); ++t) {
        const glm::vec3* v = &light.triangles[3 * t];
        const double area = 0.5 * glm::length(glm::dvec3(glm::cross(v[1] - v[0], v[2] - v[0])));
        if (!(area > 0.0) || !std::isfinite(area)) {
            continue;
        }
        const std::uint32_t level = light.pieces != nullptr && t < light.pieces->triangle_count()
                                        ? light.pieces->level(t)
                                        : 1;
        glm::dvec3 sum(0.0);
        for (std::uint32_t k = 0; k < level * level; ++k) {
            sum += glm::dvec3(area_radiance(light, t, k));
        }
        out.radiance_times_area += sum * (area / (static_cast<double>(level) * level));
        out.area += area;
    }
    return out;
}

TriangleSampler::TriangleSampler(std::vector<glm::vec3> triangles,
                                 std::shared_ptr<const EmissionPieces> pieces)
    : vertices_(std::move(triangles)), pieces_(std::move(pieces)) {
    if (vertices_.size() % 3 != 0) {
        throw Error("TriangleSampler: triangles need three vertices each");
    }
    if (pieces_ != nullptr && pieces_->triangle_count() != vertices_.size() / 3) {
        throw Error("TriangleSampler: " + std::to_string(pieces_->triangle_count()) +
                    " triangles of pieces for " + std::to_string(vertices_.size() / 3) +
                    " triangles");
    }
    for (std::size_t t = 0; t < vertices_.size(); t += 3) {
        const glm::vec3 cross =
            glm::cross(vertices_[t + 1] - vertices_[t], vertices_[t + 2] - vertices_[t]);
        const float length = glm::length(cross);
        const double area = std::isfinite(length) ? 0.5 * static_cast<double>(length) : 0.0;
        area_ += area;
        triangle_area_.push_back(area);
        normals_.push_back(length > 0.0f && std::isfinite(length) ? cross / length
                                                                  : glm::vec3(0.0f));
        if (pieces_ == nullptr) {
            cdf_.push_back(area_);
            continue;
        }
        // Each piece covers 1/level^2 of its triangle (a regular subdivision).
        const std::size_t triangle = t / 3;
        const std::uint32_t level = pieces_->level(triangle);
        const double piece_area = area / (static_cast<double>(level) * level);
        for (std::uint32_t k = 0; k < level * level; ++k) {
            const glm::vec3& radiance = pieces_->radiance(triangle, k);
            const double weight = static_cast<double>(radiance.x) + radiance.y + radiance.z;
            if (weight > 0.0 && std::isfinite(weight)) {
                weighted_area_ += piece_area * weight;
            }
            cdf_.push_back(weighted_area_);
            piece_triangle_.push_back(static_cast<std::uint32_t>(triangle));
        }
    }
    const double total = pieces_ == nullptr ? area_ : weighted_area_;
    for (double& c : cdf_) {
        c = total > 0.0 ? c / total : 0.0;
    }
}

double TriangleSampler::density(std::size_t triangle, std::uint32_t piece) const {
    if (pieces_ == nullptr) {
        return area_ > 0.0 ? 1.0 / area_ : 0.0;
    }
    if (triangle >= pieces_->triangle_count() || !(weighted_area_ > 0.0)) {
        return 0.0;
    }
    const glm::vec3& radiance = pieces_->radiance(triangle, piece);
    const double weight = static_cast<double>(radiance.x) + radiance.y + radiance.z;
    // p(point) = (piece area x weight / total) / piece area.
    return weight > 0.0 && std::isfinite(weight) ? weight / weighted_area_ : 0.0;
}

std::uint32_t TriangleSampler::piece_at(std::size_t triangle, const glm::vec3& point) const {
    if (pieces_ == nullptr || triangle >= normals_.size()) {
        return 0;
    }
    const glm::dvec3 a(vertices_[3 * triangle]);
    const glm::dvec3 e1 = glm::dvec3(vertices_[3 * triangle + 1]) - a;
    const glm::dvec3 e2 = glm::dvec3(vertices_[3 * triangle + 2]) - a;
    const glm::dvec3 d = glm::dvec3(point) - a;
    // Least squares in the triangle's plane: [e1 e2] (s, q) = d.
    const double d11 = glm::dot(e1, e1);
    const double d12 = glm::dot(e1, e2);
    const double d22 = glm::dot(e2, e2);
    const double det = d11 * d22 - d12 * d12;
    if (!(det > 0.0)) {
        return 0;
    }
    const double b1 = glm::dot(d, e1);
    const double b2 = glm::dot(d, e2);
    const glm::dvec2 sq((d22 * b1 - d12 * b2) / det, (d11 * b2 - d12 * b1) / det);
    return EmissionPieces::piece_at(pieces_->level(triangle), sq);
}

TriangleSampler::Sample TriangleSampler::sample(const glm::dvec2& p) const {
    if (cdf_.empty()) {
        return {};
    }
    const auto found = std::upper_bound(cdf_.begin(), cdf_.end(), p.x);
    const std::size_t entry =
        std::min<std::size_t>(static_cast<std::size_t>(found - cdf_.begin()), cdf_.size() - 1);
    const double low = entry == 0 ? 0.0 : cdf_[entry - 1];
    const double width = cdf_[entry] - low;
    double s = width > 0.0 ? std::clamp((p.x - low) / width, 0.0, 1.0) : 0.0;
    double q = p.y;
    if (s + q > 1.0) {  // fold the far half of the parallelogram back into the triangle
        s = 1.0 - s;
        q = 1.0 - q;
    }
    std::size_t t = entry;
    std::uint32_t piece = 0;
    if (pieces_ != nullptr) {
        t = piece_triangle_[entry];
        piece = static_cast<std::uint32_t>(entry - pieces_->first_piece(t));
        // (s, q) within the piece, to the triangle's own barycentrics.
        const auto corner = EmissionPieces::corners(pieces_->level(t), piece);
        const glm::dvec2 sq = corner[0] + s * (corner[1] - corner[0]) + q * (corner[2] - corner[0]);
        s = sq.x;
        q = sq.y;
    }
    const glm::vec3& a = vertices_[3 * t];
    const glm::vec3& b = vertices_[3 * t + 1];
    const glm::vec3& c = vertices_[3 * t + 2];
    return {a + static_cast<float>(s) * (b - a) + static_cast<float>(q) * (c - a), normals_[t], t,
            piece, density(t, piece)};
}

void orthonormal_basis(const glm::vec3& n, glm::vec3& tangent, glm::vec3& bitangent) {
    // Duff et al.'s branchless construction: continuous except at n.z = -1 exactly.
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    tangent = glm::vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    bitangent = glm::vec3(b, sign + n.y * n.y * a, -n.y);
}

glm::vec3 cosine_direction(const glm::vec3& n, const glm::dvec2& u) {
    // In float: the result is a float direction, and double sin and cos were 8% of a photon
    // trace's profile.
    const auto ux = static_cast<float>(u.x);
    const float r = std::sqrt(ux);
    const auto phi = static_cast<float>(kTwoPi * u.y);
    glm::vec3 t;
    glm::vec3 b;
    orthonormal_basis(n, t, b);
    const float x = r * std::cos(phi);
    const float y = r * std::sin(phi);
    const float z = std::sqrt(std::max(0.0f, 1.0f - ux));
    return glm::normalize(x * t + y * b + z * n);
}

float spot_falloff(double cos_outer, double cos_inner, double cos_axis) {
    if (!(cos_inner > cos_outer)) {
        return cos_axis >= cos_inner ? 1.0f : 0.0f;
    }
    const double t = std::clamp((cos_axis - cos_outer) / (cos_inner - cos_outer), 0.0, 1.0);
    return static_cast<float>(t * t * (3.0 - 2.0 * t));
}

float spot_falloff(const LightSource& light, double cos_axis) {
    return spot_falloff(
        std::cos(static_cast<double>(light.outer_cone)),
        std::cos(static_cast<double>(std::clamp(light.inner_cone, 0.0f, light.outer_cone))),
        cos_axis);
}

glm::vec3 scene_disc_origin(const BoundingSphere& scene, const glm::vec3& travel,
                            const glm::dvec2& u) {
    glm::vec3 t;
    glm::vec3 b;
    orthonormal_basis(travel, t, b);
    const double r = static_cast<double>(scene.radius) * std::sqrt(u.x);
    const double phi = kTwoPi * u.y;
    return scene.centre + static_cast<float>(r * std::cos(phi)) * t +
           static_cast<float>(r * std::sin(phi)) * b - 2.0f * scene.radius * travel;
}

PhotonEmitter::PhotonEmitter(LightSource light, const BoundingSphere& scene_bounds)
    : light_(std::move(light)), bounds_(scene_bounds) {
    constexpr float pi = glm::pi<float>();
    switch (light_.kind) {
        case LightKind::Point:
        case LightKind::Spot:
            total_power_ = light_.power;
            break;
        case LightKind::Directional:
            if (!light_.portals.empty()) {
                portals_ = TriangleSampler(light_.portals);
                total_power_ = light_.power * static_cast<float>(portals_.area());
                break;
            }
            total_power_ = light_.power * pi * bounds_.radius * bounds_.radius;
            break;
        case LightKind::Area: {
            area_ = TriangleSampler(light_.triangles, light_.pieces);
            if (light_.pieces == nullptr) {
                total_power_ = light_.power * (pi * static_cast<float>(area_.area()));
                break;
            }
            total_power_ =
                glm::vec3(integrate_area_radiance(light_).radiance_times_area * glm::pi<double>());
            break;
        }
        case LightKind::Sky:
            if (!light_.portals.empty()) {
                portals_ = TriangleSampler(light_.portals);
                total_power_ =
                    light_.sky != nullptr
                        ? glm::vec3(light_.sky->integral() *
                                    (0.5 * portals_.area() * static_cast<double>(light_.sky_scale)))
                        : glm::vec3(0.0f);
                break;
            }
            total_power_ =
                light_.sky != nullptr
                    ? glm::vec3(light_.sky->integral() *
                                (glm::pi<double>() * static_cast<double>(bounds_.radius) *
                                 static_cast<double>(bounds_.radius) *
                                 static_cast<double>(light_.sky_scale)))
                    : glm::vec3(0.0f);
            break;
    }
}

EmittedPhoton PhotonEmitter::emit(const glm::dvec2& d, const glm::dvec2& p,
                                  std::uint64_t photon_count) const {
    EmittedPhoton photon;
    const float share = 1.0f / static_cast<float>(std::max<std::uint64_t>(photon_count, 1));
    photon.power = total_power_ * share;
    switch (light_.kind) {
        case LightKind::Point: {
            const double z = 1.0 - 2.0 * d.x;
            const auto r = static_cast<float>(std::sqrt(std::max(0.0, 1.0 - z * z)));
            // The azimuth's sin and cos in float, as in cosine_direction.
            const auto phi = static_cast<float>(kTwoPi * d.y);
            photon.origin = light_.position;
            photon.direction =
                glm::vec3(r * std::cos(phi), r * std::sin(phi), static_cast<float>(z));
            break;
        }
        case LightKind::Spot: {
            photon.origin = light_.position;
            photon.direction = cone_direction(light_.direction, light_.outer_cone, d);
            // Intensity falls off smoothly from the inner to the outer cone.
            photon.power *= spot_falloff(light_, glm::dot(photon.direction, light_.direction));
            break;
        }
        case LightKind::Directional: {
            if (!light_.portals.empty()) {
                photon = portal_beam(light_, portals_, d, photon_count);
                break;
            }
            // One direction: d places the photon on the scene's disc.
            photon.origin = scene_disc_origin(bounds_, light_.direction, d);
            photon.direction = light_.direction;
            break;
        }
        case LightKind::Area: {
            // p places the point on the light, d picks the cosine-distributed direction.
            const TriangleSampler::Sample on_light = area_.sample(p);
            photon.origin = on_light.point;
            const glm::vec3 normal = on_light.normal;
            photon.direction = cosine_direction(normal, d);
            photon.origin = offset_ray_origin(photon.origin, normal);
            if (light_.pieces != nullptr) {
                // pi L / (density N): the flux estimate of a point chosen by power.
                const double weight = on_light.density * static_cast<double>(photon_count);
                photon.power = weight > 0.0
                                   ? glm::vec3(glm::dvec3(area_radiance(light_, on_light.triangle,
                                                                        on_light.piece)) *
                                               (glm::pi<double>() / weight))
                                   : glm::vec3(0.0f);
            }
            break;
        }
        case LightKind::Sky: {
            // d picks the direction the sky sends the photon from (so the groups are regions
            // of the sky), p a point on the disc of the scene's sphere facing it, moved back
            // outside the sphere as for a directional light.
            photon.power = glm::vec3(0.0f);
            if (light_.sky == nullptr) {
                break;
            }
            if (!light_.portals.empty()) {
                photon = portal_photon(light_, portals_, d, p, photon_count);
                break;
            }
            const SkyRadiance::Sample from = light_.sky->sample(d);
            const glm::vec3 travel = -from.direction;
            photon.origin = scene_disc_origin(bounds_, travel, p);
            photon.direction = travel;
            // L pi R^2 / (pdf N): the flux through the disc from a direction chosen by pdf.
            const double weight = from.pdf * static_cast<double>(photon_count);
            if (weight > 0.0) {
                const double disc = glm::pi<double>() * static_cast<double>(bounds_.radius) *
                                    static_cast<double>(bounds_.radius);
                photon.power = glm::vec3(glm::dvec3(from.radiance) *
                                         (disc * static_cast<double>(light_.sky_scale) / weight));
            }
            break;
        }
    }
    return photon;
}

}  // namespace luxel::lighting
