// The ray-differential footprint kernel (S. Larsen 2006 §4.4.5; docs/METHOD.md §7.4): each
// photon spread over the disc its photon differential stands for. It reads smooth close up
// where a fixed screen-space kernel breaks into dots, it keeps every photon's power, so a small
// bright focus stays where it is (the mip-maps' per-pixel widening spread it into a ring), and
// a surface nearer the camera than a photon takes none of it.

#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "caustic_test_support.hpp"
#include "luxel/lighting/gpu/caustic_kernel.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;

constexpr double kPi = 3.14159265358979323846;

class PhotonFootprintKernel : public ::testing::Test {
  protected:
    void SetUp() override { context_ = test::make_caustic_gl_context(); }
    void TearDown() override { context_.reset(); }
    std::unique_ptr<GlContext> context_;
};

/// The footprint a photon differential gives a photon that stands for `area` m^2.
std::uint32_t footprint_of(double area) {
    return encode_footprint_radius(static_cast<float>(std::sqrt(area / kPi)));
}

/// side x side photons over the 2 x 2 m square around the origin on the z = 0 plane, one at a
/// random point of each cell of a side x side grid (stratified, as the tracer's Halton photons
/// land where the path maps them smoothly), `watts` in all, each with the footprint of its
/// share of the square.
std::vector<CausticPhoton> uniform_photons(int side, float watts) {
    std::mt19937 random(7);
    std::uniform_real_distribution<float> jitter(0.0f, 1.0f);
    const float cell = 2.0f / static_cast<float>(side);
    const int count = side * side;
    std::vector<CausticPhoton> photons;
    for (int j = 0; j < side; ++j) {
        for (int i = 0; i < side; ++i) {
            CausticPhoton p;
            p.position = {-1.0f + (static_cast<float>(i) + jitter(random)) * cell,
                          -1.0f + (static_cast<float>(j) + jitter(random)) * cell, 0.0f};
            p.power = glm::vec3(watts / static_cast<float>(count));
            p.footprint = footprint_of(4.0 / count);
            photons.push_back(p);
        }
    }
    return photons;
}

TEST_F(PhotonFootprintKernel, SparsePhotonsReadSmootherThanThroughLarsensKernel) {
    // A camera 0.3 m from a uniformly lit plane: about 0.03 photons a pixel, a close-up where
    // Larsen's 7 x 7 kernel holds one or two photons; a footprint (twice the radius of the
    // photon's share of the plane) holds about four, however close the camera comes. (At
    // 0.6 m, 0.12 photons a pixel, Larsen's square holds six and is the smoother: 19.5%
    // against 29.5%.)
    const glm::ivec2 size(128, 96);
    const test::RectScene scene(test::look_at({0.0f, 0.0f, 0.3f}, {0.0f, 0.0f, 0.0f}, size),
                                {{{0, 0, 0}, {5, 0, 0}, {0, 5, 0}}});
    const float watts = 4.0f;
    const std::vector<CausticPhoton> photons = uniform_photons(100, watts);
    const double expected = watts / 4.0;
    CausticPassSettings larsen;
    larsen.kernel = CausticKernel::Larsen;
    CausticPassSettings footprints;
    footprints.kernel = CausticKernel::PhotonFootprints;
    const auto [larsen_error, larsen_mean] =
        test::uniform_error(test::filtered(larsen, scene, size, photons), size, expected, 16);
    const auto [error, mean] =
        test::uniform_error(test::filtered(footprints, scene, size, photons), size, expected, 16);
    std::printf(
        "[ figures  ] 0.03 photons a pixel: relRMSE Larsen k=3 %.1f%% (mean %.3f), "
        "footprints %.1f%% (mean %.3f)\n",
        100.0 * larsen_error, larsen_mean, 100.0 * error, mean);
    EXPECT_LT(error, 0.75 * larsen_error);
    EXPECT_NEAR(mean, 1.0, 0.05);
}

