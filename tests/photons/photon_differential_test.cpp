// Photon differentials (docs/METHOD.md §7.4): the first-order footprint a caustic photon
// carries, checked against geometry worked out by hand (a point light's patch, a plane mirror's
// image) and against offset rays traced exactly through an analytic ball lens, not against
// the code under test; then end to end, the footprints of a glass sphere's caustic against the
// density of the photons around them.

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <vector>

#include <gtest/gtest.h>

#include "caustic_test_scenes.hpp"
#include "luxel/lighting/core/caustic_photons.hpp"
#include "luxel/lighting/core/photon_differential.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;

constexpr double kPi = 3.14159265358979323846;

TEST(PhotonDifferential, APointLightsPatchGrowsAsDistanceSquaredOverTheCosine) {
    const double share = 1e-4;  // steradians per photon
    const glm::vec3 down(0.0f, -1.0f, 0.0f);
    PhotonDifferential facing = emission_differential(down, 0.0, share);
    transfer(facing, down, 3.0f, {0.0f, 1.0f, 0.0f});
    EXPECT_NEAR(footprint_area(facing), share * 9.0, 1e-6 * 9.0);

    // The same ray on a plane tilted 60 degrees: the patch stretches by 1 / cos 60 = 2.
    PhotonDifferential tilted = emission_differential(down, 0.0, share);
    const float c = std::cos(static_cast<float>(kPi) / 3.0f);
    const float s = std::sin(static_cast<float>(kPi) / 3.0f);
    transfer(tilted, down, 3.0f, {s, c, 0.0f});
    EXPECT_NEAR(footprint_area(tilted), share * 9.0 * 2.0, 1e-5 * 18.0);

    // A beam (position offsets only) keeps its patch however far it goes.
    PhotonDifferential beam = emission_differential(down, 2e-4, 0.0);
    transfer(beam, down, 50.0f, {0.0f, 1.0f, 0.0f});
    EXPECT_NEAR(footprint_area(beam), 2e-4, 1e-9);

    // A ray along the plane says nothing.
    PhotonDifferential grazing = emission_differential(down, 0.0, share);
    transfer(grazing, down, 1.0f, {1.0f, 0.0f, 0.0f});
    EXPECT_FALSE(grazing.valid);
    EXPECT_EQ(footprint_area(grazing), 0.0f);
}

TEST(PhotonDifferential, APlaneMirrorsFootprintIsThatOfTheLightsMirrorImage) {
    // 1 m down at 45 degrees to a mirror at y = 0, then 2 m on to a plane facing the ray: the
    // image of the light is 3 m behind that plane along the ray.
    const double share = 4e-5;
    const glm::vec3 in = glm::normalize(glm::vec3(1.0f, -1.0f, 0.0f));
    const glm::vec3 up(0.0f, 1.0f, 0.0f);
    PhotonDifferential d = emission_differential(in, 0.0, share);
    transfer(d, in, 1.0f, up);
    reflect(d, in, up, glm::mat3(0.0f));
    const glm::vec3 out = in - 2.0f * glm::dot(in, up) * up;
    transfer(d, out, 2.0f, -out);
    EXPECT_NEAR(footprint_area(d), share * 9.0, 1e-4 * share * 9.0);
}

