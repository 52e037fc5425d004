// The indirect component against an independent integration of one diffuse bounce: a point
// light in front of a diffuse wall of albedo rho standing on a black floor. The floor reflects
// nothing, so the only indirect light on it is the wall's first bounce,
//   E1(x) = integral over the wall of (rho / pi) E0(y) cos(theta_x) cos(theta_y) / r^2 dA(y),
//   E0(y) = I cos(theta_light) / d^2,
// which the test integrates by composite Gauss-Legendre and compares with the reference's
// per-texel indirect irradiance from both of its methods: paths (a point estimate at the texel
// centre) and photons (the texel's mean, luxel-ref's default).

#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "luxel/lighting/reference/reference_integrator.hpp"
#include "quadrature.hpp"
#include "scene_builder.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;
using namespace luxel::lighting::reference;

constexpr double kPi = glm::pi<double>();
constexpr double kPower = 100.0;  // W, every channel
const glm::vec3 kAlbedo(0.8f, 0.5f, 0.2f);
const glm::vec3 kLight(0.6f, 1.1f, 0.25f);
constexpr int kFloorTexels = 6;  // 0.5 m texels on the 3 x 3 m floor

// The wall: the plane x = 0 facing +x, y in [0, 2], z in [-1.5, 1.5]; the floor: y = 0 facing
// up, x in [0, 3], z in [-1.5, 1.5], light-mapped. They meet along the wall's bottom edge; the
// light and every segment between them lie in x, y > 0, so nothing occludes anything.
const luxel::testing::Rectangle kWall{
    {0.0f, 1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 1.0f}, 1.0f, 1.5f, {1.0f, 0.0f, 0.0f}};
const luxel::testing::Rectangle kFloor{
    {1.5f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f}, 1.5f, 1.5f, {0.0f, 1.0f, 0.0f}};
// Receiver texels (x, z index), at least 0.5 m from the wall, where E1 is smooth (the kernel
// 1 / r^4 peaks only along the shared edge).
const std::vector<glm::ivec2> kReceivers{{1, 1}, {1, 3}, {2, 2}, {2, 5}, {3, 3}, {4, 1}};

/// E1 at floor point p for unit albedo, by 8-point Gauss-Legendre on panels x panels * 3 / 2
/// panels of the wall (0.25 m panels at 8: the light's peak on the wall is 0.6 m wide).
double first_bounce(const glm::dvec3& p, int panels) {
    static const luxel::testing::GaussLegendre rule = luxel::testing::gauss_legendre(8);
    const glm::dvec3 light(kLight);
    const double intensity = kPower / (4.0 * kPi);
    return luxel::testing::integrate_2d(
        rule, 0.0, 2.0, panels, -1.5, 1.5, panels * 3 / 2, [&](double y, double z) {
            const glm::dvec3 w(0.0, y, z);
            const glm::dvec3 to_light = light - w;
            const double d2 = glm::dot(to_light, to_light);
            const double e0 = intensity * to_light.x / (d2 * std::sqrt(d2));  // I cos / d^2
            const glm::dvec3 to_wall = w - p;
            const double r2 = glm::dot(to_wall, to_wall);
            // cos at the floor: to_wall.y / r; at the wall: -to_wall.x / r.
            return e0 * to_wall.y * -to_wall.x / (kPi * r2 * r2);
        });
}

/// The mean of E1 (unit albedo) over floor texel (tx, tz): 4-point Gauss-Legendre on
/// panels x panels of the texel's square.
double texel_mean(const glm::ivec2& texel, int panels, int wall_panels) {
    static const luxel::testing::GaussLegendre rule = luxel::testing::gauss_legendre(4);
    const double size = 3.0 / kFloorTexels;
    const double x0 = size * texel.x;
    const double z0 = -1.5 + size * texel.y;
    return luxel::testing::integrate_2d(rule, x0, x0 + size, panels, z0, z0 + size, panels,
                                        [&](double x, double z) {
                                            return first_bounce({x, 0.0, z}, wall_panels);
                                        }) /
           (size * size);
}

struct Corner {
    RayScene rays;
    std::vector<TraceMaterial> materials;
    LightSource light;

    Corner() {
        TraceMaterial black;
        black.albedo = glm::vec3(0.0f);
        TraceMaterial wall;
        wall.albedo = kAlbedo;
        materials = {black, wall};
        rays.add_object(kFloor.mesh(0, 0), glm::mat4(1.0f), false);
        rays.add_object(kWall.mesh(-1, 1), glm::mat4(1.0f), false);
        rays.commit();
        light.kind = LightKind::Point;
        light.position = kLight;
        light.power = glm::vec3(static_cast<float>(kPower));
    }

    [[nodiscard]] ReferenceScene scene() const {
        ReferenceSurface floor;
        floor.surface = 0;
        floor.page_size = kFloorTexels;
        for (const glm::ivec2& r : kReceivers) {
            floor.texels.push_back(kFloor.texel(r.x, r.y, kFloorTexels));
        }
        return {rays, materials, {light}, {floor}};
    }
};

