// glTF scenes into the ECS: entities, components, hierarchy, animation and light switches.

#include <cmath>
#include <memory>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "luxel/ecs/hierarchy.hpp"
#include "luxel/ecs/transform_system.hpp"
#include "luxel/lighting/components.hpp"
#include "luxel/lighting/core/photon_world.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/scene/lightmap_layout.hpp"
#include "luxel/world/animation_system.hpp"
#include "luxel/world/scene_instance.hpp"

namespace {

using namespace luxel;

scene::Primitive triangle() {
    scene::Primitive p;
    p.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    p.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    p.indices = {0, 1, 2};
    return p;
}

/// A small scene: a root with a child mesh (glass), an emissive panel, a point light with a
/// switch, a spot light that starts off, a camera, and an animation sliding the root.
std::shared_ptr<scene::Scene> make_scene() {
    auto s = std::make_shared<scene::Scene>();
    scene::Material glass;
    glass.name = "glass";
    glass.metallic = 0.0f;
    glass.roughness = 0.0f;
    glass.transmission = 1.0f;
    glass.ior = 1.33f;
    scene::Material panel;
    panel.name = "panel";
    panel.metallic = 0.0f;
    panel.emissive = glm::vec3(1.0f, 0.5f, 0.25f);
    panel.emissive_strength = 4.0f;
    s->materials = {glass, panel};
    s->meshes.resize(2);
    s->meshes[0].primitives.push_back(triangle());
    s->meshes[0].primitives[0].material = 0;
    s->meshes[1].primitives.push_back(triangle());
    s->meshes[1].primitives[0].material = 1;

    scene::Light point;
    point.name = "bulb";
    point.intensity = scene::kLumensPerWatt;  // 1 W/sr -> 4 pi W
    scene::Light spot = scene::Light::spot_from_power(glm::vec3(10.0f), 0.2f, 0.4f);
    s->lights = {point, spot};
    s->cameras.resize(1);

    s->nodes.resize(6);
    s->nodes[0].name = "root";
    s->nodes[0].translation = {1.0f, 0.0f, 0.0f};
    s->nodes[0].children = {1};
    s->nodes[1].name = "glass child";
    s->nodes[1].parent = 0;
    s->nodes[1].translation = {0.0f, 2.0f, 0.0f};
    s->nodes[1].mesh = 0;
    s->nodes[2].name = "panel";
    s->nodes[2].mesh = 1;
    s->nodes[3].name = "bulb";
    s->nodes[3].light = 0;
    s->nodes[3].flags.raw["switch"] = {{"period", 4.0}, {"on", 1.0}, {"phase", 0.0}};
    s->nodes[4].name = "spot";
    s->nodes[4].light = 1;
    s->nodes[4].flags.light_enabled = false;
    s->nodes[5].name = "camera";
    s->nodes[5].camera = 0;
    s->roots = {0, 2, 3, 4, 5};

    scene::Animation slide;
    slide.name = "slide";
    slide.samplers.push_back({{0.0f, 2.0f},
                              {glm::vec4(1, 0, 0, 0), glm::vec4(3, 0, 0, 0)},
                              scene::Interpolation::Linear});
    slide.channels.push_back({0, scene::AnimatedProperty::Translation, 0});
    s->animations.push_back(slide);
    s->validate();
    return s;
}

TEST(SceneInstance, CreatesEntitiesComponentsAndHierarchy) {
    ecs::Registry registry;
    const auto source = make_scene();
    const auto instance = world::instantiate(registry, source);
    ASSERT_EQ(instance.nodes.size(), 6u);
    ASSERT_EQ(instance.animations.size(), 1u);

    const ecs::Entity root = instance.find("root");
    const ecs::Entity child = instance.find("glass child");
    EXPECT_EQ(ecs::parent_of(registry, child), root);
    EXPECT_EQ(registry.get<scene::Name>(child).value, "glass child");

    const auto& generator = registry.get<lighting::CausticGenerator>(child);
    EXPECT_FLOAT_EQ(generator.ior, 1.33f);
    EXPECT_FLOAT_EQ(generator.transmission, 1.0f);
    EXPECT_EQ(registry.get<scene::MeshInstance>(child).geometry().primitives.size(), 1u);
    EXPECT_FALSE(registry.has<lighting::AreaLight>(child));

    const ecs::Entity panel = instance.find("panel");
    EXPECT_TRUE(registry.has<lighting::AreaLight>(panel));
    EXPECT_FALSE(registry.has<lighting::CausticGenerator>(panel));
    EXPECT_FALSE(registry.has<scene::Dynamic>(panel));

    const auto& bulb = registry.get<lighting::PointLight>(instance.find("bulb"));
    EXPECT_NEAR(bulb.power.r, 4.0f * glm::pi<float>(), 1e-4f);
    EXPECT_TRUE(bulb.enabled);
    EXPECT_TRUE(registry.has<world::LightSwitch>(instance.find("bulb")));
    const auto& spot = registry.get<lighting::SpotLight>(instance.find("spot"));
    EXPECT_NEAR(spot.power.g, 10.0f, 1e-3f);
    EXPECT_FALSE(spot.enabled);
    EXPECT_TRUE(registry.has<scene::CameraComponent>(instance.find("camera")));

    // The animated root and its child are dynamic; nothing else is.
    EXPECT_TRUE(registry.has<scene::Dynamic>(root));
    EXPECT_TRUE(registry.has<scene::Dynamic>(child));
    EXPECT_FALSE(registry.has<scene::Dynamic>(instance.find("bulb")));

    ecs::TransformSystem transforms(registry);
    transforms.update();
    const glm::vec3 child_world = registry.get<ecs::WorldTransform>(child).position();
    EXPECT_FLOAT_EQ(child_world.x, 1.0f);
    EXPECT_FLOAT_EQ(child_world.y, 2.0f);
}

TEST(AnimationSystem, MovesTargetsAndReportsThemAsChanged) {
    ecs::Registry registry;
    const auto instance = world::instantiate(registry, make_scene());
    ecs::TransformSystem transforms(registry);
    transforms.update();
    auto moved = registry.observe<ecs::WorldTransform>();

    world::update_animations(registry, 0.5);  // a quarter of the way: x = 1.5
    transforms.update();
    const ecs::Entity root = instance.find("root");
    const ecs::Entity child = instance.find("glass child");
    EXPECT_FLOAT_EQ(registry.get<ecs::Transform>(root).translation.x, 1.5f);
    EXPECT_FLOAT_EQ(registry.get<ecs::WorldTransform>(child).position().x, 1.5f);
    // Exactly the root and its child moved in the world.
    std::vector<ecs::Entity> updated(moved.updated().begin(), moved.updated().end());
    EXPECT_EQ(updated.size(), 2u);

    // Looping wraps the time: 2.5 s into a 2 s animation samples at 0.5 s... plus 0.5 above.
    world::update_animations(registry, 2.0);
    EXPECT_FLOAT_EQ(registry.get<ecs::Transform>(root).translation.x, 1.5f);
    const auto& player = registry.get<world::AnimationPlayer>(instance.animations[0]);
    EXPECT_NEAR(player.time, 0.5, 1e-12);
}

TEST(AnimationSystem, LongRunsKeepTheTimeBoundedAndExact) {
    ecs::Registry registry;
    const auto instance = world::instantiate(registry, make_scene());
    // 100,000 frames at 60 Hz: 1666.67 s, i.e. 833 loops and 0.333... s into the next.
    for (int frame = 0; frame < 100'000; ++frame) {
        world::update_animations(registry, 1.0 / 60.0);
    }
    const auto& player = registry.get<world::AnimationPlayer>(instance.animations[0]);
    EXPECT_GE(player.time, 0.0);
    EXPECT_LT(player.time, 2.0);
    EXPECT_NEAR(player.time, std::fmod(100'000.0 / 60.0, 2.0), 1e-9);
}

TEST(AnimationSystem, NonLoopingStopsAtTheEndAndStaleTargetsAreSkipped) {
    ecs::Registry registry;
    const auto instance = world::instantiate(registry, make_scene());
    auto& player = registry.get<world::AnimationPlayer>(instance.animations[0]);
    player.loop = false;
    registry.destroy(instance.find("glass child"));  // not a target: nothing changes
    world::update_animations(registry, 10.0);
    EXPECT_FALSE(registry.get<world::AnimationPlayer>(instance.animations[0]).playing);
    EXPECT_FLOAT_EQ(registry.get<ecs::Transform>(instance.find("root")).translation.x, 3.0f);
    registry.destroy(instance.find("root"));
    auto& again = registry.get<world::AnimationPlayer>(instance.animations[0]);
    again.playing = true;
    EXPECT_NO_THROW(world::update_animations(registry, 0.1));
}

TEST(AnimationSystem, APoseTheRayTracerCannotInvertIsNeverApplied) {
    // The panel is scaled through 0 (and flipped); the spot's keys are finite, but the line
    // between them overflows float. Scene::validate refuses the second; playback must not pass
    // either on to the instance transforms in case a scene bypasses it.
    std::shared_ptr<scene::Scene> source = make_scene();
    scene::Animation& animation = source->animations[0];
    animation.samplers.push_back({{0.0f, 2.0f},
                                  {glm::vec4(1, 1, 1, 0), glm::vec4(-1, 0, 1, 0)},
                                  scene::Interpolation::Linear});
    animation.channels.push_back({2, scene::AnimatedProperty::Scale, 1});
    animation.samplers.push_back({{0.0f, 2.0f},
                                  {glm::vec4(-3e38f, 0, 0, 0), glm::vec4(3e38f, 0, 0, 0)},
                                  scene::Interpolation::Linear});
    animation.channels.push_back({4, scene::AnimatedProperty::Translation, 2});

    ecs::Registry registry;
    const auto instance = world::instantiate(registry, source);
    const ecs::Entity panel = instance.find("panel");
    const ecs::Entity spot = instance.find("spot");
    world::update_animations(registry, 1.0);  // half way: the panel's x scale is 0
    EXPECT_EQ(registry.get<ecs::Transform>(panel).scale,
              glm::vec3(scene::kMinAnimatedScale, 0.5f, 1.0f));
    EXPECT_EQ(registry.get<ecs::Transform>(spot).translation, glm::vec3(0.0f));  // kept
    registry.get<world::AnimationPlayer>(instance.animations[0]).loop = false;
    world::update_animations(registry, 1.0);  // the end: y is 0, x is -1
    EXPECT_EQ(registry.get<ecs::Transform>(panel).scale.y, scene::kMinAnimatedScale);
    EXPECT_LT(registry.get<ecs::Transform>(panel).scale.x, -0.99f);

    // The ray tracer takes the posed panel as an instance and traces through it.
    ecs::TransformSystem transforms(registry);
    transforms.update();
    lighting::PhotonWorld photons(registry);
    photons.sync();
    const auto hit = photons.ray_scene().intersect(glm::vec3(0.2f, 0.2f, 1.0f),
                                                   glm::vec3(0.0f, 0.0f, -1.0f), 10.0f);
    EXPECT_FALSE(hit.has_value());  // the panel is a sliver 1e-6 high
}

TEST(LightSwitch, TurnsTheLightOnAndOffOnSchedule) {
    ecs::Registry registry;
    const auto instance = world::instantiate(registry, make_scene());
    const ecs::Entity bulb = instance.find("bulb");
    auto changes = registry.observe<lighting::PointLight>();
    // On for 1 s of every 4 s from t = 0.
    std::vector<bool> states;
    for (int step = 0; step < 16; ++step) {
        world::update_light_switches(registry, 0.5);
        states.push_back(registry.get<lighting::PointLight>(bulb).enabled);
    }
    // t = 0.5 on, 1.0 .. 3.5 off, 4.0 4.5 on, ...
    const std::vector<bool> expected = {true, false, false, false, false, false, false, true,
                                        true, false, false, false, false, false, false, true};
    EXPECT_EQ(states, expected);
    // Only flips are recorded as updates: at most one pending update for the bulb.
    EXPECT_EQ(changes.updated().size(), 1u);
    EXPECT_TRUE(world::switch_is_on({4.0, 1.0, 0.0, 0.0}, 4.5));
    EXPECT_FALSE(world::switch_is_on({4.0, 1.0, 0.0, 0.0}, 1.5));
    EXPECT_TRUE(world::switch_is_on({4.0, 1.0, 3.5, 0.0}, 0.25));  // phase wraps
}

}  // namespace

namespace {

TEST(SceneInstance, ALightmapLayoutMakesALightmappedSurface) {
    auto s = std::make_shared<luxel::scene::Scene>();
    s->meshes.resize(1);
    auto primitive = triangle();
    primitive.texcoords1 = {{0, 0}, {1, 0}, {0, 1}};
    s->meshes[0].primitives.push_back(primitive);
    s->nodes.resize(3);
    s->nodes[0].mesh = 0;  // UVs but no layout: not trusted as a light map
    s->nodes[1].mesh = 0;
    luxel::scene::LightmapLayout layout;
    layout.texel_size = 0.1f;
    layout.page_size = 64;
    layout.surfaces.push_back({3, 0, 0, {2, 2, 10, 10}, {{2, 2, 10, 10}}, 0.5, 50});
    s->nodes[1].flags.raw["lightmap"] = luxel::scene::to_json(layout);
    s->roots = {0, 1, 2};
    luxel::ecs::Registry registry;
    const auto instance = luxel::world::instantiate(registry, s);
    EXPECT_FALSE(registry.has<luxel::lighting::LightmappedSurface>(instance.nodes[0]));
    ASSERT_TRUE(registry.has<luxel::lighting::LightmappedSurface>(instance.nodes[1]));
    EXPECT_EQ(registry.get<luxel::lighting::LightmappedSurface>(instance.nodes[1]).layout, layout);

    // A layout naming a primitive without light-map UVs is an error naming the node.
    auto bad = std::make_shared<luxel::scene::Scene>(*s);
    bad->nodes[2].name = "plain";
    bad->nodes[2].mesh = 0;
    bad->meshes[0].primitives[0].texcoords1.clear();
    bad->nodes[2].flags.raw["lightmap"] = luxel::scene::to_json(layout);
    bad->nodes[1].flags.raw.erase("lightmap");
    luxel::ecs::Registry other;
    try {
        (void)luxel::world::instantiate(other, bad);
        FAIL() << "expected an error";
    } catch (const luxel::Error& e) {
        EXPECT_NE(std::string(e.what()).find("'plain'"), std::string::npos) << e.what();
    }
}

TEST(LightmapLayout, RoundTripsAndRejectsMalformedTables) {
    luxel::scene::LightmapLayout layout;
    layout.page_size = 128;
    layout.surfaces.push_back({0, 1, 2, {0, 0, 8, 4}, {{0, 0, 8, 4}}, 2.0, 32});
    nlohmann::json extras = {{"lightmap", luxel::scene::to_json(layout)}};
    EXPECT_EQ(luxel::scene::read_lightmap_layout(extras), layout);
    EXPECT_FALSE(luxel::scene::read_lightmap_layout(nlohmann::json::object()).has_value());
    auto broken = extras;
    broken["lightmap"]["surfaces"][0]["rect"] = {120, 0, 16, 4};  // off the page
    EXPECT_THROW((void)luxel::scene::read_lightmap_layout(broken), luxel::Error);
    broken = extras;
    broken["lightmap"]["page_size"] = "big";
    EXPECT_THROW((void)luxel::scene::read_lightmap_layout(broken), luxel::Error);
    broken = extras;
    broken["lightmap"]["surfaces"][0].erase("area");
    EXPECT_THROW((void)luxel::scene::read_lightmap_layout(broken), luxel::Error);
}

}  // namespace