/// An exact ray through an exact glass sphere to the floor y = 0, refracting at both surfaces;
/// nullopt where it misses or is totally reflected.
std::optional<glm::dvec3> through_ball(glm::dvec3 origin, glm::dvec3 d, glm::dvec3 centre,
                                       double radius, double ior) {
    const auto hit_sphere = [&](glm::dvec3 o, glm::dvec3 dir,
                                bool inside) -> std::optional<double> {
        const glm::dvec3 oc = o - centre;
        const double b = glm::dot(oc, dir);
        const double disc = b * b - (glm::dot(oc, oc) - radius * radius);
        if (disc < 0.0) {
            return std::nullopt;
        }
        return inside ? -b + std::sqrt(disc) : -b - std::sqrt(disc);
    };
    const auto bend = [](glm::dvec3 dir, glm::dvec3 n, double eta) -> std::optional<glm::dvec3> {
        const double cos_i = -glm::dot(dir, n);
        const double k = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
        if (k < 0.0) {
            return std::nullopt;
        }
        return eta * dir + (eta * cos_i - std::sqrt(k)) * n;
    };
    const auto t_in = hit_sphere(origin, d, false);
    if (!t_in) {
        return std::nullopt;
    }
    const glm::dvec3 p_in = origin + *t_in * d;
    const auto d_in = bend(d, (p_in - centre) / radius, 1.0 / ior);
    if (!d_in) {
        return std::nullopt;
    }
    const glm::dvec3 p_out = p_in + *hit_sphere(p_in, *d_in, true) * *d_in;
    const auto d_out = bend(*d_in, -(p_out - centre) / radius, ior);
    if (!d_out) {
        return std::nullopt;
    }
    return p_out + (-p_out.y / d_out->y) * *d_out;
}

TEST(PhotonDifferential, ThroughABallLensItMatchesOffsetRaysTracedExactly) {
    // The sun straight down through a sphere of radius 0.5 at height 1: the curvature of the
    // normal, not the flat refraction, is what focuses the beam. A ray off the axis in both x
    // and z, so neither offset is special.
    const glm::dvec3 centre(0.0, 1.0, 0.0);
    const double radius = 0.5;
    const double ior = 1.5;
    const glm::dvec3 origin(0.13, 3.0, -0.21);
    const glm::dvec3 down(0.0, -1.0, 0.0);
    const double share = 1e-6;  // m^2 of the beam per photon

    // The differential, interface by interface, with the exact sphere's normal and its
    // derivative (I - N N^T) / R (negated for the inward-facing normal on the way out).
    const glm::dvec3 oc = origin - centre;
    const double b = glm::dot(oc, down);
    const double t_in = -b - std::sqrt(b * b - (glm::dot(oc, oc) - radius * radius));
    const glm::dvec3 p_in = origin + t_in * down;
    const glm::vec3 n_in((p_in - centre) / radius);
    const glm::mat3 j_in = (glm::mat3(1.0f) - glm::outerProduct(n_in, n_in)) / float(radius);
    PhotonDifferential d = emission_differential(glm::vec3(down), share, 0.0);
    const glm::vec3 tangent_u = d.dp_u / glm::length(d.dp_u);
    const glm::vec3 tangent_v = d.dp_v / glm::length(d.dp_v);
    transfer(d, glm::vec3(down), float(t_in), n_in);
    const glm::vec3 in_dir = glm::vec3(down);
    const float cos_i = -glm::dot(in_dir, n_in);
    const float eta = float(1.0 / ior);
    const glm::vec3 d_in = glm::normalize(
        eta * in_dir + (eta * cos_i - std::sqrt(1.0f - eta * eta * (1.0f - cos_i * cos_i))) * n_in);
    refract(d, in_dir, d_in, n_in, j_in, eta);
    const glm::dvec3 oc2 = p_in - centre;
    const double b2 = glm::dot(oc2, glm::dvec3(d_in));
    const double t_mid = -b2 + std::sqrt(b2 * b2 - (glm::dot(oc2, oc2) - radius * radius));
    const glm::dvec3 p_out = p_in + t_mid * glm::dvec3(d_in);
    const glm::vec3 n_out(-(p_out - centre) / radius);
    transfer(d, d_in, float(t_mid), n_out);
    const glm::mat3 j_out = -(glm::mat3(1.0f) - glm::outerProduct(n_out, n_out)) / float(radius);
    const float cos_o = -glm::dot(d_in, n_out);
    const float eta_out = float(ior);
    const glm::vec3 d_out = glm::normalize(
        eta_out * d_in +
        (eta_out * cos_o - std::sqrt(1.0f - eta_out * eta_out * (1.0f - cos_o * cos_o))) * n_out);
    refract(d, d_in, d_out, n_out, j_out, eta_out);
    const double t_floor = -p_out.y / double(d_out.y);
    transfer(d, d_out, float(t_floor), {0.0f, 1.0f, 0.0f});
    ASSERT_TRUE(d.valid);

    // Offset rays, exactly: central differences of the landing point per unit offset.
    const double step = std::sqrt(share) * 1e-2;
    const auto landing_change = [&](const glm::vec3& tangent) {
        const glm::dvec3 t(tangent);
        const auto plus = through_ball(origin + step * t, down, centre, radius, ior);
        const auto minus = through_ball(origin - step * t, down, centre, radius, ior);
        return (*plus - *minus) / (2.0 * step) * std::sqrt(share);
    };
    const glm::dvec3 exact_u = landing_change(tangent_u);
    const glm::dvec3 exact_v = landing_change(tangent_v);
    EXPECT_LT(glm::length(glm::dvec3(d.dp_u) - exact_u), 1e-3 * glm::length(exact_u));
    EXPECT_LT(glm::length(glm::dvec3(d.dp_v) - exact_v), 1e-3 * glm::length(exact_v));
    // The lens focuses: the patch on the floor is smaller than the beam's.
    EXPECT_LT(footprint_area(d), 0.5 * share);
}