TEST_F(PhotonFootprintKernel, ABrightFocusKeepsItsPowerAndStaysWhereItIs) {
    // A focus of radius 1 cm holding 100 times the power of the dim field around it, whose
    // photons' footprints are small: every pixel beyond the focus's footprints reads the field
    // alone, and the whole frame holds the photons' power.
    const glm::ivec2 size(200, 200);
    const test::RectScene scene(test::look_at({0.0f, 0.0f, 1.2f}, {0.0f, 0.0f, 0.0f}, size),
                                {{{0, 0, 0}, {5, 0, 0}, {0, 5, 0}}});
    std::vector<CausticPhoton> photons = uniform_photons(141, 4.0f);  // 1 W/m^2
    const float focus_radius = 0.01f;
    const int focus_count = 4'000;
    const glm::vec3 focus_power(4.0f);
    for (CausticPhoton p : test::disc_photons({0.1f, -0.05f, 0.0f}, {1, 0, 0}, {0, 1, 0},
                                              focus_radius, focus_count, focus_power)) {
        p.footprint = footprint_of(kPi * focus_radius * focus_radius / focus_count);
        photons.push_back(p);
    }
    CausticPassSettings settings;
    settings.kernel = CausticKernel::PhotonFootprints;
    CausticPass pass(settings, size);
    pass.upload(photons);
    pass.render(scene.camera(), scene.depth_texture().id());
    EXPECT_EQ(pass.stats().photons_splatted, photons.size());
    const std::vector<glm::vec4> out = test::read_rgba(pass.irradiance_texture(), size);

    // The power: the field's share in view plus the focus.
    double field_in_view = 0.0;
    for (int y = 0; y < size.y; ++y) {
        for (int x = 0; x < size.x; ++x) {
            field_in_view += scene.pixel_area(x, y);  // 1 W/m^2 of field everywhere in view
        }
    }
    const glm::dvec3 total = test::total_power(out, scene);
    EXPECT_NEAR(total.g, field_in_view + focus_power.g, 0.03 * (field_in_view + focus_power.g));

    // A ring 3 to 6 cm from the focus's centre: the field alone (its mean within its noise).
    double ring = 0.0;
    int ring_pixels = 0;
    for (int y = 0; y < size.y; ++y) {
        for (int x = 0; x < size.x; ++x) {
            const auto p = scene.hit(x, y);
            const float d = glm::length(glm::vec2(*p) - glm::vec2(0.1f, -0.05f));
            if (d > 0.03f && d < 0.06f) {
                ring += out[static_cast<std::size_t>(y * size.x + x)].g;
                ++ring_pixels;
            }
        }
    }
    ASSERT_GT(ring_pixels, 100);
    std::printf(
        "[ figures  ] a focus 100x the field: power %.4f of the photons', ring %.3f of "
        "the field\n",
        total.g / (field_in_view + focus_power.g), ring / ring_pixels);
    EXPECT_NEAR(ring / ring_pixels, 1.0, 0.1);

    // Switching kernels on a live pass gives the footprints' result back, and Larsen's its own.
    CausticPass larsen_pass(CausticPassSettings{}, size);
    larsen_pass.upload(photons);
    larsen_pass.render(scene.camera(), scene.depth_texture().id());
    const std::vector<glm::vec4> larsen = test::read_rgba(larsen_pass.irradiance_texture(), size);
    settings.kernel = CausticKernel::Larsen;
    pass.set_settings(settings);
    pass.render(scene.camera(), scene.depth_texture().id());
    EXPECT_EQ(test::read_rgba(pass.irradiance_texture(), size), larsen);
    settings.kernel = CausticKernel::PhotonFootprints;
    pass.set_settings(settings);
    pass.render(scene.camera(), scene.depth_texture().id());
    EXPECT_EQ(test::read_rgba(pass.irradiance_texture(), size), out);
}

