// Indirect light where an object rests on a light-mapped surface (issue 28): a box standing on a
// plane under a uniform sky, turned so that its edges cross texel centres. The plane's texels
// whose centres lie under the box are enclosed (the AIM finds every probe blocked); gathered at
// their centres they hold the box's unlit inside, and a bilinear lookup just beside the box
// reads them. The lookup there is compared with a gather at that very point (the same
// estimator, no texels), as a player sees the floor along a box's base: gathered at their
// centres, the texels under the box's edge showed as a black notch (ContactTexels).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>

#include "cube_scene.hpp"
#include "luxel/ecs/transform_system.hpp"
#include "luxel/lighting/components.hpp"
#include "luxel/lighting/core/cpu_gather.hpp"
#include "luxel/lighting/core/lighting_system.hpp"
#include "luxel/lighting/core/sky_radiance.hpp"
#include "luxel/runtime/jobs.hpp"
#include "map_test_scenes.hpp"
#include "sheet_mesh.hpp"

namespace {

using namespace luxel;

constexpr float kSide = 4.0f;
constexpr float kTexel = 0.1f;
constexpr float kHalf = 0.5f;  // the box's half edge
constexpr float kTurnDegrees = 30.0f;
constexpr float kSkyRadiance = 1.0f;

/// The light-mapped plane, 4 x 4 m at 10 cm texels, albedo 0.5, from the origin along +x, +z.
void add_plane(ecs::Registry& registry) {
    const ecs::Entity plane = registry.create();
    registry.emplace<scene::MeshInstance>(
        plane, luxel::testing::lightmapped_plane(kSide, 8, kTexel, 64, glm::vec3(0.5f)), 0);
    registry.emplace<lighting::LightmappedSurface>(plane,
                                                   luxel::testing::plane_layout(kSide, kTexel, 64));
    registry.emplace<ecs::Transform>(plane, ecs::Transform{});
}

/// A uniform sky of radiance kSkyRadiance.
void add_uniform_sky(ecs::Registry& registry) {
    const ecs::Entity sky = registry.create();
    registry.emplace<lighting::SkyLight>(
        sky, lighting::SkyLight{std::make_shared<const lighting::SkyRadiance>(
                                    lighting::SkyRadiance::uniform(glm::vec3(kSkyRadiance))),
                                1.0f, true});
}

/// The plane (4 x 4 m at 10 cm texels, albedo 0.5) under a uniform sky, a 1 m box of albedo 0.5
/// resting on its middle turned 30 degrees about the vertical, and the lighting system.
struct BoxOnPlane {
    ecs::Registry registry;
    ecs::TransformSystem transforms{registry};
    JobSystem jobs{2};
    std::unique_ptr<lighting::LightingSystem> lighting;
    double time = 0.0;

    explicit BoxOnPlane(bool contact_texels) {
        add_plane(registry);

        const ecs::Entity box = registry.create();
        registry.emplace<scene::MeshInstance>(
            box, luxel::testing::cube_scene(kHalf, luxel::testing::diffuse_material(0.5f)), 0);
        ecs::Transform placed;
        placed.translation = glm::vec3(0.5f * kSide, kHalf, 0.5f * kSide);
        placed.rotation = glm::angleAxis(glm::radians(kTurnDegrees), glm::vec3(0.0f, 1.0f, 0.0f));
        registry.emplace<ecs::Transform>(box, placed);

        add_uniform_sky(registry);
        transforms.update();
        lighting::LightingConfig config = luxel::testing::closed_form_config(256, 32);
        config.maps.contact_texels = contact_texels;
        // The box has no light map. Its own light in the gathers (UnmappedRadiance) is not what
        // this test measures, and the 4,096-ray gather it judges the lookups by reads the box
        // black: so do the maps here.
        config.gather.unmapped_radiance = false;
        lighting = std::make_unique<lighting::LightingSystem>(registry, jobs, config);
    }

