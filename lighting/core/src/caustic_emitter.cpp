#include "luxel/lighting/core/caustic_emitter.hpp"

#include <algorithm>
#include <cmath>

#include "luxel/lighting/core/ray_scene.hpp"

namespace luxel::lighting {
namespace {

constexpr double kPi = 3.14159265358979323846264338327950288;
constexpr double kTwoPi = 2.0 * kPi;
constexpr double kFourPi = 4.0 * kPi;

/// Half angle of a cone in radians (pi for the full sphere of directions).
double half_angle(const DirectionCone& cone) {
    return std::acos(std::clamp(cone.cos_half_angle, -1.0, 1.0));
}

bool has_power(const glm::vec3& power) {
    return power.r > 0.0f || power.g > 0.0f || power.b > 0.0f;
}

/// Whether the ray (whole_line: the line) through `origin` along unit `direction` meets the
/// sphere; in double, as the cone a sibling samples is decided at its boundary.
bool meets(const glm::vec3& origin, const glm::vec3& direction, const BoundingSphere& sphere,
           bool whole_line) {
    const glm::dvec3 to_centre = glm::dvec3(sphere.centre) - glm::dvec3(origin);
    const double r2 = static_cast<double>(sphere.radius) * static_cast<double>(sphere.radius);
    const double along = glm::dot(to_centre, glm::dvec3(direction));
    const double distance2 = glm::dot(to_centre, to_centre);
    if (!whole_line && distance2 <= r2) {
        return true;  // the apex is inside: that pair samples every direction
    }
    return (whole_line || along > 0.0) && distance2 - along * along <= r2;
}

}  // namespace

double DirectionCone::solid_angle() const {
    return kTwoPi * (1.0 - std::clamp(cos_half_angle, -1.0, 1.0));
}

DirectionCone cone_toward(const glm::vec3& apex, const BoundingSphere& sphere) {
    const glm::dvec3 to_centre = glm::dvec3(sphere.centre) - glm::dvec3(apex);
    const double distance = glm::length(to_centre);
    const auto radius = static_cast<double>(sphere.radius);
    DirectionCone cone;
    if (distance <= radius || !(distance > 0.0)) {
        // The apex is inside the sphere: every direction can reach it.
        cone.axis = distance > 0.0 ? glm::vec3(to_centre / distance) : glm::vec3(0, 0, -1);
        cone.cos_half_angle = -1.0;
        return cone;
    }
    cone.axis = glm::vec3(to_centre / distance);
    // cos = sqrt(d^2 - r^2) / d, written as a product so that a sphere nearly touching the
    // apex keeps its precision.
    cone.cos_half_angle = std::sqrt((distance - radius) * (distance + radius)) / distance;
    return cone;
}

glm::vec3 direction_in_cone(const DirectionCone& cone, const glm::dvec2& u) {
    const double cos_max = std::clamp(cone.cos_half_angle, -1.0, 1.0);
    const double cos_theta = 1.0 - u.x * (1.0 - cos_max);
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    const double phi = kTwoPi * u.y;
    glm::vec3 tangent;
    glm::vec3 bitangent;
    orthonormal_basis(cone.axis, tangent, bitangent);
    return glm::normalize(static_cast<float>(sin_theta * std::cos(phi)) * tangent +
                          static_cast<float>(sin_theta * std::sin(phi)) * bitangent +
                          static_cast<float>(cos_theta) * cone.axis);
}

CausticEmitter::CausticEmitter(const LightSource& light, const BoundingSphere& generator,
                               const BoundingSphere& scene)
    : kind_(light.kind), generator_(generator) {
    if (!has_power(light.power) || !(generator.radius > 0.0f)) {
        return;
    }
    switch (light.kind) {
        case LightKind::Point: {
            origin_ = light.position;
            cone_ = cone_toward(light.position, generator);
            const double intensity_scale = cone_.solid_angle() / kFourPi;
            power_scale_ = light.power * static_cast<float>(intensity_scale);
            reaches_ = true;
            break;
        }
        case LightKind::Spot: {
            origin_ = light.position;
            spot_axis_ = glm::normalize(light.direction);
            const double outer = std::clamp(static_cast<double>(light.outer_cone), 1e-6, kPi);
            cos_outer_ = static_cast<float>(std::cos(outer));
            cos_inner_ = std::cos(std::clamp(light.inner_cone, 0.0f, light.outer_cone));
            const DirectionCone toward = cone_toward(light.position, generator);
            const double toward_angle = half_angle(toward);
            const double between = std::acos(
                std::clamp(static_cast<double>(glm::dot(toward.axis, spot_axis_)), -1.0, 1.0));
            if (between >= toward_angle + outer) {
                return;  // the generator lies outside the spot's cone
            }
            // Sample whichever cone is smaller when one holds the other; otherwise the
            // generator's cone, and the falloff zeroes the directions outside the spot.
            if (between + outer <= toward_angle) {
                cone_ = {spot_axis_, std::cos(outer)};
            } else {
                cone_ = toward;
            }
            const double spot_solid_angle = kTwoPi * (1.0 - std::cos(outer));
            power_scale_ = light.power * static_cast<float>(cone_.solid_angle() / spot_solid_angle);
            reaches_ = true;
            break;
        }
        case LightKind::Directional: {
            beam_direction_ = glm::normalize(light.direction);
            beam_radius_ = generator.radius;
            // Start the beam behind everything in the scene (as PhotonEmitter does for its
            // scene disc), so occluders between the sun and the generator cast their shadow.
            const float behind_scene =
                glm::dot(generator.centre - scene.centre, beam_direction_) + scene.radius;
            const float back = std::max(behind_scene, generator.radius) + generator.radius;
            beam_centre_ = generator.centre - back * beam_direction_;
            const double disc_area =
                kPi * static_cast<double>(generator.radius) * static_cast<double>(generator.radius);
            power_scale_ = light.power * static_cast<float>(disc_area);
            reaches_ = true;
            break;
        }
        case LightKind::Area: {
            area_ = TriangleSampler(light.triangles, light.pieces);
            pieces_ = light.pieces;
            piece_scale_ = light.piece_scale;
            const double area = area_.area();
            for (std::size_t t = 0; t < area_.size(); ++t) {
                // The light reaches the generator if the sphere is not wholly behind some
                // triangle's emitting side.
                const glm::vec3& normal = area_.normals()[t];
                if (glm::dot(normal, normal) > 0.0f &&
                    glm::dot(generator.centre - area_.vertices()[3 * t], normal) >
                        -generator.radius) {
                    reaches_ = true;
                }
            }
            if (!(area > 0.0)) {
                reaches_ = false;
                return;
            }
            power_scale_ = light.power * static_cast<float>(area);
            break;
        }
        case LightKind::Sky: {
            // A directional beam onto the generator's disc per sampled sky direction, started
            // behind everything in the scene whatever the direction.
            sky_ = light.sky;
            sky_scale_ = light.sky_scale;
            generator_ = generator;
            beam_radius_ = generator.radius;
            beam_back_ = glm::length(generator.centre - scene.centre) + scene.radius +
                         2.0f * generator.radius;
            reaches_ = sky_ != nullptr && !sky_->black() && sky_scale_ > 0.0f;
            break;
        }
    }
}

std::uint32_t CausticEmitter::sampling_pairs(const glm::vec3& apex,
                                             const glm::vec3& direction) const {
    // A light at infinity samples lines (the beam starts behind the whole scene whatever the
    // generator); a light with a position samples rays from the point it emits at.
    const bool whole_line = kind_ == LightKind::Directional || kind_ == LightKind::Sky;
    std::uint32_t pairs = 1;
    for (const BoundingSphere& sibling : siblings_) {
        if (meets(apex, direction, sibling, whole_line)) {
            ++pairs;
        }
    }
    return pairs;
}

bool CausticEmitter::may_sample(const BoundingSphere& sphere) const {
    if (!reaches_) {
        return false;
    }
    switch (kind_) {
        case LightKind::Point:
        case LightKind::Spot: {
            // Two cones from one apex meet when their axes are closer than the half angles'
            // sum; an apex inside either sphere sees it in every direction.
            const DirectionCone other = cone_toward(origin_, sphere);
            if (other.cos_half_angle <= -1.0 || cone_.cos_half_angle <= -1.0) {
                return true;
            }
            const double between = std::acos(std::clamp(
                static_cast<double>(glm::dot(glm::normalize(other.axis), cone_.axis)), -1.0, 1.0));
            return between <= half_angle(cone_) + half_angle(other) + 1e-6;
        }
        case LightKind::Directional: {
            // Parallel lines: the two discs across the beam overlap.
            const glm::dvec3 offset = glm::dvec3(sphere.centre) - glm::dvec3(beam_centre_);
            const glm::dvec3 along = glm::dvec3(beam_direction_);
            const glm::dvec3 across = offset - glm::dot(offset, along) * along;
            const double reach =
                static_cast<double>(beam_radius_) + static_cast<double>(sphere.radius);
            return glm::dot(across, across) <= reach * reach * (1.0 + 1e-6);
        }
        case LightKind::Area:
        case LightKind::Sky:
            return true;
    }
    return true;
}

EmittedPhoton CausticEmitter::emit(const glm::dvec2& d, const glm::dvec2& p,
                                   std::uint64_t photon_count) const {
    glm::vec3 apex(0.0f);
    EmittedPhoton photon = emit_alone(d, p, photon_count, apex);
    if (!siblings_.empty() && has_power(photon.power)) {
        photon.power /= static_cast<float>(sampling_pairs(apex, photon.direction));
    }
    return photon;
}

EmittedPhoton CausticEmitter::emit_alone(const glm::dvec2& d, const glm::dvec2& p,
                                         std::uint64_t photon_count, glm::vec3& apex) const {
    EmittedPhoton photon;
    photon.power = glm::vec3(0.0f);
    if (!reaches_) {
        return photon;
    }
    const double share = 1.0 / static_cast<double>(std::max<std::uint64_t>(photon_count, 1));
    switch (kind_) {
        case LightKind::Point:
            photon.origin = origin_;
            apex = origin_;
            photon.direction = direction_in_cone(cone_, d);
            photon.power = power_scale_ * static_cast<float>(share);
            break;
        case LightKind::Spot: {
            photon.origin = origin_;
            apex = origin_;
            photon.direction = direction_in_cone(cone_, d);
            const float falloff =
                spot_falloff(cos_outer_, cos_inner_, glm::dot(photon.direction, spot_axis_));
            photon.power = power_scale_ * static_cast<float>(share) * falloff;
            break;
        }
        case LightKind::Directional: {
            glm::vec3 tangent;
            glm::vec3 bitangent;
            orthonormal_basis(beam_direction_, tangent, bitangent);
            const double r = static_cast<double>(beam_radius_) * std::sqrt(p.x);
            const double phi = kTwoPi * p.y;
            photon.origin = beam_centre_ + static_cast<float>(r * std::cos(phi)) * tangent +
                            static_cast<float>(r * std::sin(phi)) * bitangent;
            photon.direction = beam_direction_;
            apex = photon.origin;
            photon.power = power_scale_ * static_cast<float>(share);
            break;
        }
        case LightKind::Area: {
            // A point on the light by area (as PhotonEmitter picks it), then a direction in
            // the cone from that point toward the generator.
            const TriangleSampler::Sample on_light = area_.sample(p);
            const glm::vec3 point = on_light.point;
            const glm::vec3& normal = on_light.normal;
            const DirectionCone toward = cone_toward(point, generator_);
            photon.direction = direction_in_cone(toward, d);
            photon.origin = offset_ray_origin(point, normal);
            apex = point;  // the cones are drawn from the point itself, before the offset
            const float cosine = glm::dot(normal, photon.direction);
            if (cosine > 0.0f && pieces_ != nullptr) {
                // L cos / (density x cone pdf x N), the cone's pdf 1 / solid angle.
                const double density = on_light.density;
                photon.power = density > 0.0
                                   ? glm::vec3(glm::dvec3(pieces_->radiance(on_light.triangle,
                                                                            on_light.piece) *
                                                          piece_scale_) *
                                               (static_cast<double>(cosine) * toward.solid_angle() *
                                                share / density))
                                   : glm::vec3(0.0f);
            } else if (cosine > 0.0f) {
                photon.power = power_scale_ * static_cast<float>(static_cast<double>(cosine) *
                                                                 toward.solid_angle() * share);
            }
            break;
        }
        case LightKind::Sky: {
            const SkyRadiance::Sample from = sky_->sample(d);
            if (!(from.pdf > 0.0)) {
                break;
            }
            const glm::vec3 travel = -from.direction;
            glm::vec3 tangent;
            glm::vec3 bitangent;
            orthonormal_basis(travel, tangent, bitangent);
            const double r = static_cast<double>(beam_radius_) * std::sqrt(p.x);
            const double phi = kTwoPi * p.y;
            photon.origin = generator_.centre - beam_back_ * travel +
                            static_cast<float>(r * std::cos(phi)) * tangent +
                            static_cast<float>(r * std::sin(phi)) * bitangent;
            photon.direction = travel;
            apex = photon.origin;
            // L pi r^2 / (pdf N) through the generator's disc.
            const double disc =
                kPi * static_cast<double>(beam_radius_) * static_cast<double>(beam_radius_);
            photon.power = glm::vec3(glm::dvec3(from.radiance) *
                                     (static_cast<double>(sky_scale_) * disc * share / from.pdf));
            break;
        }
    }
    return photon;
}

PhotonDifferential CausticEmitter::differential(const EmittedPhoton& photon,
                                                std::uint64_t photon_count) const {
    const double n = static_cast<double>(std::max<std::uint64_t>(photon_count, 1));
    const double disc = kPi * static_cast<double>(beam_radius_) * static_cast<double>(beam_radius_);
    switch (kind_) {
        case LightKind::Point:
        case LightKind::Spot:
            return emission_differential(photon.direction, 0.0, cone_.solid_angle() / n);
        case LightKind::Directional:
        case LightKind::Sky:
            return emission_differential(photon.direction, disc / n, 0.0);
        case LightKind::Area: {
            const double root = std::sqrt(n);
            const DirectionCone toward = cone_toward(photon.origin, generator_);
            return emission_differential(photon.direction, area_.area() / root,
                                         toward.solid_angle() / root);
        }
    }
    return emission_differential(photon.direction, 0.0, 0.0);
}

}  // namespace luxel::lighting
