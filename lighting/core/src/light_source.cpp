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

}  // namespace

TriangleSampler::TriangleSampler(std::vector<glm::vec3> triangles)
    : vertices_(std::move(triangles)) {
    if (vertices_.size() % 3 != 0) {
        throw Error("TriangleSampler: triangles need three vertices each");
    }
    for (std::size_t t = 0; t < vertices_.size(); t += 3) {
        const glm::vec3 cross =
            glm::cross(vertices_[t + 1] - vertices_[t], vertices_[t + 2] - vertices_[t]);
        const float length = glm::length(cross);
        area_ += 0.5 * static_cast<double>(length);
        normals_.push_back(length > 0.0f ? cross / length : glm::vec3(0.0f));
        cdf_.push_back(area_);
    }
    for (double& c : cdf_) {
        c = area_ > 0.0 ? c / area_ : 0.0;
    }
}

TriangleSampler::Sample TriangleSampler::sample(const glm::dvec2& p) const {
    if (cdf_.empty()) {
        return {};
    }
    const auto found = std::upper_bound(cdf_.begin(), cdf_.end(), p.x);
    const std::size_t t =
        std::min<std::size_t>(static_cast<std::size_t>(found - cdf_.begin()), cdf_.size() - 1);
    const double low = t == 0 ? 0.0 : cdf_[t - 1];
    const double width = cdf_[t] - low;
    double s = width > 0.0 ? std::clamp((p.x - low) / width, 0.0, 1.0) : 0.0;
    double q = p.y;
    if (s + q > 1.0) {  // fold the far half of the parallelogram back into the triangle
        s = 1.0 - s;
        q = 1.0 - q;
    }
    const glm::vec3& a = vertices_[3 * t];
    const glm::vec3& b = vertices_[3 * t + 1];
    const glm::vec3& c = vertices_[3 * t + 2];
    return {a + static_cast<float>(s) * (b - a) + static_cast<float>(q) * (c - a), normals_[t], t};
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
    const double r = std::sqrt(u.x);
    const double phi = kTwoPi * u.y;
    glm::vec3 t;
    glm::vec3 b;
    orthonormal_basis(n, t, b);
    const auto x = static_cast<float>(r * std::cos(phi));
    const auto y = static_cast<float>(r * std::sin(phi));
    const auto z = static_cast<float>(std::sqrt(std::max(0.0, 1.0 - u.x)));
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

PhotonEmitter::PhotonEmitter(LightSource light, const BoundingSphere& scene_bounds)
    : light_(std::move(light)), bounds_(scene_bounds) {
    constexpr float pi = glm::pi<float>();
    switch (light_.kind) {
        case LightKind::Point:
        case LightKind::Spot:
            total_power_ = light_.power;
            break;
        case LightKind::Directional:
            total_power_ = light_.power * pi * bounds_.radius * bounds_.radius;
            break;
        case LightKind::Area: {
            area_ = TriangleSampler(light_.triangles);
            const double area = area_.area();
            total_power_ = light_.power * (pi * static_cast<float>(area));
            break;
        }
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
            const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
            const double phi = kTwoPi * d.y;
            photon.origin = light_.position;
            photon.direction =
                glm::vec3(static_cast<float>(r * std::cos(phi)),
                          static_cast<float>(r * std::sin(phi)), static_cast<float>(z));
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
            // A point on the disc of the scene's bounding sphere facing the light, moved back
            // behind the sphere so every photon starts outside the scene.
            glm::vec3 t;
            glm::vec3 b;
            orthonormal_basis(light_.direction, t, b);
            const double r = static_cast<double>(bounds_.radius) * std::sqrt(d.x);
            const double phi = kTwoPi * d.y;
            photon.origin = bounds_.centre + static_cast<float>(r * std::cos(phi)) * t +
                            static_cast<float>(r * std::sin(phi)) * b -
                            2.0f * bounds_.radius * light_.direction;
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
            break;
        }
    }
    return photon;
}

}  // namespace luxel::lighting