TEST(PhotonDifferential, ATessellatedSpheresNormalTurnsAsTheSphereDoes) {
    RayScene scene;
    const glm::vec3 centre(0.0f, 1.0f, 0.0f);
    const float radius = 0.5f;
    scene.add_object(luxel::testing::sphere_mesh(centre, radius, 96, 48, 0), glm::mat4(1.0f),
                     false);
    scene.commit();
    const glm::vec3 origin(0.17f, 3.0f, 0.09f);
    const auto hit = scene.intersect(origin, {0.0f, -1.0f, 0.0f});
    ASSERT_TRUE(hit);
    const glm::mat3 jacobian = shading_normal_jacobian(scene, *hit);
    // On a sphere the unit normal moves by d / R for a tangent displacement d.
    const glm::vec3 n = hit->shading_normal;
    const glm::vec3 t = glm::normalize(glm::cross(n, glm::vec3(1.0f, 0.0f, 0.0f)));
    const glm::vec3 turned = jacobian * t;
    EXPECT_NEAR(glm::dot(turned, t), 1.0f / radius, 0.05f / radius);
    EXPECT_NEAR(glm::dot(turned, n), 0.0f, 1e-4f) << "a unit normal turns, it does not grow";

    // A flat quad without vertex normals does not turn.
    RayScene flat;
    flat.add_object(luxel::testing::quad_mesh({-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, 0, 0),
                    glm::mat4(1.0f), false);
    flat.commit();
    const auto floor_hit = flat.intersect({0.0f, 1.0f, 0.0f}, {0.0f, -1.0f, 0.0f});
    ASSERT_TRUE(floor_hit);
    EXPECT_EQ(shading_normal_jacobian(flat, *floor_hit), glm::mat3(0.0f));
}

TEST(PhotonDifferential, AGlassSpheresPhotonsFootprintsTileTheCaustic) {
    // Each photon's footprint stands for its share of the caustic: around a photon of
    // footprint radius r, a disc of radius 2 r holds about four photons of its generation.
    RayScene scene;
    const std::vector<TraceMaterial> materials = {
        {Scattering::Diffuse, glm::vec3(0.5f), glm::vec3(1.0f), 1.5f},
        {Scattering::Dielectric, glm::vec3(0.0f), glm::vec3(1.0f), 1.5f}};
    scene.add_object(luxel::testing::quad_mesh({-10, 0, 10}, {20, 0, 0}, {0, 0, -20}, 0, 0),
                     glm::mat4(1.0f), false);
    const glm::vec3 centre(0.0f, 1.0f, 0.0f);
    scene.add_object(luxel::testing::sphere_mesh(centre, 0.5f, 96, 48, 1), glm::mat4(1.0f), false);
    scene.commit();
    LightSource light;
    light.position = {0.3f, 3.0f, 0.2f};
    light.power = glm::vec3(100.0f);
    const glm::vec3 lo = scene.bounds_min();
    const glm::vec3 hi = scene.bounds_max();
    CausticPhotonList list(40'000, 8, 9);
    list.set_emitter(
        CausticEmitter(light, {centre, 0.5f}, {0.5f * (lo + hi), 0.5f * glm::length(hi - lo)}));
    JobSystem jobs(2);
    for (std::uint32_t k = 0; k < list.slice_count(); ++k) {
        (void)list.retrace_slice(scene, materials, k, 16, jobs);
    }
    std::vector<CausticPhoton> photons;
    for (std::uint32_t k = 0; k < list.slice_count(); ++k) {
        photons.insert(photons.end(), list.slice(k).begin(), list.slice(k).end());
    }
    ASSERT_GT(photons.size(), 30'000u);
    const auto known = std::count_if(photons.begin(), photons.end(),
                                     [](const CausticPhoton& p) { return p.footprint != 0; });
    EXPECT_GT(static_cast<double>(known), 0.95 * static_cast<double>(photons.size()));

    std::vector<double> ratios;
    for (std::size_t i = 0; i < photons.size(); i += 97) {
        const float r = decode_footprint_radius(photons[i].footprint);
        if (r <= 0.0f) {
            continue;
        }
        const float reach2 = 4.0f * r * r;
        int around = 0;
        for (const CausticPhoton& other : photons) {
            const glm::vec3 d = other.position - photons[i].position;
            around += glm::dot(d, d) < reach2 ? 1 : 0;
        }
        ratios.push_back(around / 4.0);
    }
    ASSERT_GT(ratios.size(), 300u);
    std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
    const double median = ratios[ratios.size() / 2];
    std::printf("[ figures  ] photons within 2 footprint radii, over the 4 expected: median %.2f\n",
                median);
    EXPECT_GT(median, 0.5);
    EXPECT_LT(median, 2.0);
}

TEST(PhotonDifferential, FootprintRadiiKeepTheirSizeThroughTheirEightBits) {
    for (const float r : {1e-4f, 3.7e-4f, 2e-3f, 0.01f, 0.05f, 1.0f, 5.0f}) {
        const std::uint32_t code = encode_footprint_radius(r);
        ASSERT_GE(code, 1u);
        ASSERT_LE(code, 255u);
        EXPECT_NEAR(decode_footprint_radius(code), r, 0.022f * r) << r;
    }
    EXPECT_EQ(encode_footprint_radius(0.0f), 0u);
    EXPECT_EQ(encode_footprint_radius(-1.0f), 0u);
    EXPECT_EQ(encode_footprint_radius(std::nanf("")), 0u);
    EXPECT_EQ(encode_footprint_radius(INFINITY), 0u);
    EXPECT_EQ(encode_footprint_radius(1e-9f), 1u) << "below the range: its smallest radius";
    EXPECT_EQ(encode_footprint_radius(1e3f), 255u) << "above it: its largest";
    EXPECT_EQ(decode_footprint_radius(0), 0.0f);
}

TEST(PhotonDifferential, SurfaceAndFootprintShareTheWordTheShadersSplit) {
    // shaders/caustics/caustic_interface.h reads the surface from bits 0-23 (sign-extended)
    // and the footprint from bits 24-31 of the word after the position.
    CausticPhoton photon;
    photon.surface = -1;
    photon.footprint = 0xABu;
    std::uint32_t word = 0;
    std::memcpy(&word, reinterpret_cast<const unsigned char*>(&photon) + sizeof(glm::vec3),
                sizeof(word));
    EXPECT_EQ(word, 0xABFFFFFFu);
    photon.surface = kMaxCausticSurface;
    photon.footprint = 1u;
    std::memcpy(&word, reinterpret_cast<const unsigned char*>(&photon) + sizeof(glm::vec3),
                sizeof(word));
    EXPECT_EQ(word, 0x017FFFFFu);
    EXPECT_EQ(photon.surface, kMaxCausticSurface);
}

}  // namespace