    /// Converges, then runs frames until the IIM's refinement passes are in.
    void settle() {
        ASSERT_LE(luxel::testing::converge(transforms, *lighting, time), 100);
        for (int i = 0; i < 40; ++i) {
            time += 1.0 / 30.0;
            transforms.update();
            lighting->update(1e9, time);
        }
    }

    /// The plane's IIM irradiance (green) at world point `p` on it, read bilinearly between
    /// texel centres as the renderer reads it (shaders/render/iim.glsl).
    [[nodiscard]] double lookup(glm::vec3 p) const {
        const lighting::IlluminationMaps& maps = lighting->maps();
        const lighting::MapSurface& surface = maps.surfaces()[0];
        const std::int32_t page_id = maps.aim().surface_page.at(0);
        const lighting::RadiancePage& page =
            maps.iim_pages()[static_cast<std::size_t>(page_id)].current;
        // The plane's chart starts at page texel (2, 2); texel (2 + i, 2 + j) is centred at
        // x = (i + 0.5) texels, z = (j + 0.5) texels (checked in the test).
        const double fx = p.x / kTexel - 0.5 + 2.0;
        const double fy = p.z / kTexel - 0.5 + 2.0;
        const int x0 = static_cast<int>(std::floor(fx));
        const int y0 = static_cast<int>(std::floor(fy));
        const double wx = fx - x0;
        const double wy = fy - y0;
        const auto at = [&](int x, int y) { return static_cast<double>(page.at(x, y).g); };
        const double value = (1.0 - wy) * ((1.0 - wx) * at(x0, y0) + wx * at(x0 + 1, y0)) +
                             wy * ((1.0 - wx) * at(x0, y0 + 1) + wx * at(x0 + 1, y0 + 1));
        return surface.content == lighting::IimContent::Radiance
                   ? value * glm::pi<double>() / static_cast<double>(surface.albedo.g)
                   : value;
    }
};

struct ContactFigures {
    double worst = 1e30;  ///< smallest lookup / gather along the box's base
    double mean = 0.0;    ///< mean lookup / gather
    int points = 0;
    std::uint64_t enclosed = 0;
    std::uint64_t edges = 0;
};

/// Along the four edges of the box's base, 1 cm outside (a tenth of a texel), 160 points: the
/// IIM lookup against a 4,096-ray gather at the point itself.
ContactFigures along_the_base(bool contact_texels) {
    BoxOnPlane world(contact_texels);
    world.settle();
    ContactFigures figures;
    const lighting::IlluminationMaps& maps = world.lighting->maps();
    figures.enclosed = maps.counters().enclosed_texels;
    figures.edges = maps.counters().edge_texels;
    // The texel layout lookup() assumes.
    for (const lighting::SurfaceTexel& texel : maps.surfaces()[0].texels.texels) {
        EXPECT_NEAR(texel.position.x, (static_cast<float>(texel.x - 2) + 0.5f) * kTexel, 1e-4f);
        EXPECT_NEAR(texel.position.z, (static_cast<float>(texel.y - 2) + 0.5f) * kTexel, 1e-4f);
    }
    lighting::CpuGatherer truth(world.lighting->photons().ray_scene(), maps.aim(), {4096});
    const glm::quat turn = glm::angleAxis(glm::radians(kTurnDegrees), glm::vec3(0.0f, 1.0f, 0.0f));
    const glm::vec3 centre(0.5f * kSide, 0.0f, 0.5f * kSide);
    constexpr int kPerEdge = 40;
    constexpr float kOutside = 0.01f;
    for (int edge = 0; edge < 4; ++edge) {
        const float angle = glm::half_pi<float>() * static_cast<float>(edge);
        const glm::vec3 out = turn * glm::vec3(std::cos(angle), 0.0f, std::sin(angle));
        const glm::vec3 along = glm::vec3(-out.z, 0.0f, out.x);
        for (int k = 0; k < kPerEdge; ++k) {
            const float s = (static_cast<float>(k) + 0.5f) / kPerEdge * 1.8f - 0.9f;
            const glm::vec3 p = centre + out * (kHalf + kOutside) + along * (s * kHalf);
            const double gathered = truth.gather_one({p, glm::vec3(0.0f, 1.0f, 0.0f)}).g;
            EXPECT_GT(gathered, 0.2 * glm::pi<double>() * kSkyRadiance) << "beside a wall";
            const double ratio = world.lookup(p) / std::max(gathered, 1e-12);
            figures.worst = std::min(figures.worst, ratio);
            figures.mean += ratio;
            ++figures.points;
        }
    }
    figures.mean /= std::max(figures.points, 1);
    return figures;
}

TEST(ContactLight, TheFloorBesideABoxReadsTheLightThereNotTheBoxsUnlitInside) {
    const ContactFigures beside = along_the_base(true);
    const ContactFigures centres = along_the_base(false);
    std::printf(
        "[ figures  ] along a box's base (%d points, %llu texels enclosed): IIM lookup / gather "
        "worst %.3f mean %.3f with the edge texels gathered beside the box, worst %.3f mean "
        "%.3f gathered at their centres\n",
        beside.points, static_cast<unsigned long long>(beside.enclosed), beside.worst, beside.mean,
        centres.worst, centres.mean);
    ASSERT_EQ(beside.points, 160);
    EXPECT_GT(beside.enclosed, 0u);
    // The ring under the box's edges: texels with an open neighbour (of the 200 enclosed at the
    // first rebuild, about its perimeter in texels); none without the contact texels.
    EXPECT_GT(beside.edges, 20u);
    EXPECT_LT(beside.edges, beside.enclosed);
    EXPECT_EQ(centres.edges, 0u);
    // Gathered beside the box, the texels under its edge hold the light there: the lookup agrees
    // with the point's own gather up to the bilinear blend with texels further out, which see
    // more sky (it reads a little bright, never dark).
    EXPECT_GT(beside.worst, 0.85);
    EXPECT_LT(beside.mean, 1.2);
    // Gathered at their centres they hold the box's black inside, and the lookup beside the box
    // reads them (the notch). The test sees it.
    EXPECT_LT(centres.worst, 0.5);
}

/// The enclosed texels the AIM finds on the 4 x 4 m plane under a 3 x 3 m sheet 0.4 m above
/// its middle, facing up, of glass (transmission 1) or of a diffuse grey.
std::uint64_t enclosed_under_sheet(bool glass) {
    ecs::Registry registry;
    ecs::TransformSystem transforms{registry};
    JobSystem jobs{2};
    add_plane(registry);
    auto sheet = std::make_shared<scene::Scene>();
    scene::Material material = luxel::testing::diffuse_material(0.5f);
    if (glass) {
        material.transmission = 1.0f;
        material.roughness = 0.0f;
        material.ior = 1.33f;
    }
    sheet->materials.push_back(material);
    scene::Primitive quad = luxel::testing::sheet_primitive(2, {0.5f, 0.4f, 0.5f}, 3.0f);
    quad.material = 0;
    sheet->meshes.push_back({"sheet", {quad}});
    const ecs::Entity sheet_entity = registry.create();
    registry.emplace<scene::MeshInstance>(sheet_entity, sheet, 0);
    registry.emplace<ecs::Transform>(sheet_entity, ecs::Transform{});
    add_uniform_sky(registry);
    transforms.update();
    lighting::LightingSystem lighting(registry, jobs, luxel::testing::closed_form_config(64, 16));
    double time = 0.0;
    EXPECT_LE(luxel::testing::converge(transforms, lighting, time), 100);
    return lighting.maps().counters().enclosed_texels;
}

TEST(ContactLight, AFloorUnderWaterIsNotEnclosed) {
    // The floor's middle sees the sheet from behind along its normal and around it, which is
    // how the inside of a closed object looks; light passes through glass and water, so under a
    // glass sheet no texel is enclosed. Under an opaque one the middle is.
    EXPECT_EQ(enclosed_under_sheet(true), 0u);
    EXPECT_GT(enclosed_under_sheet(false), 100u);
}

}  // namespace