TEST_F(PhotonFootprintKernel, ASurfaceInFrontOfThePhotonsTakesNoneOfTheirLight) {
    // Photons on the plane z = 0; a card at z = 0.3 hides the left half of the view. The card's
    // pixels are within every disc's screen square, but their surface is 30 cm from the
    // photons: they read zero, and the plane's visible pixels the field.
    const glm::ivec2 size(160, 120);
    const test::RectScene scene(
        test::look_at({0.0f, 0.0f, 1.0f}, {0.0f, 0.0f, 0.0f}, size),
        {{{0, 0, 0}, {5, 0, 0}, {0, 5, 0}}, {{-1.0f, 0, 0.3f}, {1.0f, 0, 0}, {0, 1, 0}}});
    const std::vector<CausticPhoton> photons = uniform_photons(200, 4.0f);
    CausticPassSettings settings;
    settings.kernel = CausticKernel::PhotonFootprints;
    settings.footprint_scale = 30.0f;  // discs far wider than the card's edge is from them
    settings.world_radius = 0.5f;
    const std::vector<glm::vec4> out = test::filtered(settings, scene, size, photons);
    int card = 0;
    double plane = 0.0;
    int plane_pixels = 0;
    for (int y = 0; y < size.y; ++y) {
        for (int x = 0; x < size.x; ++x) {
            const float e = out[static_cast<std::size_t>(y * size.x + x)].g;
            if (scene.view_depth(x, y) < 0.8) {
                ASSERT_EQ(e, 0.0f) << "card pixel " << x << ", " << y;
                ++card;
            } else if (x > size.x / 2 + 40 && y > 10 && y < size.y - 10) {
                plane += e;
                ++plane_pixels;
            }
        }
    }
    EXPECT_GT(card, 1000);
    ASSERT_GT(plane_pixels, 100);
    EXPECT_NEAR(plane / plane_pixels, 1.0, 0.1);
}

TEST_F(PhotonFootprintKernel, AnUnknownFootprintTakesTheWidestRadiusAndBadSettingsAreRefused) {
    // One photon without a footprint, seen from 1 m: it is spread over world_radius (5 cm).
    const glm::ivec2 size(160, 160);
    const test::RectScene scene(test::look_at({0.0f, 0.0f, 1.0f}, {0.0f, 0.0f, 0.0f}, size),
                                {{{0, 0, 0}, {5, 0, 0}, {0, 5, 0}}});
    CausticPhoton photon;
    photon.power = glm::vec3(1.0f);
    CausticPassSettings settings;
    settings.kernel = CausticKernel::PhotonFootprints;
    const std::vector<glm::vec4> out = test::filtered(settings, scene, size, {photon});
    float reach = 0.0f;
    for (int y = 0; y < size.y; ++y) {
        for (int x = 0; x < size.x; ++x) {
            if (out[static_cast<std::size_t>(y * size.x + x)].g > 0.0f) {
                reach = std::max(reach, glm::length(glm::vec2(*scene.hit(x, y))));
            }
        }
    }
    EXPECT_GT(reach, 0.04f);
    EXPECT_LE(reach, 0.05f);
    EXPECT_NEAR(test::total_power(out, scene).g, 1.0, 0.02);

    // No disc wider than footprint_max_pixels: 8 pixels here, about 1.4 cm at 1 m, still
    // holding the photon's power.
    settings.footprint_max_pixels = 8.0f;
    const std::vector<glm::vec4> capped = test::filtered(settings, scene, size, {photon});
    int lit = 0;
    for (const glm::vec4& e : capped) {
        lit += e.g > 0.0f ? 1 : 0;
    }
    EXPECT_GT(lit, 100);
    EXPECT_LT(lit, 210) << "pi 8^2 = 201 pixels at most";
    EXPECT_NEAR(test::total_power(capped, scene).g, 1.0, 0.02);
    settings.footprint_max_pixels = 0.5f;
    EXPECT_THROW(CausticPass(settings, size), Error);
    settings.footprint_max_pixels = 64.0f;

    settings.footprint_scale = 0.0f;
    EXPECT_THROW(CausticPass(settings, size), Error);
    settings.footprint_scale = 1.0f;
    settings.footprint_min_pixels = 0.5f;
    EXPECT_THROW(CausticPass(settings, size), Error);
}

}  // namespace