/// Checks every receiver texel's indirect irradiance against `expected` (unit albedo) times
/// the wall's albedo, channel by channel, within 4 reported standard errors plus the
/// quadrature's own error; prints the figures.
void check(const char* method, const ReferenceIntegrator& integrator,
           const std::vector<double>& expected, const std::vector<double>& other,
           const char* other_name) {
    double worst_sigma = 0.0;
    for (std::size_t t = 0; t < kReceivers.size(); ++t) {
        const glm::dvec3 got = integrator.irradiance(Component::Indirect, t);
        const glm::dvec3 se = integrator.standard_error(Component::Indirect, t);
        for (int c = 0; c < 3; ++c) {
            const double want = expected[t] * static_cast<double>(kAlbedo[c]);
            // 4 sigma: the estimates are means of >= 1e4 independent samples or photon
            // arrivals, close to normal; the quadrature is converged to 1e-6 (checked), 1e-5
            // is allowed for it.
            EXPECT_NEAR(got[c], want, 4.0 * se[c] + 1e-5 * want)
                << method << " texel " << t << " channel " << c;
            if (se[c] > 0.0) {
                worst_sigma = std::max(worst_sigma, std::abs(got[c] - want) / se[c]);
            }
        }
        std::printf(
            "[ figures  ] first bounce, %s, texel (%d, %d): E %.5f expected %.5f (%+.2f%%, se "
            "%.2f%%), %s %.5f (%+.2f%%)\n",
            method, kReceivers[t].x, kReceivers[t].y, got.x,
            expected[t] * static_cast<double>(kAlbedo.x),
            100.0 * (got.x / (expected[t] * static_cast<double>(kAlbedo.x)) - 1.0),
            100.0 * se.x / got.x, other_name, other[t] * static_cast<double>(kAlbedo.x),
            100.0 * (other[t] / expected[t] - 1.0));
    }
    std::printf("[ figures  ] first bounce, %s: worst |error| %.2f sigma\n", method, worst_sigma);
}

TEST(FirstBounce, PathsMatchTheIntegratedBounceAtTexelCentres) {
    const Corner corner;
    const ReferenceScene scene = corner.scene();
    ASSERT_EQ(scene.texel_count(), kReceivers.size());
    std::vector<double> centre;
    std::vector<double> mean;
    for (std::size_t t = 0; t < kReceivers.size(); ++t) {
        const glm::dvec3 p(scene.texel(t).position);
        centre.push_back(first_bounce(p, 16));
        // Converged: halving the panels changes E1 by under 1e-6.
        ASSERT_NEAR(first_bounce(p, 8), centre.back(), 1e-6 * centre.back()) << "texel " << t;
        mean.push_back(texel_mean(kReceivers[t], 1, 8));
    }
    ReferenceSettings settings;
    settings.indirect = IndirectMethod::Paths;
    settings.samples_per_pass = 65'536;
    ReferenceIntegrator integrator(scene, settings);
    JobSystem jobs(2);
    for (int pass = 0; pass < 4; ++pass) {
        integrator.run_pass(jobs);
    }
    // A path sample is a point estimate at the texel centre: compared with E1 there, so the
    // texel-averaging error does not enter. The texel mean is printed for scale: it differs
    // from the centre by up to 1.6% on these 0.5 m texels, about the tolerance.
    check("paths", integrator, centre, mean, "texel mean");
}

TEST(FirstBounce, PhotonsMatchTheIntegratedBounceOverEachTexel) {
    const Corner corner;
    const ReferenceScene scene = corner.scene();
    ASSERT_EQ(scene.texel_count(), kReceivers.size());
    std::vector<double> centre;
    std::vector<double> mean;
    for (std::size_t t = 0; t < kReceivers.size(); ++t) {
        EXPECT_NEAR(scene.texel(t).area, 0.25, 1e-6);  // whole 0.5 m texels
        centre.push_back(first_bounce(glm::dvec3(scene.texel(t).position), 16));
        mean.push_back(texel_mean(kReceivers[t], 2, 8));
        // Converged: one panel per texel and 8 wall panels agree to 1e-6.
        ASSERT_NEAR(texel_mean(kReceivers[t], 1, 8), mean.back(), 1e-6 * mean.back())
            << "texel " << t;
    }
    ReferenceSettings settings;
    settings.indirect = IndirectMethod::Photons;
    settings.samples_per_pass = 0;  // the indirect component is the photons' alone
    settings.indirect_photons.photons_per_pass = 4'000'000;
    ReferenceIntegrator integrator(scene, settings);
    JobSystem jobs(2);
    for (int pass = 0; pass < 3; ++pass) {
        integrator.run_pass(jobs);
    }
    // Photons are binned over the texel's area: compared with E1's mean over the texel, so
    // there is no texel-averaging error to allow for. The centre value is printed for scale
    // (up to 1.7% off the mean, about the tolerance: what comparing with it would cost).
    check("photons", integrator, mean, centre, "centre");
}

}  // namespace
