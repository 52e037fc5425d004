#include "luxel/lighting/core/photon_differential.hpp"

#include <cmath>

#include "luxel/lighting/core/light_source.hpp"

// Igehy, "Tracing ray differentials", SIGGRAPH 1999, section 3; the notation of S. Larsen
// (2006, §2.10): P, D the ray, N the unit normal, t the distance, eta = eta_from / eta_to.
namespace luxel::lighting {
namespace {

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

PhotonDifferential emission_differential(const glm::vec3& direction, double area,
                                         double solid_angle) {
    glm::vec3 tangent;
    glm::vec3 bitangent;
    orthonormal_basis(direction, tangent, bitangent);
    const float along = static_cast<float>(std::sqrt(std::max(area, 0.0)));
    const float turn = static_cast<float>(std::sqrt(std::max(solid_angle, 0.0)));
    PhotonDifferential differential;
    differential.dp_u = along * tangent;
    differential.dp_v = along * bitangent;
    differential.dd_u = turn * tangent;
    differential.dd_v = turn * bitangent;
    return differential;
}

void transfer(PhotonDifferential& differential, const glm::vec3& direction, float distance,
              const glm::vec3& normal) {
    const float dn = glm::dot(direction, normal);
    if (!differential.valid || !(std::abs(dn) > 1e-6f)) {
        differential.valid = false;  // a tangent hit: the offset rays miss the plane
        return;
    }
    // dP' = dP + t dD + dt D with dt = -((dP + t dD) . N) / (D . N): the offset point slides
    // along the ray until it lies on the plane.
    const auto move = [&](glm::vec3& dp, const glm::vec3& dd) {
        const glm::vec3 moved = dp + distance * dd;
        dp = moved - (glm::dot(moved, normal) / dn) * direction;
    };
    move(differential.dp_u, differential.dd_u);
    move(differential.dp_v, differential.dd_v);
}

glm::mat3 shading_normal_jacobian(const RayScene& scene, const RayHit& hit) {
    const HitTriangle triangle = scene.triangle(hit);
    if (!triangle.has_normals) {
        return glm::mat3(0.0f);
    }
    const glm::vec3* p = triangle.positions;
    const glm::vec3* n = triangle.normals;
    const glm::vec3 e1 = p[1] - p[0];
    const glm::vec3 e2 = p[2] - p[0];
    const glm::vec3 g = glm::cross(e1, e2);
    const float g2 = glm::dot(g, g);
    if (!(g2 > 0.0f)) {
        return glm::mat3(0.0f);
    }
    // The dual basis of the edges in their plane: b1 . e1 = 1, b1 . e2 = 0 and so on, so a
    // displacement d moves the barycentrics by (b1 . d, b2 . d).
    const glm::vec3 b1 = glm::cross(e2, g) / g2;
    const glm::vec3 b2 = glm::cross(g, e1) / g2;
    const float w = 1.0f - hit.barycentric.x - hit.barycentric.y;
    const glm::vec3 unnormalised = w * n[0] + hit.barycentric.x * n[1] + hit.barycentric.y * n[2];
    const float length = glm::length(unnormalised);
    if (!(length > 0.0f)) {
        return glm::mat3(0.0f);
    }
    const glm::vec3 unit = unnormalised / length;
    // d(unnormalised) = (n1 - n0)(b1 . d) + (n2 - n0)(b2 . d): the outer products, column-major.
    const glm::mat3 change =
        glm::outerProduct(n[1] - n[0], b1) + glm::outerProduct(n[2] - n[0], b2);
    // Normalising removes the part along the normal: (I - N N^T) / |n|.
    const glm::mat3 project = glm::mat3(1.0f) - glm::outerProduct(unit, unit);
    return project * change / length;
}

void reflect(PhotonDifferential& differential, const glm::vec3& direction, const glm::vec3& normal,
             const glm::mat3& normal_jacobian) {
    if (!differential.valid) {
        return;
    }
    // D' = D - 2 (D . N) N; dD' = dD - 2 ((D . N) dN + d(D . N) N), d(D . N) = dD . N + D . dN.
    const float dn = glm::dot(direction, normal);
    const auto turn = [&](const glm::vec3& dp, glm::vec3& dd) {
        const glm::vec3 d_normal = normal_jacobian * dp;
        const float d_dn = glm::dot(dd, normal) + glm::dot(direction, d_normal);
        dd = dd - 2.0f * (dn * d_normal + d_dn * normal);
    };
    turn(differential.dp_u, differential.dd_u);
    turn(differential.dp_v, differential.dd_v);
}

void refract(PhotonDifferential& differential, const glm::vec3& direction,
             const glm::vec3& refracted, const glm::vec3& normal, const glm::mat3& normal_jacobian,
             float eta) {
    if (!differential.valid) {
        return;
    }
    // D' = eta D - mu N with mu = eta (D . N) - (D' . N);
    // dD' = eta dD - (mu dN + dmu N), dmu = (eta - eta^2 (D . N) / (D' . N)) d(D . N).
    const float dn = glm::dot(direction, normal);
    const float dn_out = glm::dot(refracted, normal);
    if (!(std::abs(dn_out) > 1e-4f)) {
        differential.valid = false;  // grazing exit: the first order says nothing
        return;
    }
    const float mu = eta * dn - dn_out;
    const auto turn = [&](const glm::vec3& dp, glm::vec3& dd) {
        const glm::vec3 d_normal = normal_jacobian * dp;
        const float d_dn = glm::dot(dd, normal) + glm::dot(direction, d_normal);
        // The offset ray itself: does Snell's law still have a solution for it?
        const float cos_offset =
            -glm::dot(direction + dd, normal + d_normal) /
            std::max(glm::length(direction + dd) * glm::length(normal + d_normal), 1e-12f);
        if (eta * eta * (1.0f - cos_offset * cos_offset) >= 1.0f) {
            differential.valid = false;
            return;
        }
        const float d_mu = (eta - eta * eta * dn / dn_out) * d_dn;
        dd = eta * dd - (mu * d_normal + d_mu * normal);
    };
    turn(differential.dp_u, differential.dd_u);
    turn(differential.dp_v, differential.dd_v);
}

float footprint_area(const PhotonDifferential& differential) {
    if (!differential.valid || !finite(differential.dp_u) || !finite(differential.dp_v)) {
        return 0.0f;
    }
    const float area = glm::length(glm::cross(differential.dp_u, differential.dp_v));
    return std::isfinite(area) ? area : 0.0f;
}

}  // namespace luxel::lighting
