// Caustic photons: emission toward generators, specular transport, storage at the first
// diffuse hit, and the slice schedule. Energies are checked against independent integrations
// (an analytic sphere tracer and quadratures over the mirror), not against the code under test.

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <set>
#include <span>
#include <vector>

#include <gtest/gtest.h>

#include "caustic_test_scenes.hpp"
#include "luxel/lighting/core/caustic_photons.hpp"
#include "luxel/lighting/core/halton.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;

constexpr double kPi = 3.14159265358979323846;
constexpr std::uint32_t kMaxSpecular = 16;

/// A ray scene with its material table, as the caustic tracer takes them.
struct CausticWorld {
    RayScene scene;
    std::vector<TraceMaterial> materials;

    [[nodiscard]] BoundingSphere bounds() const {
        const glm::vec3 lo = scene.bounds_min();
        const glm::vec3 hi = scene.bounds_max();
        return {0.5f * (lo + hi), 0.5f * glm::length(hi - lo)};
    }
};

CausticTraceCounters trace_every_slice(const CausticWorld& world, CausticPhotonList& list,
                                       JobSystem& jobs) {
    CausticTraceCounters sum;
    for (std::uint32_t k = 0; k < list.slice_count(); ++k) {
        sum += list.retrace_slice(world.scene, world.materials, k, kMaxSpecular, jobs);
    }
    return sum;
}

std::vector<CausticPhoton> all_photons(const CausticPhotonList& list) {
    std::vector<CausticPhoton> photons;
    for (std::uint32_t k = 0; k < list.slice_count(); ++k) {
        photons.insert(photons.end(), list.slice(k).begin(), list.slice(k).end());
    }
    return photons;
}

/// Every photon of a list as the emitter makes it (not traced).
std::vector<EmittedPhoton> emitted_photons(const CausticPhotonList& list) {
    std::vector<EmittedPhoton> photons;
    for (std::uint32_t j = 0; j < list.photon_count(); ++j) {
        const std::uint64_t index = list.sample_index(j);
        photons.push_back(list.emitter().emit(
            {photon_sample(index, 0, list.seed()), photon_sample(index, 1, list.seed())},
            {photon_sample(index, 2, list.seed()), photon_sample(index, 3, list.seed())},
            list.photon_count()));
    }
    return photons;
}

/// A stored photon and its direction of travel on arrival, which the photon does not keep.
struct DirectedPhoton {
    CausticPhoton photon;
    glm::vec3 incident{0.0f};
};

/// The list's first generation traced one photon at a time as retrace_slice traces it, with
/// each stored photon's incident direction.
std::vector<DirectedPhoton> directed_photons(const CausticWorld& world,
                                             const CausticPhotonList& list) {
    std::vector<DirectedPhoton> out;
    CausticTraceCounters counters;
    for (std::uint32_t j = 0; j < list.photon_count(); ++j) {
        const std::uint64_t index = list.sample_index(j);
        const EmittedPhoton emitted = list.emitter().emit(
            {photon_sample(index, 0, list.seed()), photon_sample(index, 1, list.seed())},
            {photon_sample(index, 2, list.seed()), photon_sample(index, 3, list.seed())},
            list.photon_count());
        if (!(emitted.power.r > 0.0f || emitted.power.g > 0.0f || emitted.power.b > 0.0f)) {
            continue;
        }
        DirectedPhoton directed;
        const std::optional<CausticPhoton> photon =
            trace_caustic_photon(world.scene, world.materials, emitted,
                                 list.emitter().differential(emitted, list.photon_count()), index,
                                 list.seed(), kMaxSpecular, counters, nullptr, &directed.incident);
        if (photon) {
            directed.photon = *photon;
            out.push_back(directed);
        }
    }
    return out;
}

