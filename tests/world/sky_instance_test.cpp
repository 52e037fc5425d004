// A level's sky becomes an entity with a SkyLight (world/sky.hpp): the level's own, or the one
// --sky gives in its place; a daylight sky's sun is the level's brightest directional light.

#include <cmath>
#include <fstream>
#include <memory>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>

#include "luxel/ecs/transform.hpp"
#include "luxel/lighting/components.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/runtime/image.hpp"
#include "luxel/world/scene_instance.hpp"
#include "luxel/world/sky.hpp"
#include "temp_dir.hpp"

namespace {

using namespace luxel;

/// A scene of two directional lights: a dim one straight down and a bright one whose node is
/// turned so it shines down along -z tilted 60 degrees from the vertical.
std::shared_ptr<scene::Scene> two_suns(bool bright_enabled = true) {
    auto s = std::make_shared<scene::Scene>();
    s->lights.push_back(scene::Light::directional_from_irradiance(glm::vec3(0.5f)));
    s->lights.push_back(scene::Light::directional_from_irradiance(glm::vec3(3.0f)));
    scene::Node down;
    down.name = "dim sun";
    down.light = 0;
    down.rotation = glm::angleAxis(glm::radians(-90.0f), glm::vec3(1, 0, 0));  // -z -> -y
    scene::Node tilted;
    tilted.name = "sun";
    tilted.light = 1;
    tilted.rotation = glm::angleAxis(glm::radians(-30.0f), glm::vec3(1, 0, 0));
    tilted.flags.light_enabled = bright_enabled;
    s->nodes = {down, tilted};
    s->roots = {0, 1};
    return s;
}

const lighting::SkyLight* sky_of(const ecs::Registry& registry, const world::SceneInstance& i) {
    return i.sky == ecs::null_entity ? nullptr : registry.try_get<lighting::SkyLight>(i.sky);
}

TEST(SkyInstance, TheLevelsSkyOrTheOneGivenInItsPlace) {
    auto level = two_suns();
    level->sky = scene::parse_sky("uniform:0.5");
    level->sky.scale = 2.0f;
    {
        ecs::Registry registry;
        const world::SceneInstance instance = world::instantiate(registry, level);
        const lighting::SkyLight* sky = sky_of(registry, instance);
        ASSERT_NE(sky, nullptr);
        EXPECT_EQ(sky->scale, 2.0f);
        EXPECT_EQ(sky->radiance->radiance({0.0f, 1.0f, 0.0f}), glm::vec3(0.5f));
    }
    {
        ecs::Registry registry;
        world::InstantiateOptions options;
        options.sky = scene::parse_sky("uniform:0.1,0.2,0.3");
        const world::SceneInstance instance = world::instantiate(registry, level, options);
        const lighting::SkyLight* sky = sky_of(registry, instance);
        ASSERT_NE(sky, nullptr);
        EXPECT_EQ(sky->scale, 1.0f);
        EXPECT_EQ(sky->radiance->radiance({0.0f, 1.0f, 0.0f}), glm::vec3(0.1f, 0.2f, 0.3f));
    }
    {
        ecs::Registry registry;
        world::InstantiateOptions options;
        options.sky = scene::parse_sky("none");
        const world::SceneInstance instance = world::instantiate(registry, level, options);
        EXPECT_EQ(instance.sky, ecs::null_entity);
        EXPECT_EQ(registry.size<lighting::SkyLight>(), 0u);
    }
}

TEST(SkyInstance, ADaylightSkyFollowsTheBrightestEnabledSun) {
    const glm::vec3 towards = world::sun_direction(*two_suns());
    // The bright sun's node turned -30 degrees about x: its +z axis (towards the sun) is
    // (0, sin 30, cos 30).
    EXPECT_NEAR(towards.x, 0.0f, 1e-5f);
    EXPECT_NEAR(towards.y, 0.5f, 1e-5f);
    EXPECT_NEAR(towards.z, std::sqrt(0.75f), 1e-5f);
    // Switched off, it is not the sun: the dim one (straight down, so the sun at the zenith).
    EXPECT_NEAR(world::sun_direction(*two_suns(false)).y, 1.0f, 1e-5f);
    // Without a directional light: 45 degrees up.
    EXPECT_NEAR(world::sun_direction(scene::Scene{}).y, std::sqrt(0.5f), 1e-5f);

    auto level = two_suns();
    level->sky = scene::parse_sky("daylight:1.5");
    ecs::Registry registry;
    const world::SceneInstance instance = world::instantiate(registry, level);
    const lighting::SkyLight* sky = sky_of(registry, instance);
    ASSERT_NE(sky, nullptr);
    // Brighter near the sun than on the other side of the sky at the same height.
    const glm::vec3 near_sun = sky->radiance->radiance(glm::vec3(0.0f, 0.6f, 0.8f));
    const glm::vec3 away = sky->radiance->radiance(glm::vec3(0.0f, 0.6f, -0.8f));
    EXPECT_GT(near_sun.g, 2.0f * away.g);
}

TEST(SkyInstance, ADaylightSkyTurnsWithItsSun) {
    // Time of day: the sun's node turns, update_sky rebuilds the sky for its new direction
    // (the same sky daylight_sky makes for it), once; a turn under a quarter degree, a uniform
    // sky and a sky whose sun is gone are left alone.
    auto level = two_suns();
    level->sky = scene::parse_sky("daylight:1.5,4");
    ecs::Registry registry;
    const world::SceneInstance instance = world::instantiate(registry, level);
    const ecs::Entity sun = instance.find("sun");
    const auto* daylight = registry.try_get<world::DaylightSun>(instance.sky);
    ASSERT_NE(daylight, nullptr);
    EXPECT_EQ(daylight->sun, sun);
    EXPECT_EQ(world::update_sky(registry), 0u);  // the sun has not moved
    const auto before = sky_of(registry, instance)->radiance;

    // Evening: from 30 degrees up to 10 degrees up.
    registry.patch<ecs::Transform>(sun, [](ecs::Transform& t) {
        t.rotation = glm::angleAxis(glm::radians(-10.0f), glm::vec3(1, 0, 0));
    });
    EXPECT_EQ(world::update_sky(registry), 1u);
    const lighting::SkyLight* sky = sky_of(registry, instance);
    ASSERT_NE(sky->radiance, before);
    const glm::vec3 towards(0.0f, std::sin(glm::radians(10.0f)), std::cos(glm::radians(10.0f)));
    const lighting::SkyRadiance expected = lighting::daylight_sky(towards, 4.0f, 1.5f);
    for (const glm::vec3& d : {glm::vec3(0.0f, 0.2f, 1.0f), glm::vec3(0.5f, 0.8f, -0.3f),
                               glm::vec3(-1.0f, 0.1f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f)}) {
        const glm::vec3 got = sky->radiance->radiance(glm::normalize(d));
        const glm::vec3 want = expected.radiance(glm::normalize(d));
        EXPECT_NEAR(got.g, want.g, 1e-4f * want.g) << d.x << " " << d.y << " " << d.z;
    }
    // Low sun: the horizon by it is brighter than the zenith.
    EXPECT_GT(sky->radiance->radiance(glm::normalize(glm::vec3(0.0f, 0.2f, 1.0f))).g,
              sky->radiance->radiance(glm::vec3(0.0f, 1.0f, 0.0f)).g);
    EXPECT_EQ(world::update_sky(registry), 0u);

    registry.patch<ecs::Transform>(sun, [](ecs::Transform& t) {
        t.rotation = glm::angleAxis(glm::radians(-10.1f), glm::vec3(1, 0, 0));
    });
    EXPECT_EQ(world::update_sky(registry), 0u);
    registry.destroy(sun);
    EXPECT_EQ(world::update_sky(registry), 0u);

    // A uniform sky does not follow anything.
    auto uniform = two_suns();
    uniform->sky = scene::parse_sky("uniform:1");
    ecs::Registry other;
    const world::SceneInstance plain = world::instantiate(other, uniform);
    EXPECT_FALSE(other.has<world::DaylightSun>(plain.sky));
}

TEST(SkyInstance, TheGroundIsLitByTheSkyAndBySunAsItIsNow) {
    // A ground of albedo 0.2 below a daylight sky of 1.5 W/m^2 and the 3 W/m^2 sun 30 degrees
    // up: radiance 0.2 (E_sky + 3 sin 30) / pi. The sun sinks to 10 degrees: the ground darkens
    // with it; the sun switched off: the sky alone lights it.
    auto level = two_suns();
    level->sky = scene::parse_sky("daylight:1.5,3,ground=0.2");
    ecs::Registry registry;
    const world::SceneInstance instance = world::instantiate(registry, level);
    const glm::vec3 down(0.0f, -1.0f, 0.0f);
    auto ground = [&] { return sky_of(registry, instance)->radiance->radiance(down); };
    auto expected = [](float elevation_degrees, float sun) {
        const glm::vec3 towards(0.0f, std::sin(glm::radians(elevation_degrees)),
                                std::cos(glm::radians(elevation_degrees)));
        const glm::dvec3 e_sky =
            lighting::horizontal_irradiance(lighting::daylight_sky(towards, 3.0f, 1.5f));
        return 0.2 * (e_sky.g + sun * std::sin(glm::radians(elevation_degrees))) /
               glm::pi<double>();
    };
    EXPECT_NEAR(ground().g, expected(30.0f, 3.0f), 1e-4 * expected(30.0f, 3.0f));
    const ecs::Entity sun = instance.find("sun");
    registry.patch<ecs::Transform>(sun, [](ecs::Transform& t) {
        t.rotation = glm::angleAxis(glm::radians(-10.0f), glm::vec3(1, 0, 0));
    });
    ASSERT_EQ(world::update_sky(registry), 1u);
    EXPECT_NEAR(ground().g, expected(10.0f, 3.0f), 1e-4 * expected(10.0f, 3.0f));
    EXPECT_LT(ground().g, expected(30.0f, 3.0f));
    // Switched off without turning: the sky is rebuilt all the same, its ground lit by itself.
    registry.patch<lighting::DirectionalLight>(
        sun, [](lighting::DirectionalLight& d) { d.enabled = false; });
    ASSERT_EQ(world::update_sky(registry), 1u);
    EXPECT_NEAR(ground().g, expected(10.0f, 0.0f), 1e-4 * expected(10.0f, 0.0f));
    EXPECT_EQ(world::update_sky(registry), 0u);
    // A sun of NaN irradiance lights the ground with nothing, once: no rebuild every frame.
    registry.patch<lighting::DirectionalLight>(sun, [](lighting::DirectionalLight& d) {
        d.enabled = true;
        d.irradiance = glm::vec3(std::nanf(""));
    });
    EXPECT_EQ(world::update_sky(registry), 0u);  // the same as off: nothing to rebuild
    EXPECT_EQ(world::update_sky(registry), 0u);
    EXPECT_TRUE(std::isfinite(ground().g));
    // Without a ground, below the horizon stays black.
    auto plain = two_suns();
    plain->sky = scene::parse_sky("daylight:1.5,3");
    ecs::Registry other;
    const world::SceneInstance bare = world::instantiate(other, plain);
    EXPECT_EQ(sky_of(other, bare)->radiance->radiance(down), glm::vec3(0.0f));
}

TEST(SkyInstance, AnEnvironmentMapIsReadAndABadOneIsRefusedNamingTheFile) {
    luxel::testing::TempDir dir;
    Image image(8, 4, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    image.set_pixel(3, 0, glm::vec4(5.0f, 4.0f, 3.0f, 1.0f));  // a bright cell at the zenith
    write_exr(dir / "sky.exr", image);
    const auto sky = world::make_sky_radiance(scene::parse_sky((dir / "sky.exr").string()), {});
    ASSERT_NE(sky, nullptr);
    EXPECT_EQ(sky->width(), 8);
    EXPECT_EQ(sky->height(), 4);
    // Row 0 is the zenith's, column 3 azimuths 135 to 180 degrees from +x towards +z.
    const float phi = glm::radians(157.5f);
    EXPECT_EQ(sky->radiance(glm::vec3(0.3f * std::cos(phi), 1.0f, 0.3f * std::sin(phi))),
              glm::vec3(5.0f, 4.0f, 3.0f));
    EXPECT_EQ(sky->radiance(glm::vec3(0.0f, -1.0f, 0.0f)), glm::vec3(0.0f));

    for (const char* bad : {"absent.exr", "not-an-image.exr"}) {
        if (std::string(bad) == "not-an-image.exr") {
            std::ofstream(dir / bad) << "plain text";
        }
        try {
            (void)world::make_sky_radiance(scene::parse_sky((dir / bad).string()), {});
            ADD_FAILURE() << bad << " was read";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
        }
    }
}

}  // namespace
