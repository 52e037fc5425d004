// The wave system (world/vertex_wave.hpp) and the general per-frame vertex update under it
// (world/mesh_shape.hpp): the displacement and normals against the formula and against the
// surface's own finite differences, the time it keeps, the errors of a wrong shape, and the ray
// scene refitting the moved vertices in place rather than rebuilding.

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "luxel/ecs/transform_system.hpp"
#include "luxel/lighting/core/photon_world.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/scene/components.hpp"
#include "luxel/world/mesh_shape.hpp"
#include "luxel/world/scene_instance.hpp"
#include "luxel/world/vertex_wave.hpp"
#include "sheet_mesh.hpp"

namespace {

using namespace luxel;

constexpr int kSide = 17;  // vertices along each side of the test sheet

/// A flat sheet in the xz plane, 2 x 2 m from (-1, -1), normals up (or `normal` if given).
scene::Primitive sheet(glm::vec3 normal = {0.0f, 1.0f, 0.0f}) {
    return luxel::testing::sheet_primitive(kSide, glm::vec3(-1.0f, 0.0f, -1.0f), 2.0f, normal);
}

/// A level of one node holding the sheet, its extras.luxel as given.
std::shared_ptr<const scene::Scene> level_with(const nlohmann::json& luxel) {
    auto s = std::make_shared<scene::Scene>();
    s->meshes.push_back({"water", {sheet()}});
    s->nodes.resize(1);
    s->nodes[0].name = "water";
    s->nodes[0].mesh = 0;
    s->nodes[0].flags.raw = luxel;
    s->roots = {0};
    s->validate();
    return s;
}

const scene::Mesh& shape_of(const ecs::Registry& registry, ecs::Entity entity) {
    return registry.get<scene::MeshInstance>(entity).geometry();
}

TEST(VertexWave, ReadsTheNodesExtrasWithDefaultsAndAUnitDirection) {
    EXPECT_FALSE(world::read_wave(nlohmann::json::object()));
    EXPECT_FALSE(world::read_wave({{"bounce", {{"height", 1}}}}));
    const auto defaults = world::read_wave({{"wave", nlohmann::json::object()}});
    ASSERT_TRUE(defaults);
    EXPECT_FLOAT_EQ(defaults->amplitude, 0.02f);
    EXPECT_FLOAT_EQ(defaults->wavelength, 0.5f);
    EXPECT_FLOAT_EQ(defaults->speed, 0.4f);
    const auto wave = world::read_wave(
        {{"wave", {{"amplitude", 0.1}, {"wavelength", 2}, {"speed", -1}, {"direction", {3, 4}}}}});
    ASSERT_TRUE(wave);
    EXPECT_FLOAT_EQ(wave->amplitude, 0.1f);
    EXPECT_FLOAT_EQ(wave->wavelength, 2.0f);
    EXPECT_FLOAT_EQ(wave->speed, -1.0f);
    EXPECT_FLOAT_EQ(wave->direction.x, 0.6f);
    EXPECT_FLOAT_EQ(wave->direction.y, 0.8f);
    // A zero direction (the loader refuses it) does not become NaN.
    const auto still = world::read_wave({{"wave", {{"direction", {0, 0}}}}});
    ASSERT_TRUE(still);
    EXPECT_FLOAT_EQ(still->direction.x, 1.0f);
}

TEST(VertexWave, MovesEachVertexAlongItsNormalByTheFormula) {
    world::WaveParameters wave;
    wave.amplitude = 0.05f;
    wave.wavelength = 0.8f;
    wave.speed = 0.3f;
    wave.direction = glm::normalize(glm::vec2(3.0f, 4.0f));
    const double time = 0.7;
    const scene::Mesh rest{"water", {sheet()}};
    const scene::Mesh moved = world::waved_mesh(rest, wave, time);
    const scene::Primitive& p = moved.primitives[0];
    ASSERT_EQ(p.positions.size(), rest.primitives[0].positions.size());
    EXPECT_EQ(p.indices, rest.primitives[0].indices);
    const double k = 2.0 * std::numbers::pi / 0.8;
    for (std::size_t i = 0; i < p.positions.size(); ++i) {
        const glm::vec3& r = rest.primitives[0].positions[i];
        const double phase = k * (0.6 * r.x + 0.8 * r.z - 0.3 * time);
        EXPECT_NEAR(p.positions[i].y, 0.05 * std::sin(phase), 1e-6) << i;
        EXPECT_FLOAT_EQ(p.positions[i].x, r.x);
        EXPECT_FLOAT_EQ(p.positions[i].z, r.z);
        // The heightfield's normal (-dh/dx, 1, -dh/dz), normalised.
        const double slope = 0.05 * k * std::cos(phase);
        const glm::dvec3 expected = glm::normalize(glm::dvec3(-slope * 0.6, 1.0, -slope * 0.8));
        EXPECT_NEAR(p.normals[i].x, expected.x, 1e-5) << i;
        EXPECT_NEAR(p.normals[i].y, expected.y, 1e-5) << i;
        EXPECT_NEAR(p.normals[i].z, expected.z, 1e-5) << i;
    }
    // The normals agree with the moved surface itself: at an inner vertex, the cross product of
    // central differences of the positions (spacing 12.5 cm against a 80 cm wavelength).
    int checked = 0;
    for (int z = 1; z + 1 < kSide; ++z) {
        for (int x = 1; x + 1 < kSide; ++x) {
            const auto at = [&](int dx, int dz) {
                return p.positions[static_cast<std::size_t>((z + dz) * kSide + x + dx)];
            };
            const glm::vec3 surface =
                glm::normalize(glm::cross(at(0, 1) - at(0, -1), at(1, 0) - at(-1, 0)));
            const glm::vec3 normal = p.normals[static_cast<std::size_t>(z * kSide + x)];
            EXPECT_GT(glm::dot(surface, normal), 0.995f) << x << ", " << z;
            ++checked;
        }
    }
    EXPECT_EQ(checked, (kSide - 2) * (kSide - 2));
}

TEST(VertexWave, AWallMovesAlongItsOwnNormal) {
    // A sheet whose normals face +x (as if the mesh were a wall): the wave lifts along +x.
    world::WaveParameters wave;
    wave.amplitude = 0.03f;
    const scene::Mesh rest{"wall", {sheet(glm::vec3(1.0f, 0.0f, 0.0f))}};
    const scene::Mesh moved = world::waved_mesh(rest, wave, 0.2);
    float largest = 0.0f;
    for (std::size_t i = 0; i < moved.primitives[0].positions.size(); ++i) {
        const glm::vec3 d = moved.primitives[0].positions[i] - rest.primitives[0].positions[i];
        EXPECT_FLOAT_EQ(d.y, 0.0f);
        EXPECT_FLOAT_EQ(d.z, 0.0f);
        EXPECT_LE(std::abs(d.x), 0.03f + 1e-6f);
        largest = std::max(largest, std::abs(d.x));
        EXPECT_NEAR(glm::length(moved.primitives[0].normals[i]), 1.0f, 1e-5f);
    }
    EXPECT_GT(largest, 0.025f) << "the wave's crests pass over the sheet";
}

TEST(VertexWave, InstantiateShapesTimeZeroAndUpdateWavesFollowsTime) {
    // Flagged static: a wave moves the mesh all the same, so the entity is dynamic.
    const auto level =
        level_with({{"dynamic", false},
                    {"wave", {{"amplitude", 0.02}, {"wavelength", 0.5}, {"speed", 0.25}}}});
    ecs::Registry registry;
    const world::SceneInstance instance = world::instantiate(registry, level);
    const ecs::Entity water = instance.nodes[0];
    EXPECT_TRUE(registry.has<scene::Dynamic>(water));
    ASSERT_TRUE(registry.has<world::VertexWave>(water));
    const world::WaveParameters& wave = registry.get<world::VertexWave>(water).wave;
    const auto expect_shape_at = [&](double time) {
        const scene::Mesh expected = world::waved_mesh(level->meshes[0], wave, time);
        EXPECT_EQ(shape_of(registry, water).primitives[0].positions,
                  expected.primitives[0].positions)
            << "at " << time << " s";
    };
    expect_shape_at(0.0);
    EXPECT_EQ(world::update_waves(registry, 0.0), 0u) << "time 0 was shaped at load";
    EXPECT_EQ(world::update_waves(registry, 0.5), 1u);
    expect_shape_at(0.5);
    // The period is 0.5 m / 0.25 m/s = 2 s: the time wraps, and a whole period later the
    // shape is the same one, so nothing is shaped.
    EXPECT_EQ(world::update_waves(registry, 2.0), 0u);
    EXPECT_NEAR(registry.get<world::VertexWave>(water).time, 0.5, 1e-9);
    EXPECT_EQ(world::update_waves(registry, 2.3), 1u);
    EXPECT_NEAR(registry.get<world::VertexWave>(water).time, 0.8, 1e-9);
    expect_shape_at(0.8);
    // A paused wave keeps its shape; a game that took the mesh away is left alone.
    registry.get<world::VertexWave>(water).playing = false;
    EXPECT_EQ(world::update_waves(registry, 0.3), 0u);
    registry.get<world::VertexWave>(water).playing = true;
    registry.remove<scene::MeshInstance>(water);
    EXPECT_EQ(world::update_waves(registry, 0.3), 0u);
    // A node without a wave gets no VertexWave.
    ecs::Registry plain;
    const auto still = world::instantiate(plain, level_with(nlohmann::json::object()));
    EXPECT_FALSE(plain.has<world::VertexWave>(still.nodes[0]));
    EXPECT_FALSE(plain.get<scene::MeshInstance>(still.nodes[0]).posed);
}

TEST(VertexWave, TheRaySceneRefitsTheWavedMeshInPlace) {
    const auto level = level_with({{"wave", {{"amplitude", 0.05}, {"wavelength", 1.0}}}});
    ecs::Registry registry;
    const world::SceneInstance instance = world::instantiate(registry, level);
    const ecs::Entity water = instance.nodes[0];
    ecs::TransformSystem transforms(registry);
    transforms.update();
    lighting::PhotonWorld photons(registry);
    photons.sync();
    const lighting::ObjectId object = photons.mesh_objects().at(water);
    const std::uint64_t rebuilds = photons.ray_scene().static_rebuilds();
    const std::uint64_t deformations = photons.ray_scene().deformations(object);
    for (int frame = 1; frame <= 3; ++frame) {
        ASSERT_EQ(world::update_waves(registry, 0.1), 1u);
        photons.sync();
        EXPECT_EQ(photons.mesh_objects().at(water), object) << "the same object, not a new one";
        EXPECT_EQ(photons.ray_scene().deformations(object),
                  deformations + static_cast<std::uint64_t>(frame));
    }
    EXPECT_EQ(photons.ray_scene().static_rebuilds(), rebuilds);
    // A ray straight down meets the surface where the wave has put it now.
    const glm::vec3 origin(0.3f, 1.0f, -0.2f);
    const auto hit = photons.ray_scene().intersect(origin, glm::vec3(0.0f, -1.0f, 0.0f));
    ASSERT_TRUE(hit);
    const world::VertexWave& wave = registry.get<world::VertexWave>(water);
    const double height = 0.05 * std::sin(2.0 * std::numbers::pi * (0.3 - 0.4 * wave.time));
    // Between vertices 12.5 cm apart the surface is flat: within the chord's sag.
    EXPECT_NEAR(origin.y - hit->distance, height, 0.006);
}

TEST(MeshShape, AWrongShapeIsRefusedByNameAndChangesNothing) {
    const auto level = level_with(nlohmann::json::object());
    ecs::Registry registry;
    const world::SceneInstance instance = world::instantiate(registry, level);
    const ecs::Entity water = instance.nodes[0];
    const auto refused = [&](const scene::Mesh& shape) {
        try {
            world::set_mesh_shape(registry, water, std::make_shared<const scene::Mesh>(shape));
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("(accepted)");
    };
    scene::Mesh fewer = level->meshes[0];
    fewer.primitives[0].positions.pop_back();
    EXPECT_NE(refused(fewer).find("'water': primitive 0's shape has 288 vertices, its mesh 289"),
              std::string::npos)
        << refused(fewer);
    scene::Mesh other = level->meshes[0];
    std::swap(other.primitives[0].indices[0], other.primitives[0].indices[1]);
    EXPECT_NE(refused(other).find("other triangles"), std::string::npos);
    scene::Mesh torn = level->meshes[0];
    torn.primitives[0].positions[7].y = std::numeric_limits<float>::quiet_NaN();
    EXPECT_NE(refused(torn).find("not finite"), std::string::npos);
    EXPECT_FALSE(registry.get<scene::MeshInstance>(water).posed) << "nothing changed";
    EXPECT_FALSE(registry.has<scene::Dynamic>(water));

    // A right shape on a static mesh makes it dynamic, so the ray scene can refit it.
    scene::Mesh lifted = level->meshes[0];
    lifted.primitives[0].positions[7].y = 0.1f;
    EXPECT_EQ(refused(lifted), "(accepted)");
    EXPECT_TRUE(registry.has<scene::Dynamic>(water));
    EXPECT_FLOAT_EQ(shape_of(registry, water).primitives[0].positions[7].y, 0.1f);
}

}  // namespace
