// The reference under a sky (issue 20), against closed forms: a floor open to a uniform sky of
// radiance L receives E = pi L; the centre of a black box's floor under a square hole in its
// roof receives L times the hole's projected solid angle (pi times the view factor of a
// parallel square), which checks the sky's next-event estimate, its shadow rays and its
// weighting against paths that leave through the hole. An uneven sky checks the same with
// importance sampling that is far from the cosine.

#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "luxel/lighting/reference/reference_integrator.hpp"
#include "scene_builder.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;
using namespace luxel::lighting::reference;

constexpr double kPi = glm::pi<double>();

LightSource sky_light(SkyRadiance sky, float scale = 1.0f) {
    LightSource light;
    light.kind = LightKind::Sky;
    light.sky = std::make_shared<const SkyRadiance>(std::move(sky));
    light.sky_scale = scale;
    light.power = glm::vec3(light.sky->integral()) * scale;
    return light;
}

/// A black material: no indirect light, so the direct component is all there is.
std::vector<TraceMaterial> black_materials() {
    TraceMaterial black;
    black.albedo = glm::vec3(0.0f);
    return {black};
}

/// Runs `passes` passes and checks every texel's direct irradiance against `expected` within 4
/// standard errors plus `slack` (relative); prints the worst deviation in sigmas.
void check_direct(const ReferenceScene& scene, const glm::dvec3& expected, const char* what,
                  int passes, double slack = 0.0) {
    ReferenceSettings settings;
    settings.samples_per_pass = 8192;
    ReferenceIntegrator integrator(scene, settings);
    JobSystem jobs(2);
    for (int pass = 0; pass < passes; ++pass) {
        integrator.run_pass(jobs);
    }
    double worst_sigma = 0.0;
    for (std::size_t t = 0; t < scene.texel_count(); ++t) {
        const glm::dvec3 got = integrator.irradiance(Component::Direct, t);
        const glm::dvec3 se = integrator.standard_error(Component::Direct, t);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(got[c], expected[c], 4.0 * se[c] + slack * expected[c] + 1e-12)
                << what << " texel " << t << " channel " << c;
            if (se[c] > 0.0) {
                worst_sigma = std::max(worst_sigma, std::abs(got[c] - expected[c]) / se[c]);
            }
        }
        EXPECT_EQ(integrator.irradiance(Component::Indirect, t), glm::dvec3(0.0));
        if (t == 0) {
            std::printf("[ figures  ] %s: E %.5f expected %.5f (%+.3f%%, se %.3f%%)\n", what, got.y,
                        expected.y, 100.0 * (got.y / expected.y - 1.0), 100.0 * se.y / got.y);
        }
    }
    std::printf("[ figures  ] %s: worst |error| %.2f sigma over %zu texels\n", what, worst_sigma,
                scene.texel_count());
}

TEST(SkyReference, AFloorUnderAUniformSkyReceivesPiL) {
    RayScene rays;
    rays.add_object(luxel::testing::horizontal_quad(0.0f, 2.0f, true, 0, 0), glm::mat4(1.0f),
                    false);
    rays.commit();
    const glm::vec3 radiance(0.4f, 0.8f, 1.6f);
    const ReferenceScene scene(rays, black_materials(), {sky_light(SkyRadiance::uniform(radiance))},
                               {luxel::testing::quad_texels(0, 0.0f, 2.0f, true, 4)});
    check_direct(scene, kPi * glm::dvec3(radiance), "uniform sky over a floor", 8);
}

/// A black box 2 x 2 m, 1 m high, whose roof has a square hole of half side `a` at its centre;
/// the floor's one texel sits at the centre.
struct HoleBox {
    static constexpr float kHalf = 1.0f;
    static constexpr float kHeight = 1.0f;
    RayScene rays;

    explicit HoleBox(float a) {
        using luxel::testing::Rectangle;
        rays.add_object(luxel::testing::horizontal_quad(0.0f, kHalf, true, 0, 0), glm::mat4(1.0f),
                        false);
        // The roof around the hole: four strips facing down.
        const float strip = 0.5f * (kHalf - a);
        const glm::vec3 down(0.0f, -1.0f, 0.0f);
        const Rectangle roof[4] = {
            {{0.0f, kHeight, a + strip}, {1.0f, 0, 0}, {0, 0, 1.0f}, kHalf, strip, down},
            {{0.0f, kHeight, -a - strip}, {1.0f, 0, 0}, {0, 0, 1.0f}, kHalf, strip, down},
            {{a + strip, kHeight, 0.0f}, {1.0f, 0, 0}, {0, 0, 1.0f}, strip, a, down},
            {{-a - strip, kHeight, 0.0f}, {1.0f, 0, 0}, {0, 0, 1.0f}, strip, a, down}};
        for (const Rectangle& r : roof) {
            rays.add_object(r.mesh(-1, 0), glm::mat4(1.0f), false);
        }
        const float mid = 0.5f * kHeight;
        const Rectangle walls[4] = {
            {{kHalf, mid, 0}, {0, 1.0f, 0}, {0, 0, 1.0f}, mid, kHalf, {-1.0f, 0, 0}},
            {{-kHalf, mid, 0}, {0, 1.0f, 0}, {0, 0, 1.0f}, mid, kHalf, {1.0f, 0, 0}},
            {{0, mid, kHalf}, {1.0f, 0, 0}, {0, 1.0f, 0}, kHalf, mid, {0, 0, -1.0f}},
            {{0, mid, -kHalf}, {1.0f, 0, 0}, {0, 1.0f, 0}, kHalf, mid, {0, 0, 1.0f}}};
        for (const Rectangle& r : walls) {
            rays.add_object(r.mesh(-1, 0), glm::mat4(1.0f), false);
        }
        rays.commit();
    }
};

