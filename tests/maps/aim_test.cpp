// The AIM against analytic irradiance: a light-mapped plane receives photons drawn from a known
// field, and each texel's reconstructed radiance must give that field back, right up to the
// plane's edges and corners.

#include <cmath>
#include <functional>
#include <random>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "cube_scene.hpp"
#include "luxel/lighting/core/surface_footprint.hpp"
#include "map_test_scenes.hpp"

namespace {

using namespace luxel;

constexpr float kSide = 2.0f;
constexpr float kTexel = 0.05f;
constexpr int kPage = 64;
const glm::vec3 kAlbedo(0.8f, 0.5f, 0.25f);

struct FieldResult {
    double worst_interior = 0.0;     ///< largest |E/E_true - 1| at least 2 texels from the edge
    double worst_border_dark = 0.0;  ///< largest 1 - E/E_true on the outer ring of texels
    int texels = 0;
};

/// Photons on a jittered `per_side` x `per_side` grid over the plane, each carrying
/// E(x) times its cell's area (stratified, as a QMC photon set is), then the AIM.
FieldResult run_field(const std::function<double(double, double)>& irradiance, int per_side,
                      std::uint32_t nearest) {
    lighting::IlluminationSettings settings;
    settings.density.nearest = nearest;
    luxel::testing::PlaneWorld world(kSide, kTexel, kPage, kAlbedo, settings);
    std::mt19937 random(7);
    std::uniform_real_distribution<double> jitter(0.0, 1.0);
    const double cell = kSide / per_side;
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> powers;
    for (int j = 0; j < per_side; ++j) {
        for (int i = 0; i < per_side; ++i) {
            const double x = (i + jitter(random)) * cell;
            const double z = (j + jitter(random)) * cell;
            positions.emplace_back(x, 0.0, z);
            powers.emplace_back(static_cast<float>(irradiance(x, z) * cell * cell));
        }
    }
    world.store(positions, powers);
    const auto requests = world.maps->aim_requests();
    EXPECT_EQ(requests.size(), 1u);
    world.maps->rebuild_aim(0);
    EXPECT_TRUE(world.maps->aim_requests().empty()) << "delta_f must reset after a rebuild";

    FieldResult result;
    const lighting::MapSurface& surface = world.maps->surfaces()[0];
    const lighting::RadiancePage& page = world.maps->aim().pages.at(0);
    const int last = static_cast<int>(kSide / kTexel) - 1;
    for (const lighting::SurfaceTexel& texel : surface.texels.texels) {
        const double expected = irradiance(texel.position.x, texel.position.z);
        const glm::vec3 radiance = page.at(texel.x, texel.y);
        for (int c = 0; c < 3; ++c) {
            const double e = radiance[c] * glm::pi<double>() / kAlbedo[c];
            const double ratio = e / expected;
            const int u = texel.x - 2;
            const int v = texel.y - 2;
            const bool interior = u >= 2 && v >= 2 && u <= last - 2 && v <= last - 2;
            const bool border = u == 0 || v == 0 || u == last || v == last;
            if (interior) {
                result.worst_interior = std::max(result.worst_interior, std::abs(ratio - 1.0));
            }
            if (border) {
                result.worst_border_dark = std::max(result.worst_border_dark, 1.0 - ratio);
            }
        }
        ++result.texels;
    }
    return result;
}

void expect_field(const char* name, const FieldResult& result) {
    EXPECT_EQ(result.texels, 40 * 40) << name;
    EXPECT_LE(result.worst_interior, 0.03) << name << ": interior error";
    EXPECT_LE(result.worst_border_dark, 0.10) << name << ": edges and corners too dark";
    std::printf("[ figures  ] %s: worst interior error %.2f%%, worst border darkening %.2f%%\n",
                name, 100.0 * result.worst_interior, 100.0 * result.worst_border_dark);
}

TEST(AimAnalytic, ConstantField) {
    expect_field("constant 10 W/m^2", run_field([](double, double) { return 10.0; }, 400, 400));
}

TEST(AimAnalytic, LinearRamp) {
    expect_field("ramp 2..12 W/m^2",
                 run_field([](double x, double) { return 2.0 + 5.0 * x; }, 400, 400));
}

TEST(AimAnalytic, InverseSquareFromAPoint) {
    // A 100 W isotropic point source 1 m above the plane's centre: E = I cos / d^2.
    const double intensity = 100.0 / (4.0 * glm::pi<double>());
    const auto field = [&](double x, double z) {
        const double dx = x - 1.0;
        const double dz = z - 1.0;
        const double d2 = dx * dx + dz * dz + 1.0;
        return intensity / d2 / std::sqrt(d2);
    };
    expect_field("inverse square", run_field(field, 400, 400));
}

TEST(AimAnalytic, NoPhotonsGiveZeroNotNaN) {
    luxel::testing::PlaneWorld world(kSide, kTexel, kPage, kAlbedo);
    world.maps->rebuild_aim(0);
    for (const glm::vec3& texel : world.maps->aim().pages.at(0).texels) {
        EXPECT_EQ(texel, glm::vec3(0.0f));
    }
}

TEST(AimAnalytic, FewerThanNPhotonsUseTheCappedRadius) {
    lighting::IlluminationSettings settings;
    settings.density.nearest = 50;
    settings.max_radius_texels = 10.0f;  // 0.5 m at 5 cm texels
    settings.density.kernel = lighting::DensityKernel::Disc;
    luxel::testing::PlaneWorld world(kSide, kTexel, kPage, kAlbedo, settings);
    // 3 photons of 1 W near the centre: a texel there sees all 3 in a 0.5 m disc.
    world.store({{1.0f, 0.0f, 1.0f}, {1.05f, 0.0f, 1.0f}, {1.0f, 0.0f, 1.05f}},
                {glm::vec3(1.0f), glm::vec3(1.0f), glm::vec3(1.0f)});
    world.maps->rebuild_aim(0);
    const lighting::MapSurface& surface = world.maps->surfaces()[0];
    const auto& page = world.maps->aim().pages.at(0);
    for (const auto& texel : surface.texels.texels) {
        if (glm::distance(texel.position, glm::vec3(1.0f, 0.0f, 1.0f)) < 0.01f) {
            const double e = page.at(texel.x, texel.y).x * glm::pi<double>() / kAlbedo.x;
            EXPECT_NEAR(e, 3.0 / (glm::pi<double>() * 0.25), 1e-4);
        }
        EXPECT_TRUE(std::isfinite(page.at(texel.x, texel.y).x));
    }
}

TEST(AimEnclosure, TexelsUnderAnObjectGetNoLightAndThoseUnderItsEdgeTheLightBesideIt) {
    // A 0.5 m cube resting 1 mm above the middle of the plane, and photons of a constant
    // 10 W/m^2 everywhere, under the cube too (stored by the test, as light leaking in would
    // be). The texels under the cube are enclosed (every probe ray meets the cube within 1.5
    // texels): those deeper than a texel get no light, and the ring under its edge (edge
    // texels, docs/METHOD.md §6.12) the light at the open point beside it; those beside it keep
    // the field: the density estimate there is the plain one.
    luxel::testing::PlaneWorld world(kSide, kTexel, kPage, kAlbedo);
    const ecs::Entity cube = world.registry.create();
    world.registry.emplace<scene::MeshInstance>(
        cube, luxel::testing::cube_scene(0.25f, scene::Material{}), 0);
    ecs::Transform placed;
    placed.translation = glm::vec3(1.0f, 0.251f, 1.0f);
    world.registry.emplace<ecs::Transform>(cube, placed);
    world.transforms.update();
    world.photons->sync();
    world.maps->sync();
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> powers;
    const int per_side = 400;
    const double cell = kSide / per_side;
    for (int j = 0; j < per_side; ++j) {
        for (int i = 0; i < per_side; ++i) {
            positions.emplace_back((i + 0.5) * cell, 0.0, (j + 0.5) * cell);
            powers.emplace_back(static_cast<float>(10.0 * cell * cell));
        }
    }
    world.store(positions, powers);
    world.maps->rebuild_aim(0);
    const lighting::RadiancePage& page = world.maps->aim().pages.at(0);
    int under = 0;
    int deep = 0;
    int beside = 0;
    double worst_beside = 0.0;
    double worst_edge = 0.0;
    for (const lighting::SurfaceTexel& texel : world.maps->surfaces()[0].texels.texels) {
        // Distance of the texel centre outside the cube's footprint [0.75, 1.25]^2 (negative
        // inside).
        const double outside =
            std::max(std::abs(texel.position.x - 1.0), std::abs(texel.position.z - 1.0)) - 0.25;
        const glm::vec3 radiance = page.at(texel.x, texel.y);
        if (outside < -kTexel) {
            EXPECT_EQ(radiance, glm::vec3(0.0f))
                << "under the cube at " << texel.position.x << ", " << texel.position.z;
            ++under;
            ++deep;
        } else if (outside < -0.01) {
            const double e = radiance.g * glm::pi<double>() / kAlbedo.g;
            worst_edge = std::max(worst_edge, std::abs(e / 10.0 - 1.0));
            ++under;
        } else if (outside > kTexel) {
            const double e = radiance.g * glm::pi<double>() / kAlbedo.g;
            const int u = texel.x - 2;
            const int v = texel.y - 2;
            const int last = static_cast<int>(kSide / kTexel) - 1;
            if (u >= 2 && v >= 2 && u <= last - 2 && v <= last - 2) {
                worst_beside = std::max(worst_beside, std::abs(e / 10.0 - 1.0));
                ++beside;
            }
        }
    }
    // 10 x 10 texels of 5 cm have their centres under the 0.5 m cube, and only they are
    // enclosed: the ring around it sees the sky half of its probes.
    EXPECT_EQ(under, 10 * 10);
    EXPECT_EQ(deep, 8 * 8);
    EXPECT_EQ(world.maps->counters().enclosed_texels, static_cast<std::uint64_t>(under));
    EXPECT_GT(beside, 1000);
    // As the constant field's interior (AimAnalytic.ConstantField): 3%.
    EXPECT_LE(worst_beside, 0.03);
    // The edge texels read the field at the cube's edge (the test's photons lie under the cube
    // too, so the estimate there is the plain one).
    EXPECT_LE(worst_edge, 0.05);
    std::printf(
        "[ figures  ] cube on the plane: %d texels under it (%d deeper than a texel, dark), %llu "
        "enclosed in all; worst error beside it %.2f%%, of the ring under its edge %.2f%%\n",
        under, deep, static_cast<unsigned long long>(world.maps->counters().enclosed_texels),
        100.0 * worst_beside, 100.0 * worst_edge);
}

TEST(SurfaceFootprint, CornerEdgeAndInterior) {
    const auto plane = luxel::testing::lightmapped_plane(kSide, 4, kTexel, kPage, kAlbedo);
    const auto& primitive = plane->meshes[0].primitives[0];
    const lighting::SurfaceTexels texels = lighting::rasterize_surface(primitive, 0, kPage);
    ASSERT_EQ(texels.texels.size(), 1600u);
    EXPECT_NEAR(texels.metres_per_texel, kTexel, 1e-5);
    const lighting::SurfaceFootprint footprint(primitive, texels);
    // Texel (0, 0) of the chart is a corner: its point is 0.5 texel in from both edges.
    const std::size_t corner = 0;
    const std::size_t edge = 20;  // row 0, column 20
    const std::size_t centre = 20 * 40 + 20;
    EXPECT_NEAR(footprint.fraction(corner, 10.0), 0.25 + 0.05, 0.05);
    EXPECT_NEAR(footprint.fraction(edge, 10.0), 0.5 + 0.03, 0.04);
    EXPECT_DOUBLE_EQ(footprint.fraction(centre, 10.0), 1.0);
    EXPECT_DOUBLE_EQ(footprint.fraction(corner, 0.4), 1.0);  // the disc stays inside
}

}  // namespace