double smoothstep(double edge0, double edge1, double x) {
    const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

/// An orthonormal frame around a unit axis (the test's own, not the engine's).
void frame_around(const glm::dvec3& axis, glm::dvec3& x, glm::dvec3& y) {
    const glm::dvec3 helper = std::abs(axis.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    x = glm::normalize(glm::cross(helper, axis));
    y = glm::cross(axis, x);
}

TEST(CausticEmission, PointPhotonsCarryIntensityTimesTheConeSolidAngle) {
    LightSource light;
    light.kind = LightKind::Point;
    light.position = {0.1f, 3.0f, -0.2f};
    light.power = glm::vec3(static_cast<float>(4.0 * kPi * 10.0));  // I = 10 W/sr
    const BoundingSphere generator{{0.5f, 1.0f, 0.2f}, 0.5f};
    CausticPhotonList list(10'000, 8, 3);
    list.set_emitter(CausticEmitter(light, generator, {}));
    ASSERT_TRUE(list.emitter().reaches_generator());

    const double distance = glm::length(glm::dvec3(generator.centre - light.position));
    const double cos_half = std::sqrt(1.0 - 0.25 / (distance * distance));
    const double solid_angle = 2.0 * kPi * (1.0 - cos_half);
    double total = 0.0;
    double widest = 1.0;
    for (const EmittedPhoton& photon : emitted_photons(list)) {
        total += static_cast<double>(photon.power.r);
        // Every photon aims at the sphere: its line passes within the radius of the centre.
        const glm::dvec3 to_centre = glm::dvec3(generator.centre - photon.origin);
        const double along = glm::dot(to_centre, glm::dvec3(photon.direction));
        const double miss =
            std::sqrt(std::max(0.0, glm::dot(to_centre, to_centre) - along * along));
        EXPECT_LE(miss, 0.5 * (1.0 + 1e-4));
        widest = std::min(widest, along / distance);
    }
    EXPECT_NEAR(total, 10.0 * solid_angle, 10.0 * solid_angle * 1e-5);
    EXPECT_LT(widest, cos_half + 0.02 * (1.0 - cos_half));  // and the cone is filled to its rim
}

/// The summed red power of every photon a list's emitter makes.
double emitted_power(const CausticPhotonList& list) {
    double total = 0.0;
    for (const EmittedPhoton& photon : emitted_photons(list)) {
        total += static_cast<double>(photon.power.r);
    }
    return total;
}

TEST(CausticEmission, OverlappingConesOfOneLightCountItsLightOnce) {
    // A point light with a near generator A and a far one B wholly inside A's cone: the two
    // pairs sample B's cone twice. With their siblings each sample carries half there, so the
    // pairs together carry I * Omega_A, the light toward the union of the two cones, not
    // I * (Omega_A + Omega_B).
    LightSource light;
    light.kind = LightKind::Point;
    light.position = {0.0f, 3.0f, 0.0f};
    light.power = glm::vec3(static_cast<float>(4.0 * kPi * 10.0));  // I = 10 W/sr
    const BoundingSphere near_sphere{{0.0f, 2.0f, 0.0f}, 0.4f};
    const BoundingSphere far_sphere{{0.05f, 0.0f, 0.0f}, 0.6f};
    const auto solid_angle = [&](const BoundingSphere& sphere) {
        const double d = glm::length(glm::dvec3(sphere.centre - light.position));
        const double r = sphere.radius;
        return 2.0 * kPi * (1.0 - std::sqrt(d * d - r * r) / d);
    };
    ASSERT_LT(solid_angle(far_sphere), solid_angle(near_sphere));
    CausticPhotonList near_list(40'000, 8, 3);
    CausticPhotonList far_list(40'000, 8, 5);
    CausticEmitter near_emitter(light, near_sphere, {});
    CausticEmitter far_emitter(light, far_sphere, {});
    near_list.set_emitter(near_emitter);
    far_list.set_emitter(far_emitter);
    const double alone = emitted_power(near_list) + emitted_power(far_list);
    EXPECT_NEAR(alone, 10.0 * (solid_angle(near_sphere) + solid_angle(far_sphere)), 1e-3 * alone)
        << "without siblings the overlap counts twice";
    near_emitter.set_siblings({far_sphere});
    far_emitter.set_siblings({near_sphere});
    near_list.set_emitter(near_emitter);
    far_list.set_emitter(far_emitter);
    for (const EmittedPhoton& photon : emitted_photons(far_list)) {
        EXPECT_NEAR(photon.power.r, 0.5f * 10.0f * solid_angle(far_sphere) / 40'000.0, 1e-9)
            << "every ray toward B also goes toward A";
    }
    const double shared = emitted_power(near_list) + emitted_power(far_list);
    EXPECT_NEAR(shared, 10.0 * solid_angle(near_sphere), 0.005 * shared);
}

TEST(CausticEmission, OverlappingBeamsOfTheSunCountTheirDiscsUnionOnce) {
    // Two spheres of radius r whose discs, seen from the sun, overlap with their centres d
    // apart: the beams together carry E times the area of the union of the two discs.
    LightSource sun;
    sun.kind = LightKind::Directional;
    sun.direction = glm::normalize(glm::vec3(0.2f, -1.0f, 0.1f));
    sun.power = glm::vec3(3.0f);  // E = 3 W/m^2
    const float r = 0.5f;
    const glm::vec3 across = glm::normalize(glm::cross(sun.direction, glm::vec3(1, 0, 0)));
    const BoundingSphere a{{0.0f, 0.5f, 0.0f}, r};
    // 0.6 m across the beam and 1 m along it: the discs overlap, the spheres do not.
    const BoundingSphere b{a.centre + 0.6f * across - 1.0f * sun.direction, r};
    const BoundingSphere scene{{0.0f, 0.0f, 0.0f}, 5.0f};
    CausticEmitter to_a(sun, a, scene);
    CausticEmitter to_b(sun, b, scene);
    to_a.set_siblings({b});
    to_b.set_siblings({a});
    CausticPhotonList list_a(40'000, 8, 7);
    CausticPhotonList list_b(40'000, 8, 9);
    list_a.set_emitter(to_a);
    list_b.set_emitter(to_b);
    const double d = 0.6;
    const double rr = r;
    const double lens =
        2.0 * rr * rr * std::acos(d / (2.0 * rr)) - 0.5 * d * std::sqrt(4.0 * rr * rr - d * d);
    const double union_area = 2.0 * kPi * rr * rr - lens;
    const double total = emitted_power(list_a) + emitted_power(list_b);
    EXPECT_NEAR(total, 3.0 * union_area, 0.005 * 3.0 * union_area);
}

TEST(CausticEmission, SlicesAreDisjointRunsOfTheSequenceThatEachCoverTheCone) {
    CausticPhotonList list(10'001, 8, 1);  // not a multiple of K on purpose
    std::set<std::uint64_t> indices;
    std::uint32_t counted = 0;
    for (std::uint32_t k = 0; k < 8; ++k) {
        counted += list.slice_size(k);
        double lo = 1.0;
        double hi = 0.0;
        for (std::uint32_t j = k; j < list.photon_count(); j += 8) {
            indices.insert(list.sample_index(j));
            // Base 2 picks cos theta in the cone: each slice must span it, not one band.
            lo = std::min(lo, radical_inverse(2, list.sample_index(j)));
            hi = std::max(hi, radical_inverse(2, list.sample_index(j)));
        }
        EXPECT_LT(lo, 0.01) << "slice " << k;
        EXPECT_GT(hi, 0.99) << "slice " << k;
    }
    EXPECT_EQ(counted, 10'001u);
    EXPECT_EQ(indices.size(), 10'001u);  // every photon its own Halton point
}

TEST(CausticEmission, SpotsAreClippedToTheirConeAndApplyTheirFalloff) {
    LightSource spot;
    spot.kind = LightKind::Spot;
    spot.position = {0.0f, 3.0f, 0.0f};
    spot.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.0f));
    spot.inner_cone = 0.15f;
    spot.outer_cone = 0.25f;
    spot.power = glm::vec3(20.0f);
    const BoundingSphere generator{{0.5f, 1.0f, 0.2f}, 0.5f};
    CausticPhotonList list(20'000, 8, 5);
    list.set_emitter(CausticEmitter(spot, generator, {}));
    ASSERT_TRUE(list.emitter().reaches_generator());
    double total = 0.0;
    for (const EmittedPhoton& photon : emitted_photons(list)) {
        total += static_cast<double>(photon.power.g);
    }
    // Independent: a midpoint quadrature of I0 * falloff over the generator's cone.
    const glm::dvec3 to_centre = glm::dvec3(generator.centre - spot.position);
    const glm::dvec3 axis = glm::normalize(to_centre);
    const double cos_half = std::sqrt(1.0 - 0.25 / glm::dot(to_centre, to_centre));
    glm::dvec3 x;
    glm::dvec3 y;
    frame_around(axis, x, y);
    const double intensity = 20.0 / (2.0 * kPi * (1.0 - std::cos(0.25)));
    const int steps = 1000;
    double expected = 0.0;
    for (int i = 0; i < steps; ++i) {
        const double cos_theta = 1.0 - (i + 0.5) / steps * (1.0 - cos_half);
        const double sin_theta = std::sqrt(1.0 - cos_theta * cos_theta);
        for (int k = 0; k < steps; ++k) {
            const double phi = 2.0 * kPi * (k + 0.5) / steps;
            const glm::dvec3 w =
                sin_theta * (std::cos(phi) * x + std::sin(phi) * y) + cos_theta * axis;
            expected +=
                smoothstep(std::cos(0.25), std::cos(0.15), glm::dot(w, glm::dvec3(spot.direction)));
        }
    }
    expected *= intensity * 2.0 * kPi * (1.0 - cos_half) / (double(steps) * steps);
    ASSERT_GT(expected, 0.0);
    EXPECT_NEAR(total, expected, expected * 0.002);
    // The clip matters here: the unclipped cone would carry far more.
    EXPECT_LT(total, 0.8 * intensity * 2.0 * kPi * (1.0 - cos_half));

    // A narrow spot inside the generator's cone: its own cone is sampled, none wasted.
    spot.direction = glm::vec3(axis);
    spot.outer_cone = 0.05f;
    spot.inner_cone = 0.05f;
    const CausticEmitter narrow(spot, generator, {});
    EXPECT_NEAR(narrow.cone().cos_half_angle, std::cos(0.05), 1e-6);
    // Aimed away from the generator: nothing to emit.
    spot.direction = glm::vec3(0.0f, 1.0f, 0.0f);
    EXPECT_FALSE(CausticEmitter(spot, generator, {}).reaches_generator());
}

TEST(CausticPhotonStorage, LightMapUvsSurviveTheFixedPointEncoding) {
    double worst = 0.0;
    for (std::uint64_t i = 1; i <= 20'000; ++i) {
        const glm::vec2 uv(static_cast<float>(radical_inverse(2, i)),
                           static_cast<float>(radical_inverse(3, i)));
        const glm::vec2 back = decode_lightmap_uv(encode_lightmap_uv(uv));
        worst = std::max(worst, static_cast<double>(glm::length(back - uv)));
    }
    // Half a step of 1/65535 per axis.
    EXPECT_LT(worst, 0.5 * std::sqrt(2.0) / 65535.0 + 1e-7);
    EXPECT_EQ(decode_lightmap_uv(encode_lightmap_uv({1.0f, 0.0f})), glm::vec2(1.0f, 0.0f));
    // Out of range and NaN clamp into the page.
    EXPECT_EQ(decode_lightmap_uv(encode_lightmap_uv({-0.5f, 2.0f})), glm::vec2(0.0f, 1.0f));
    EXPECT_EQ(decode_lightmap_uv(encode_lightmap_uv({std::nanf(""), 0.0f})), glm::vec2(0.0f));
    // u in the low half, as GLSL's unpackUnorm2x16 reads it.
    EXPECT_EQ(encode_lightmap_uv({1.0f, 0.0f}), 0xFFFFu);
    EXPECT_EQ(sizeof(CausticPhoton), 32u);
}

TEST(CausticPhotonStorage, AStoredPhotonKeepsTheLightMapUvOfItsHit) {
    // A mirror over a 20 x 20 m floor whose light map spans it linearly: every stored photon's
    // UV must be the floor's UV at its position.
    CausticWorld world;
    world.materials = {{Scattering::Diffuse, glm::vec3(0.5f), glm::vec3(1.0f), 1.5f},
                       {Scattering::Mirror, glm::vec3(0.0f), glm::vec3(0.8f), 1.5f}};
    TriangleMesh floor = luxel::testing::quad_mesh({-10, 0, 10}, {20, 0, 0}, {0, 0, -20}, 0, 0);
    floor.lightmap_uvs = {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}};
    world.scene.add_object(floor, glm::mat4(1.0f), false);
    const TriangleMesh mirror =
        luxel::testing::quad_mesh({0.0f, 0.4f, 0.5f}, {0, 0, -1}, {0, 1, 0}, -1, 1);
    world.scene.add_object(mirror, glm::mat4(1.0f), false);
    world.scene.commit();
    LightSource light;
    light.position = {0.8f, 1.2f, 0.15f};
    light.power = glm::vec3(10.0f);
    CausticPhotonList list(4'000, 8, 2);
    list.set_emitter(
        CausticEmitter(light, luxel::testing::bounding_sphere(mirror), world.bounds()));
    JobSystem jobs(2);
    trace_every_slice(world, list, jobs);
    const std::vector<CausticPhoton> photons = all_photons(list);
    ASSERT_GT(photons.size(), 400u);
    double worst = 0.0;
    glm::vec2 lo(1.0f);
    glm::vec2 hi(0.0f);
    for (const CausticPhoton& photon : photons) {
        ASSERT_EQ(photon.surface, 0);
        const glm::vec2 expected((photon.position.x + 10.0f) / 20.0f,
                                 (10.0f - photon.position.z) / 20.0f);
        worst = std::max(worst, static_cast<double>(glm::length(photon.lightmap_uv() - expected)));
        lo = glm::min(lo, photon.lightmap_uv());
        hi = glm::max(hi, photon.lightmap_uv());
    }
    EXPECT_LT(worst, 1e-4);
    // The photons spread over the floor's light map, not onto one texel.
    EXPECT_GT(hi.x - lo.x, 0.01f);
    EXPECT_GT(hi.y - lo.y, 0.01f);
}

// --- A glass sphere over a floor, against an analytic sphere tracer --------------------------

struct AnalyticGlassSphere {
    glm::dvec3 centre;
    double radius;
    double ior;
};

double fresnel_unpolarised(double cos_i, double eta_from, double eta_to) {
    const double sin_t = eta_from / eta_to * std::sqrt(std::max(0.0, 1.0 - cos_i * cos_i));
    if (sin_t >= 1.0) {
        return 1.0;
    }
    const double cos_t = std::sqrt(1.0 - sin_t * sin_t);
    const double rs = (eta_from * cos_i - eta_to * cos_t) / (eta_from * cos_i + eta_to * cos_t);
    const double rp = (eta_to * cos_i - eta_from * cos_t) / (eta_to * cos_i + eta_from * cos_t);
    return 0.5 * (rs * rs + rp * rp);
}

/// Follows a ray through an exact sphere, splitting at every interface into its reflected and
/// refracted parts, and adds to `floor` the power that reaches the plane y = 0 (|x|, |z| <= 10)
/// after at least one specular interaction.
void split_trace(const AnalyticGlassSphere& sphere, glm::dvec3 origin, glm::dvec3 d, double power,
                 bool inside, std::uint32_t specular, double& floor) {
    if (power < 1e-12 || specular > kMaxSpecular) {
        return;
    }
    const glm::dvec3 oc = origin - sphere.centre;
    const double b = glm::dot(oc, d);
    const double disc = b * b - (glm::dot(oc, oc) - sphere.radius * sphere.radius);
    const double t = disc < 0.0 ? -1.0 : (inside ? -b + std::sqrt(disc) : -b - std::sqrt(disc));
    if (!(t > 1e-9)) {
        if (!inside && specular > 0 && d.y < 0.0) {
            const glm::dvec3 p = origin + (-origin.y / d.y) * d;
            if (std::abs(p.x) <= 10.0 && std::abs(p.z) <= 10.0) {
                floor += power;
            }
        }
        return;
    }
    const glm::dvec3 p = origin + t * d;
    const glm::dvec3 outward = (p - sphere.centre) / sphere.radius;
    const glm::dvec3 n = inside ? -outward : outward;  // facing the arriving ray
    const double cos_i = -glm::dot(d, n);
    const double eta_from = inside ? sphere.ior : 1.0;
    const double eta_to = inside ? 1.0 : sphere.ior;
    const double reflectance = fresnel_unpolarised(cos_i, eta_from, eta_to);
    split_trace(sphere, p, d + 2.0 * cos_i * n, power * reflectance, inside, specular + 1, floor);
    if (reflectance < 1.0) {
        const double eta = eta_from / eta_to;
        const double cos_t = std::sqrt(1.0 - eta * eta * (1.0 - cos_i * cos_i));
        const glm::dvec3 refracted = glm::normalize(eta * d + (eta * cos_i - cos_t) * n);
        split_trace(sphere, p, refracted, power * (1.0 - reflectance), !inside, specular + 1,
                    floor);
    }
}

TEST(CausticEnergy, AGlassSphereDeliversWhatAnAnalyticSphereTracerPredicts) {
    CausticWorld world;
    world.materials = {{Scattering::Diffuse, glm::vec3(0.5f), glm::vec3(1.0f), 1.5f},
                       {Scattering::Dielectric, glm::vec3(0.0f), glm::vec3(1.0f), 1.5f}};
    world.scene.add_object(luxel::testing::quad_mesh({-10, 0, 10}, {20, 0, 0}, {0, 0, -20}, 0, 0),
                           glm::mat4(1.0f), false);
    const glm::vec3 centre(0.0f, 1.0f, 0.0f);
    world.scene.add_object(luxel::testing::sphere_mesh(centre, 0.5f, 96, 48, 1), glm::mat4(1.0f),
                           false);
    world.scene.commit();
    LightSource light;
    light.position = {0.3f, 3.0f, 0.2f};
    light.power = glm::vec3(static_cast<float>(4.0 * kPi * 10.0));  // I = 10 W/sr
    const BoundingSphere generator{centre, 0.5f};
    CausticPhotonList list(40'000, 8, 9);
    list.set_emitter(CausticEmitter(light, generator, world.bounds()));
    JobSystem jobs(2);
    const CausticTraceCounters counters = trace_every_slice(world, list, jobs);
    EXPECT_EQ(counters.photons, 40'000u);
    EXPECT_GT(counters.stored, 30'000u);
    const double stored = list.stored_power().r;

    // Independent estimate: the exact sphere, Fresnel split at every interface, over a midpoint
    // grid of the same cone.
    const AnalyticGlassSphere sphere{glm::dvec3(centre), 0.5, 1.5};
    const glm::dvec3 apex(light.position);
    const glm::dvec3 to_centre = sphere.centre - apex;
    const glm::dvec3 axis = glm::normalize(to_centre);
    const double cos_half = std::sqrt(1.0 - 0.25 / glm::dot(to_centre, to_centre));
    const double cone_power = 10.0 * 2.0 * kPi * (1.0 - cos_half);
    glm::dvec3 x;
    glm::dvec3 y;
    frame_around(axis, x, y);
    const int steps = 300;
    double floor = 0.0;
    for (int i = 0; i < steps; ++i) {
        const double cos_theta = 1.0 - (i + 0.5) / steps * (1.0 - cos_half);
        const double sin_theta = std::sqrt(1.0 - cos_theta * cos_theta);
        for (int k = 0; k < steps; ++k) {
            const double phi = 2.0 * kPi * (k + 0.5) / steps;
            split_trace(sphere, apex,
                        sin_theta * (std::cos(phi) * x + std::sin(phi) * y) + cos_theta * axis, 1.0,
                        false, 0, floor);
        }
    }
    const double expected = cone_power * floor / (double(steps) * steps);
    // Fresnel matters: a good part of the cone's power is reflected away from the floor.
    EXPECT_LT(expected, 0.95 * cone_power);
    EXPECT_GT(expected, 0.5 * cone_power);
    // The tessellated sphere (96 x 48, smooth normals) against the exact one.
    EXPECT_NEAR(stored, expected, expected * 0.0075)
        << "stored " << stored << " W, analytic " << expected << " W of " << cone_power << " W";
}

// --- A plane mirror: the patch on the floor comes from the light's mirror image -------------

/// A 1 x 1 m mirror in the plane x = 0 (y in [0.4, 1.4], z in [-0.5, 0.5]) facing +x, above a
/// 20 x 20 m floor at y = 0.
struct MirrorWorld : CausticWorld {
    static constexpr float kF0 = 0.8f;
    BoundingSphere mirror_sphere;

    MirrorWorld() {
        materials = {{Scattering::Diffuse, glm::vec3(0.5f), glm::vec3(1.0f), 1.5f},
                     {Scattering::Mirror, glm::vec3(0.0f), glm::vec3(kF0), 1.5f}};
        scene.add_object(luxel::testing::quad_mesh({-10, 0, 10}, {20, 0, 0}, {0, 0, -20}, 0, 0),
                         glm::mat4(1.0f), false);
        const TriangleMesh mirror =
            luxel::testing::quad_mesh({0.0f, 0.4f, 0.5f}, {0, 0, -1}, {0, 1, 0}, -1, 1);
        mirror_sphere = luxel::testing::bounding_sphere(mirror);
        scene.add_object(mirror, glm::mat4(1.0f), false);
        scene.commit();
    }

    /// Power reflected onto the floor, by a midpoint quadrature over the mirror of the
    /// irradiance `incident(m)` -> (direction of travel, W/m^2 across it) times Schlick's F.
    template <class Incident>
    static double reflected_to_floor(Incident&& incident, int steps) {
        double total = 0.0;
        const double cell = 1.0 / (double(steps) * steps);
        for (int i = 0; i < steps; ++i) {
            for (int k = 0; k < steps; ++k) {
                const glm::dvec3 m(0.0, 0.4 + (i + 0.5) / steps, -0.5 + (k + 0.5) / steps);
                const auto [w, irradiance_normal] = incident(m);
                const double cos_m = -w.x;  // the mirror's normal is +x
                if (!(cos_m > 0.0) || w.y >= 0.0) {
                    continue;  // from behind, or reflected upwards (reflection keeps w.y)
                }
                // Reflected (x flips), it must land on the 20 x 20 m floor: a photon leaving
                // near the light's height travels far before it comes down.
                const glm::dvec3 floor_hit = m + (m.y / -w.y) * glm::dvec3(-w.x, w.y, w.z);
                if (std::abs(floor_hit.x) > 10.0 || std::abs(floor_hit.z) > 10.0) {
                    continue;
                }
                const double f = kF0 + (1.0 - kF0) * std::pow(1.0 - cos_m, 5.0);
                total += irradiance_normal * cos_m * f * cell;
            }
        }
        return total;
    }
};

TEST(CausticMirror, APointLightsPatchComesFromItsMirrorImageWithTheRightPower) {
    MirrorWorld world;
    LightSource light;
    light.position = {0.8f, 1.2f, 0.15f};
    light.power = glm::vec3(static_cast<float>(4.0 * kPi * 10.0));  // I = 10 W/sr
    CausticPhotonList list(20'000, 8, 2);
    list.set_emitter(CausticEmitter(light, world.mirror_sphere, world.bounds()));
    JobSystem jobs(2);
    const CausticTraceCounters counters = trace_every_slice(world, list, jobs);
    // The cone around the mirror's sphere also reaches the floor directly: dropped.
    EXPECT_GT(counters.direct_diffuse, 1000u);
    const std::vector<CausticPhoton> photons = all_photons(list);
    ASSERT_GT(photons.size(), 2000u);

    // Traced back along its incident direction, every photon comes from the mirror image of
    // the light; the least-squares meeting point of all those lines is the image.
    const glm::dvec3 image(-0.8, 1.2, 0.15);
    glm::dmat3 normal_matrix(0.0);
    glm::dvec3 rhs(0.0);
    double worst_miss = 0.0;
    const std::vector<DirectedPhoton> directed = directed_photons(world, list);
    EXPECT_EQ(directed.size(), photons.size());
    for (const auto& [photon, incident] : directed) {
        EXPECT_EQ(photon.surface, 0);
        const glm::dvec3 p(photon.position);
        const glm::dvec3 d = glm::normalize(glm::dvec3(incident));
        const glm::dvec3 offset = image - p;
        worst_miss = std::max(worst_miss, glm::length(offset - glm::dot(offset, d) * d));
        const glm::dmat3 projector = glm::dmat3(1.0) - glm::outerProduct(d, d);
        normal_matrix += projector;
        rhs += projector * p;
    }
    const glm::dvec3 focus = glm::inverse(normal_matrix) * rhs;
    EXPECT_LT(glm::length(focus - image), 1e-3) << focus.x << " " << focus.y << " " << focus.z;
    EXPECT_LT(worst_miss, 2e-3);

    const double expected = MirrorWorld::reflected_to_floor(
        [&](const glm::dvec3& m) {
            const glm::dvec3 to = m - glm::dvec3(light.position);
            return std::make_pair(glm::normalize(to), 10.0 / glm::dot(to, to));
        },
        400);
    EXPECT_NEAR(list.stored_power().r, expected, expected * 0.005);
}

TEST(CausticMirror, SpotAreaAndDirectionalLightsDeliverTheirQuadraturePower) {
    MirrorWorld world;
    JobSystem jobs(2);
    auto stored_power = [&](const LightSource& light) {
        CausticPhotonList list(20'000, 8, 4);
        list.set_emitter(CausticEmitter(light, world.mirror_sphere, world.bounds()));
        trace_every_slice(world, list, jobs);
        return list.stored_power().r;
    };

    // A spot that lights only part of the mirror, with its falloff.
    LightSource spot;
    spot.kind = LightKind::Spot;
    spot.position = {0.8f, 1.2f, 0.15f};
    spot.direction = glm::normalize(glm::vec3(0.0f, 0.7f, -0.2f) - spot.position);
    spot.inner_cone = 0.2f;
    spot.outer_cone = 0.3f;
    spot.power = glm::vec3(30.0f);
    const double spot_intensity = 30.0 / (2.0 * kPi * (1.0 - std::cos(0.3)));
    const double spot_expected = MirrorWorld::reflected_to_floor(
        [&](const glm::dvec3& m) {
            const glm::dvec3 to = m - glm::dvec3(spot.position);
            const glm::dvec3 w = glm::normalize(to);
            const double falloff =
                smoothstep(std::cos(0.3), std::cos(0.2), glm::dot(w, glm::dvec3(spot.direction)));
            return std::make_pair(w, spot_intensity * falloff / glm::dot(to, to));
        },
        400);
    EXPECT_NEAR(stored_power(spot), spot_expected, spot_expected * 0.005);

    // A parallel beam from above and in front.
    LightSource sun;
    sun.kind = LightKind::Directional;
    sun.direction = glm::normalize(glm::vec3(-1.0f, -0.8f, 0.1f));
    sun.power = glm::vec3(5.0f);  // W/m^2
    const double sun_expected = MirrorWorld::reflected_to_floor(
        [&](const glm::dvec3&) { return std::make_pair(glm::dvec3(sun.direction), 5.0); }, 400);
    EXPECT_NEAR(stored_power(sun), sun_expected, sun_expected * 0.005);

    // A 0.3 x 0.3 m panel facing the mirror, radiance 20 W/(m^2 sr).
    LightSource panel;
    panel.kind = LightKind::Area;
    panel.power = glm::vec3(20.0f);
    const glm::vec3 corner(0.8f, 1.05f, 0.0f);
    const glm::vec3 u(0.0f, 0.0f, 0.3f);
    const glm::vec3 v(0.0f, 0.3f, 0.0f);  // cross(u, v) = -x: facing the mirror
    panel.triangles = {corner, corner + u, corner + u + v, corner, corner + u + v, corner + v};
    const int light_steps = 16;
    double panel_expected = 0.0;
    for (int a = 0; a < light_steps; ++a) {
        for (int b = 0; b < light_steps; ++b) {
            const glm::dvec3 x = glm::dvec3(corner) + (a + 0.5) / light_steps * glm::dvec3(u) +
                                 (b + 0.5) / light_steps * glm::dvec3(v);
            panel_expected += MirrorWorld::reflected_to_floor(
                [&](const glm::dvec3& m) {
                    const glm::dvec3 to = m - x;
                    const glm::dvec3 w = glm::normalize(to);
                    const double cos_light = std::max(0.0, -w.x);  // the panel faces -x
                    return std::make_pair(w, 20.0 * cos_light / glm::dot(to, to));
                },
                100);
        }
    }
    panel_expected *= 0.09 / (light_steps * light_steps);
    EXPECT_NEAR(stored_power(panel), panel_expected, panel_expected * 0.01);
}

// --- Total internal reflection in a right prism ----------------------------------------------

TEST(CausticRefraction, TotalInternalReflectionTurnsTheBeamInAPrism) {
    // A vertical beam enters the prism's top face, meets the hypotenuse at 45 degrees from
    // inside and, beyond the critical angle (41.8 degrees for ior 1.5), turns through 90
    // degrees onto the wall at x = 2. With ior 1.2 (critical angle 56.4) it leaves through the
    // hypotenuse towards the floor instead.
    auto run = [](float ior) {
        CausticWorld world;
        world.materials = {{Scattering::Diffuse, glm::vec3(0.5f), glm::vec3(1.0f), 1.5f},
                           {Scattering::Dielectric, glm::vec3(0.0f), glm::vec3(1.0f), ior}};
        world.scene.add_object(
            luxel::testing::quad_mesh({-10, -0.5f, 10}, {20, 0, 0}, {0, 0, -20}, 0, 0),
            glm::mat4(1.0f), false);
        world.scene.add_object(
            luxel::testing::quad_mesh({2.0f, -0.5f, -5.0f}, {0, 0, 10}, {0, 5, 0}, 1, 0),
            glm::mat4(1.0f), false);
        const TriangleMesh prism = luxel::testing::right_prism_mesh(1);
        const BoundingSphere generator = luxel::testing::bounding_sphere(prism);
        world.scene.add_object(prism, glm::mat4(1.0f), false);
        world.scene.commit();
        LightSource sun;
        sun.kind = LightKind::Directional;
        sun.direction = {0.0f, -1.0f, 0.0f};
        sun.power = glm::vec3(2.0f);
        CausticPhotonList list(20'000, 8, 6);
        list.set_emitter(CausticEmitter(sun, generator, world.bounds()));
        JobSystem jobs(2);
        trace_every_slice(world, list, jobs);
        glm::dvec2 wall_floor(0.0);
        for (const CausticPhoton& photon : all_photons(list)) {
            wall_floor[photon.surface == 1 ? 0 : 1] += static_cast<double>(photon.power.r);
        }
        if (ior > 1.4f) {
            for (const auto& [photon, incident] : directed_photons(world, list)) {
                if (photon.surface == 1) {
                    EXPECT_GT(incident.x, 0.999f);
                }
            }
        }
        return wall_floor;
    };
    // The top face (1 m^2) takes E * 1 W; two normal-incidence interfaces pass (1 - 0.04)^2.
    const double through_two_faces = (1.0 - 0.04) * (1.0 - 0.04);
    const glm::dvec2 glass = run(1.5f);
    EXPECT_NEAR(glass[0], 2.0 * through_two_faces, 2.0 * through_two_faces * 0.01);
    EXPECT_LT(glass[1], 0.02 * glass[0]);
    const glm::dvec2 weak = run(1.2f);
    EXPECT_LT(weak[0], 0.15 * glass[0]);
    EXPECT_GT(weak[1], 0.7 * 2.0);
}

// --- The slice schedule -------------------------------------------------------------------

/// The slice tests' scene: a floor, and a mirror that throws a light's caustic onto it.
CausticWorld mirror_world() {
    CausticWorld world;
    world.materials = {{Scattering::Diffuse, glm::vec3(0.5f), glm::vec3(1.0f), 1.5f},
                       {Scattering::Mirror, glm::vec3(0.0f), glm::vec3(1.0f), 1.5f}};
    world.scene.add_object(luxel::testing::quad_mesh({-5, 0, 5}, {10, 0, 0}, {0, 0, -10}, 0, 0),
                           glm::mat4(1.0f), false);
    world.scene.add_object(
        luxel::testing::quad_mesh({0.0f, 0.4f, 0.5f}, {0, 0, -1}, {0, 1, 0}, -1, 1),
        glm::mat4(1.0f), false);
    world.scene.commit();
    return world;
}

CausticPhotonList mirror_list(const CausticWorld& world) {
    LightSource light;
    light.position = {0.8f, 1.2f, 0.15f};
    light.power = glm::vec3(50.0f);
    CausticPhotonList list(1'000, 8, 1);
    list.set_emitter(CausticEmitter(light, {{0.0f, 0.9f, 0.0f}, 0.71f}, world.bounds()));
    return list;
}

bool same_bits(std::span<const CausticPhoton> a, std::span<const CausticPhoton> b) {
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(CausticPhoton)) == 0);
}

TEST(CausticSlices, DirtySlicesAreRetracedOncePerFrameInRoundRobinOrder) {
    const CausticWorld world = mirror_world();
    CausticPhotonList list = mirror_list(world);
    EXPECT_TRUE(list.needs_retrace());  // a new list has never been traced
    JobSystem jobs(1);
    for (std::uint64_t frame = 0; frame < 8; ++frame) {
        const auto slice = list.slice_for_frame(frame);
        ASSERT_TRUE(slice.has_value());
        EXPECT_EQ(*slice, frame % 8);
        list.retrace_slice(world.scene, world.materials, *slice, kMaxSpecular, jobs);
    }
    EXPECT_FALSE(list.needs_retrace());
    EXPECT_FALSE(list.slice_for_frame(8).has_value());
    for (std::uint32_t k = 0; k < 8; ++k) {
        EXPECT_EQ(list.slice_retraces(k), 1u);
    }
    // Invalidated at frame 13: the next eight frames start at 13 mod 8 and visit every slice.
    list.invalidate();
    std::set<std::uint32_t> visited;
    for (std::uint64_t frame = 13; frame < 21; ++frame) {
        const auto slice = list.slice_for_frame(frame);
        ASSERT_TRUE(slice.has_value());
        visited.insert(*slice);
        list.retrace_slice(world.scene, world.materials, *slice, kMaxSpecular, jobs);
    }
    EXPECT_EQ(visited.size(), 8u);
    EXPECT_FALSE(list.needs_retrace());
    // A slice's photons are those of its own samples: a second trace stores the same ones.
    const std::vector<CausticPhoton> before(list.slice(3).begin(), list.slice(3).end());
    list.retrace_slice(world.scene, world.materials, 3, kMaxSpecular, jobs);
    ASSERT_EQ(before.size(), list.slice(3).size());
    ASSERT_FALSE(before.empty());
    EXPECT_EQ(std::memcmp(before.data(), list.slice(3).data(), before.size() * 32), 0);
    EXPECT_GE(list.bytes_used(), list.stored_count() * sizeof(CausticPhoton));
}

TEST(CausticSlices, FreshSlicesStandInForStaleOnesAfterAChangeToASettledList) {
    const CausticWorld world = mirror_world();
    CausticPhotonList list = mirror_list(world);
    JobSystem jobs(1);
    trace_every_slice(world, list, jobs);  // a new list builds up without stand-ins
    ASSERT_FALSE(list.needs_retrace());
    EXPECT_FALSE(list.standing_in());
    std::vector<std::vector<CausticPhoton>> before;
    std::vector<std::uint64_t> retraces;
    for (std::uint32_t k = 0; k < 8; ++k) {
        before.emplace_back(list.slice(k).begin(), list.slice(k).end());
        ASSERT_FALSE(before.back().empty());
        retraces.push_back(list.slice_retraces(k));
    }
    const glm::dvec3 settled = list.stored_power();

    // A change meets the settled list: until a slice is retraced the stale photons show.
    list.invalidate();
    EXPECT_FALSE(list.standing_in());
    EXPECT_EQ(list.stored_count(), all_photons(list).size());
    EXPECT_NEAR(list.stored_power().x, settled.x, 1e-9 * settled.x);
    // One retraced slice shows beside the seven stale ones, as traced.
    list.retrace_slice(world.scene, world.materials, 5, kMaxSpecular, jobs);
    EXPECT_FALSE(list.standing_in());
    EXPECT_TRUE(list.catching_up());
    EXPECT_TRUE(same_bits(list.slice(5), before[5])) << "an unchanged scene's photons";
    EXPECT_TRUE(same_bits(list.slice(0), before[0])) << "a stale slice in view";
    // With a quarter of them retraced the fresh slices hide the stale ones and carry the
    // pair's power alone.
    list.retrace_slice(world.scene, world.materials, 6, kMaxSpecular, jobs);
    EXPECT_TRUE(list.standing_in());
    for (std::uint32_t k = 0; k < 8; ++k) {
        EXPECT_GT(list.slice_retraces(k), retraces[k]) << "slice " << k << " is re-read";
        if (k != 5 && k != 6) {
            EXPECT_TRUE(list.slice(k).empty()) << "stale slice " << k;
        }
    }
    for (const std::uint32_t k : {5u, 6u}) {
        ASSERT_EQ(list.slice(k).size(), before[k].size());
        for (std::size_t i = 0; i < before[k].size(); ++i) {
            EXPECT_EQ(list.slice(k)[i].position, before[k][i].position);
            EXPECT_EQ(list.slice(k)[i].power, before[k][i].power * 4.0f);  // x4 is exact
        }
    }
    // A quarter of the photons, each slice covering the whole cone: the same power within
    // the slices' spread (the mirror's patch is a fixed share of the cone).
    EXPECT_NEAR(list.stored_power().x, settled.x, 0.05 * settled.x);
    // One more: three slices, each photon at 8/3 of its traced power.
    list.retrace_slice(world.scene, world.materials, 7, kMaxSpecular, jobs);
    for (const std::uint32_t k : {5u, 6u, 7u}) {
        ASSERT_EQ(list.slice(k).size(), before[k].size());
        EXPECT_FLOAT_EQ(list.slice(k)[0].power.y, before[k][0].power.y * (8.0f / 3.0f));
    }
    EXPECT_TRUE(list.slice(0).empty());
    EXPECT_NEAR(list.stored_power().x, settled.x, 0.03 * settled.x);
    // The last stale slice retraced: every slice as traced, bit for bit (the stored photons
    // were never scaled in place), and the settled power exactly.
    for (const std::uint32_t k : {0u, 1u, 2u, 3u, 4u}) {
        list.retrace_slice(world.scene, world.materials, k, kMaxSpecular, jobs);
    }
    EXPECT_FALSE(list.needs_retrace());
    EXPECT_FALSE(list.standing_in());
    for (std::uint32_t k = 0; k < 8; ++k) {
        EXPECT_TRUE(same_bits(list.slice(k), before[k])) << "slice " << k;
    }
    EXPECT_EQ(list.stored_power(), settled);
}

TEST(CausticSlices, AListCatchesUpUntilItHoldsTheGenerationsItHadBeforeTheChange) {
    const CausticWorld world = mirror_world();
    CausticPhotonList list = mirror_list(world);
    JobSystem jobs(1);
    EXPECT_FALSE(list.catching_up()) << "a new list builds up; it had nothing to catch up to";
    trace_every_slice(world, list, jobs);
    list.set_generation_limit(2);
    const auto trace_until = [&](auto done) {
        for (int part = 0; part < 100 && !done(); ++part) {
            list.trace_part(world.scene, world.materials, 50, kMaxSpecular, jobs);
        }
    };
    trace_until([&] { return list.generations() == 2; });
    ASSERT_EQ(list.generations(), 2u);
    EXPECT_FALSE(list.catching_up());

    list.invalidate();
    EXPECT_TRUE(list.catching_up());
    trace_until([&] { return !list.needs_retrace(); });
    EXPECT_EQ(list.generations(), 1u);
    EXPECT_TRUE(list.catching_up()) << "one generation of the two it held";
    trace_until([&] { return list.generations() == 2; });
    EXPECT_FALSE(list.catching_up());
    // Hit while still retracing (something keeps moving): no catching up.
    list.invalidate();
    list.trace_part(world.scene, world.materials, 50, kMaxSpecular, jobs);
    list.invalidate();
    EXPECT_FALSE(list.catching_up());
}

/// Power of a photon relative to `reference`'s, for photons traced from the same sample.
float power_ratio(const CausticPhoton& photon, const CausticPhoton& reference) {
    return photon.power.y / reference.power.y;
}

TEST(CausticSlices, ACatchingUpListShowsEachRefinementSliceAsItIsTraced) {
    const CausticWorld world = mirror_world();
    JobSystem jobs(1);
    const auto refine_to = [&](CausticPhotonList& list, std::uint32_t generations) {
        for (int part = 0; part < 200 && list.generations() < generations; ++part) {
            list.trace_part(world.scene, world.materials, 1'000, kMaxSpecular, jobs);
        }
        ASSERT_EQ(list.generations(), generations);
    };
    // The same photons refined a generation at a time, as a still list is: slices 8-15 are
    // the second generation's, each photon at 1/2 of its traced power.
    CausticPhotonList still = mirror_list(world);
    trace_every_slice(world, still, jobs);
    still.set_generation_limit(2);
    refine_to(still, 2);

    CausticPhotonList list = mirror_list(world);
    trace_every_slice(world, list, jobs);
    list.set_generation_limit(3);
    refine_to(list, 3);
    const glm::dvec3 settled = list.stored_power();
    list.invalidate();
    EXPECT_EQ(list.catch_up_photons_left(), 24u * 125u) << "eight dirty slices, then sixteen";
    for (int frame = 0; frame < 8; ++frame) {
        list.trace_part(world.scene, world.materials, 1'000, kMaxSpecular, jobs);
    }
    ASSERT_FALSE(list.needs_retrace());
    ASSERT_TRUE(list.catching_up());
    ASSERT_EQ(list.slice_count(), 8u);
    EXPECT_EQ(list.catch_up_photons_left(), 16u * 125u) << "two generations to refine back";

    // Each refinement slice shows as it completes: with m slices shown, every photon carries
    // K / m of its traced power, and the slices together the pair's power.
    for (std::uint32_t m = 9; m <= 16; ++m) {
        const std::uint64_t first_reads = list.slice_retraces(0);
        list.trace_part(world.scene, world.materials, 1'000, kMaxSpecular, jobs);
        ASSERT_EQ(list.slice_count(), m);
        EXPECT_GT(list.slice_retraces(0), first_reads) << "rescaled, so re-read";
        const float share = 8.0f / static_cast<float>(m);
        ASSERT_FALSE(list.slice(0).empty());
        EXPECT_NEAR(power_ratio(list.slice(0)[0], still.slice(0)[0]), share / 0.5f, 1e-5f);
        const std::span<const CausticPhoton> fresh = list.slice(m - 1);
        ASSERT_EQ(fresh.size(), still.slice(m - 1).size());
        ASSERT_FALSE(fresh.empty());
        EXPECT_EQ(fresh[0].position, still.slice(m - 1)[0].position) << "the same sample";
        EXPECT_NEAR(power_ratio(fresh[0], still.slice(m - 1)[0]), share / 0.5f, 1e-5f);
        EXPECT_NEAR(list.stored_power().y, settled.y, 0.05 * settled.y) << m << " slices";
    }
    EXPECT_EQ(list.generations(), 2u);
    EXPECT_TRUE(list.catching_up()) << "two generations of the three it held";
    EXPECT_EQ(list.catch_up_photons_left(), 8u * 125u);
    refine_to(list, 3);
    EXPECT_FALSE(list.catching_up());
    EXPECT_EQ(list.catch_up_photons_left(), 0u);
    EXPECT_NEAR(list.stored_power().y, settled.y, 1e-5 * settled.y) << "back where it was";

    // Caught up, the list refines a generation at a time again: nothing shows until the
    // fourth is complete.
    list.set_generation_limit(4);
    list.trace_part(world.scene, world.materials, 1'000, kMaxSpecular, jobs);
    EXPECT_EQ(list.slice_count(), 24u);
    // A change from a partly refined state: the first generation alone carries the power again.
    list.invalidate();
    ASSERT_EQ(list.slice_count(), 8u);
    EXPECT_NEAR(power_ratio(list.slice(0)[0], still.slice(0)[0]), 2.0f, 1e-5f);
}

TEST(CausticSlices, AListHitAgainWhileRetracingKeepsItsStaleSlicesInView) {
    const CausticWorld world = mirror_world();
    CausticPhotonList list = mirror_list(world);
    JobSystem jobs(1);
    trace_every_slice(world, list, jobs);
    std::vector<std::vector<CausticPhoton>> before;
    for (std::uint32_t k = 0; k < 8; ++k) {
        before.emplace_back(list.slice(k).begin(), list.slice(k).end());
    }
    list.invalidate();
    list.retrace_slice(world.scene, world.materials, 2, kMaxSpecular, jobs);
    list.retrace_slice(world.scene, world.materials, 3, kMaxSpecular, jobs);
    ASSERT_TRUE(list.standing_in());
    // Something keeps moving: hit again before the list was current. The hidden slices come
    // back and the fresh one carries its own share again; no stand-in while it keeps moving.
    list.invalidate();
    EXPECT_FALSE(list.standing_in());
    for (std::uint32_t k = 0; k < 8; ++k) {
        EXPECT_TRUE(same_bits(list.slice(k), before[k])) << "slice " << k;
    }
    list.retrace_slice(world.scene, world.materials, 4, kMaxSpecular, jobs);
    EXPECT_FALSE(list.standing_in());
    for (std::uint32_t k = 0; k < 8; ++k) {
        EXPECT_TRUE(same_bits(list.slice(k), before[k])) << "slice " << k;
    }
    EXPECT_EQ(list.stored_count(), all_photons(list).size());
    EXPECT_GE(list.bytes_used(), list.stored_count() * sizeof(CausticPhoton));
}

}  // namespace