/// Pi times the view factor from a point to a parallel square of half side a centred at height
/// h above it: four corner rectangles a x a (the differential-area-to-rectangle form).
double projected_solid_angle_of_square(double a, double h) {
    const double x = a / h;
    const double s = std::sqrt(1.0 + x * x);
    const double corner = (x / s * std::atan(x / s) * 2.0) / (2.0 * kPi);
    return 4.0 * kPi * corner;
}

TEST(SkyReference, TheFloorOfABoxGetsWhatItsRoofHoleLetsThrough) {
    const float a = 0.25f;
    const HoleBox box(a);
    const glm::vec3 radiance(1.0f, 2.0f, 0.5f);
    const ReferenceScene scene(box.rays, black_materials(),
                               {sky_light(SkyRadiance::uniform(radiance))},
                               {luxel::testing::quad_texels(0, 0.0f, HoleBox::kHalf, true, 1)});
    ASSERT_EQ(scene.texel_count(), 1u);
    const double omega = projected_solid_angle_of_square(a, HoleBox::kHeight);
    // 0.2308 sr for a 0.5 m hole 1 m up: a small share of the sky's pi.
    EXPECT_NEAR(omega, 0.2308, 1e-3);
    check_direct(scene, omega * glm::dvec3(radiance), "uniform sky through a roof hole", 32);
}

/// Radiance 3 within 30 degrees of the zenith, 0.75 elsewhere above the horizon, black below, on
/// a 64 x 48 grid (3.75 degree rows: the cap ends on a row boundary, 8 rows).
SkyRadiance capped_sky() {
    const int width = 64;
    const int height = 48;
    std::vector<glm::vec3> cells(static_cast<std::size_t>(width) * height);
    for (int row = 0; row < height; ++row) {
        for (int col = 0; col < width; ++col) {
            cells[static_cast<std::size_t>(row) * width + col] = row < 8    ? glm::vec3(3.0f)
                                                                 : row < 24 ? glm::vec3(0.75f)
                                                                            : glm::vec3(0.0f);
        }
    }
    return SkyRadiance(width, height, std::move(cells));
}

TEST(SkyReference, AnUnevenSkyThroughTheHoleMatchesTheSameFormPerCell) {
    // A sky bright only in a cap of directions within 30 degrees of the zenith and four times
    // dimmer elsewhere above the horizon, on a fine grid: the hole (within 19.5 degrees of
    // the zenith from the texel) sees only the bright cap, so the expected value is the same
    // form with the cap's radiance. The light samples mostly fall in the cap, most of it
    // outside the hole, where the shadow rays find the roof.
    const float a = 0.25f;
    const HoleBox box(a);
    const ReferenceScene scene(box.rays, black_materials(), {sky_light(capped_sky(), 0.5f)},
                               {luxel::testing::quad_texels(0, 0.0f, HoleBox::kHalf, true, 1)});
    const double omega = projected_solid_angle_of_square(a, HoleBox::kHeight);
    check_direct(scene, glm::dvec3(1.5 * omega), "uneven sky through a roof hole", 32);
}

TEST(SkyReference, APortalInTheHoleGivesTheSameLightWithLessNoise) {
    // The same box and uneven sky, with a portal filling the hole: the next-event estimate
    // also aims at the opening, and is weighed against the sky's own samples and the cosine
    // continuation, so the answer is the same and its standard error smaller.
    const float a = 0.25f;
    const HoleBox box(a);
    LightSource light = sky_light(capped_sky(), 0.5f);
    const float y = HoleBox::kHeight;
    // Facing down, into the box (either side would do).
    light.portals = {{-a, y, -a}, {a, y, a}, {a, y, -a}, {-a, y, -a}, {-a, y, a}, {a, y, a}};
    const ReferenceScene scene(box.rays, black_materials(), {light},
                               {luxel::testing::quad_texels(0, 0.0f, HoleBox::kHalf, true, 1)});
    const double omega = projected_solid_angle_of_square(a, HoleBox::kHeight);
    check_direct(scene, glm::dvec3(1.5 * omega), "uneven sky through a roof hole with a portal",
                 32);
    // Its standard error against the portal-less estimate's, same passes and seed.
    auto relative_se = [&](const ReferenceScene& of) {
        ReferenceSettings settings;
        settings.samples_per_pass = 8192;
        ReferenceIntegrator integrator(of, settings);
        JobSystem jobs(2);
        for (int pass = 0; pass < 8; ++pass) {
            integrator.run_pass(jobs);
        }
        return integrator.standard_error(Component::Direct, 0).y /
               integrator.irradiance(Component::Direct, 0).y;
    };
    LightSource plain = light;
    plain.portals.clear();
    const ReferenceScene without(box.rays, black_materials(), {plain},
                                 {luxel::testing::quad_texels(0, 0.0f, HoleBox::kHalf, true, 1)});
    const double with_portal = relative_se(scene);
    const double without_portal = relative_se(without);
    std::printf(
        "[ figures  ] roof hole, uneven sky: relative standard error %.3f%% with the "
        "portal, %.3f%% without\n",
        100.0 * with_portal, 100.0 * without_portal);
    EXPECT_LT(with_portal, 0.5 * without_portal);
}

}  // namespace
