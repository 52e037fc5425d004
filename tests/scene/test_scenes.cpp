#include "test_scenes.hpp"

#include <cmath>
#include <fstream>
#include <iterator>
#include <numbers>

#include <glm/gtc/quaternion.hpp>

#include "luxel/runtime/image.hpp"
#include "temp_dir.hpp"

namespace luxel::testing {
namespace {

using scene::Primitive;

constexpr float kPi = std::numbers::pi_v<float>;

/// An axis-aligned box of the given half size; normals point inward for a room, outward
/// otherwise. Four vertices per face so each face has its own normal and UVs.
Primitive box(glm::vec3 half, bool inward, bool with_uv1) {
    Primitive box;
    const glm::vec3 axes[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int axis = 0; axis < 3; ++axis) {
        for (const float side : {-1.0f, 1.0f}) {
            const glm::vec3 n = axes[axis] * side;
            const glm::vec3 u = axes[(axis + 1) % 3];
            const glm::vec3 v = axes[(axis + 2) % 3];
            const auto base = static_cast<std::uint32_t>(box.positions.size());
            const glm::vec2 corners[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
            for (const glm::vec2& c : corners) {
                box.positions.push_back((n + u * c.x + v * c.y) * half);
                box.normals.push_back(inward ? -n : n);
                box.texcoords0.push_back(c * 0.5f + 0.5f);
                if (with_uv1) {
                    box.texcoords1.push_back(
                        (c * 0.5f + 0.5f) * 0.15f +
                        glm::vec2(0.2f * static_cast<float>(axis), side > 0 ? 0.5f : 0.0f));
                }
            }
            // Counter-clockwise seen from where the normal points.
            const bool flip = (side > 0) == inward;
            const std::uint32_t order[6] = {0, 1, 2, 0, 2, 3};
            const std::uint32_t flipped[6] = {0, 2, 1, 0, 3, 2};
            for (int k = 0; k < 6; ++k) {
                box.indices.push_back(base + (flip ? flipped[k] : order[k]));
            }
        }
    }
    return box;
}

Primitive sphere(float radius, int rings, int segments) {
    Primitive sphere;
    for (int r = 0; r <= rings; ++r) {
        const float theta = kPi * static_cast<float>(r) / static_cast<float>(rings);
        for (int s = 0; s <= segments; ++s) {
            const float phi = 2.0f * kPi * static_cast<float>(s) / static_cast<float>(segments);
            const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta),
                              std::sin(theta) * std::sin(phi));
            sphere.positions.push_back(n * radius);
            sphere.normals.push_back(n);
        }
    }
    const auto row = static_cast<std::uint32_t>(segments + 1);
    for (std::uint32_t r = 0; r < static_cast<std::uint32_t>(rings); ++r) {
        for (std::uint32_t s = 0; s < static_cast<std::uint32_t>(segments); ++s) {
            const std::uint32_t a = r * row + s;
            const std::uint32_t b = a + row;
            // The poles' first and last rows hold degenerate triangles; leave those out so
            // the round trip compares like with like.
            if (r != 0) {
                sphere.indices.insert(sphere.indices.end(), {a, a + 1, b});
            }
            if (r + 1 != static_cast<std::uint32_t>(rings)) {
                sphere.indices.insert(sphere.indices.end(), {a + 1, b + 1, b});
            }
        }
    }
    return sphere;
}

scene::Node node(const std::string& name, glm::vec3 translation = glm::vec3(0.0f)) {
    scene::Node n;
    n.name = name;
    n.translation = translation;
    return n;
}

int add_node(scene::Scene& s, scene::Node n, int parent) {
    const int index = static_cast<int>(s.nodes.size());
    n.parent = parent;
    s.nodes.push_back(std::move(n));
    if (parent >= 0) {
        s.nodes[static_cast<std::size_t>(parent)].children.push_back(index);
    } else {
        s.roots.push_back(index);
    }
    return index;
}

scene::AnimationSampler sampler(scene::Interpolation interpolation, std::vector<float> times,
                                std::vector<glm::vec4> values) {
    scene::AnimationSampler s;
    s.interpolation = interpolation;
    s.times = std::move(times);
    s.values = std::move(values);
    return s;
}

glm::vec4 quat_values(float angle, glm::vec3 axis) {
    const glm::quat q = glm::angleAxis(angle, glm::normalize(axis));
    return {q.x, q.y, q.z, q.w};
}

}  // namespace

std::vector<std::uint8_t> tiny_png() {
    TempDir dir("luxel-png");
    luxel::Image image(2, 2, glm::vec4(0.2f, 0.4f, 0.8f, 1.0f));
    image.set_pixel(1, 0, glm::vec4(0.9f, 0.1f, 0.1f, 1.0f));
    write_png(dir / "tiny.png", image);
    std::ifstream stream(dir / "tiny.png", std::ios::binary);
    return {std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()};
}

scene::Scene box_room() {
    scene::Scene s;
    s.name = "box room";
    s.images.push_back({"checker", "image/png", tiny_png()});

    auto material = [&s](const std::string& name) -> scene::Material& {
        s.materials.emplace_back();
        s.materials.back().name = name;
        return s.materials.back();
    };
    {
        auto& m = material("walls");
        m.base_color = {0.8f, 0.8f, 0.75f, 1.0f};
        m.metallic = 0.0f;
        m.roughness = 0.9f;
    }
    {
        auto& m = material("textured");
        m.base_color_image = 0;
        m.metallic = 0.0f;
        m.roughness = 0.5f;
    }
    {
        auto& m = material("lamp panel");
        m.emissive = {1.0f, 0.9f, 0.75f};
        m.emissive_strength = 12.5f;
        m.metallic = 0.0f;
    }
    {
        auto& m = material("glass");
        m.transmission = 1.0f;
        m.ior = 1.45f;
        m.roughness = 0.0f;
        m.metallic = 0.0f;
        m.base_color = {1.0f, 1.0f, 1.0f, 0.25f};
        m.thickness = 0.05f;  // KHR_materials_volume
        m.attenuation_distance = 0.4f;
        m.attenuation_color = {0.6f, 0.8f, 0.95f};
    }
    {
        auto& m = material("mirror");
        m.metallic = 1.0f;
        m.roughness = 0.02f;
        m.double_sided = true;
    }
    {
        // No mesh uses it (the lamp panel stays the room's uniform light); it round-trips an
        // emissiveTexture.
        auto& m = material("sign");
        m.emissive = {1.0f, 1.0f, 1.0f};
        m.emissive_strength = 3.0f;
        m.emissive_image = 0;
        m.metallic = 0.0f;
    }

    auto mesh = [&s](const std::string& name, Primitive primitive, int material_index) {
        primitive.material = material_index;
        s.meshes.push_back({name, {std::move(primitive)}});
        return static_cast<int>(s.meshes.size() - 1);
    };
    const int room_mesh = mesh("room", box({2.0f, 1.5f, 2.0f}, true, true), 0);
    const int cube_mesh = mesh("cube", box({0.25f, 0.25f, 0.25f}, false, false), 1);
    Primitive panel = box({0.3f, 0.01f, 0.3f}, false, false);
    panel.texcoords0.clear();
    const int panel_mesh = mesh("panel", std::move(panel), 2);
    const int sphere_mesh = mesh("sphere", sphere(0.3f, 6, 8), 3);
    const int mirror_mesh = mesh("mirror", box({0.5f, 0.7f, 0.02f}, false, false), 4);
    // A second primitive on one mesh, without a material.
    s.meshes[static_cast<std::size_t>(mirror_mesh)].primitives.push_back(
        box({0.55f, 0.75f, 0.01f}, false, false));

    s.lights.push_back(scene::Light::point_from_power(glm::vec3(40.0f, 36.0f, 30.0f)));
    s.lights.back().name = "bulb";
    s.lights.back().range = 12.0f;
    s.lights.push_back(scene::Light::spot_from_power(glm::vec3(20.0f), 0.2f, 0.6f));
    s.lights.back().name = "spot";
    s.lights.push_back(scene::Light::directional_from_irradiance(glm::vec3(3.0f, 2.9f, 2.5f)));
    s.lights.back().name = "sun";

    scene::Camera perspective;
    perspective.name = "main";
    perspective.yfov = 0.9f;
    perspective.aspect_ratio = 1.5f;
    perspective.znear = 0.1f;
    perspective.zfar = 100.0f;
    s.cameras.push_back(perspective);
    scene::Camera infinite;
    infinite.name = "infinite";
    s.cameras.push_back(infinite);
    scene::Camera ortho;
    ortho.name = "plan";
    ortho.perspective = false;
    ortho.xmag = 2.0f;
    ortho.ymag = 1.5f;
    ortho.znear = 0.0f;
    ortho.zfar = 50.0f;
    s.cameras.push_back(ortho);

    scene::Node room_node = node("room");
    room_node.mesh = room_mesh;
    room_node.flags.raw = {{"surfaces", {{"texel_size", 0.05}}}};
    const int room = add_node(s, room_node, -1);

    scene::Node cube = node("cube", {0.5f, -1.25f, 0.3f});
    cube.mesh = cube_mesh;
    const int cube_index = add_node(s, cube, room);

    scene::Node glass = node("glass sphere", {-0.6f, -1.2f, -0.4f});
    glass.mesh = sphere_mesh;
    glass.scale = {1.0f, 0.9f, 1.0f};
    const int glass_index = add_node(s, glass, room);

    scene::Node lamp = node("lamp", {0.0f, 1.48f, 0.0f});
    lamp.mesh = panel_mesh;
    add_node(s, lamp, room);

    scene::Node mirror = node("mirror", {1.9f, 0.0f, 0.0f});
    mirror.mesh = mirror_mesh;
    mirror.rotation = glm::angleAxis(kPi / 2.0f, glm::vec3(0, 1, 0));
    add_node(s, mirror, room);

    scene::Node pivot = node("door pivot", {-2.0f, -0.5f, 1.0f});
    pivot.flags.dynamic = true;
    pivot.flags.raw = {{"dynamic", true}, {"hinge", "y"}};
    const int pivot_index = add_node(s, pivot, room);
    scene::Node door = node("door", {0.4f, 0.0f, 0.0f});
    door.mesh = cube_mesh;
    door.scale = {1.6f, 4.0f, 0.1f};
    add_node(s, door, pivot_index);

    scene::Node bulb = node("bulb", {0.0f, 1.2f, 0.0f});
    bulb.light = 0;
    bulb.flags.light_enabled = false;
    bulb.flags.light_radius = 0.125f;  // a 25 cm globe: soft shadows
    bulb.flags.raw = {
        {"enabled", false}, {"light_radius", 0.125}, {"switch", {{"period", 4.0}, {"on", 2.0}}}};
    add_node(s, bulb, room);

    scene::Node spot = node("spot", {1.5f, 1.4f, -1.5f});
    spot.light = 1;
    spot.rotation = glm::angleAxis(-kPi / 3.0f, glm::normalize(glm::vec3(1, 0, 1)));
    add_node(s, spot, room);

    scene::Node sun = node("sun");
    sun.light = 2;
    sun.rotation = glm::angleAxis(-kPi / 4.0f, glm::vec3(1, 0, 0));
    add_node(s, sun, -1);

    scene::Node camera = node("camera", {0.0f, 0.0f, 5.0f});
    camera.camera = 0;
    camera.flags.dynamic = false;
    camera.flags.raw = {{"dynamic", false}, {"note", "start view"}, {"big", 9007199254740993}};
    add_node(s, camera, -1);
    scene::Node far_camera = node("far camera", {0.0f, 1.0f, 9.0f});
    far_camera.camera = 1;
    add_node(s, far_camera, -1);
    scene::Node plan = node("plan camera", {0.0f, 10.0f, 0.0f});
    plan.camera = 2;
    plan.rotation = glm::angleAxis(-kPi / 2.0f, glm::vec3(1, 0, 0));
    add_node(s, plan, -1);

    scene::Animation slide;
    slide.name = "slide";
    slide.samplers.push_back(sampler(
        scene::Interpolation::Linear, {0.0f, 1.0f, 2.5f},
        {{0.5f, -1.25f, 0.3f, 0.0f}, {0.9f, -1.25f, 0.3f, 0.0f}, {0.5f, -1.25f, -0.2f, 0.0f}}));
    slide.samplers.push_back(sampler(scene::Interpolation::CubicSpline, {0.0f, 1.25f, 2.5f},
                                     {{0.0f, 0.1f, 0.0f, 0.0f},
                                      quat_values(0.0f, {0, 1, 0}),
                                      {0.0f, 0.2f, 0.0f, 0.0f},
                                      {0.0f, -0.1f, 0.0f, 0.0f},
                                      quat_values(1.0f, {0, 1, 0}),
                                      {0.0f, 0.3f, 0.0f, 0.0f},
                                      {0.1f, 0.0f, 0.0f, 0.0f},
                                      quat_values(2.0f, {0, 1, 0}),
                                      {0.0f, 0.0f, 0.0f, 0.0f}}));
    slide.channels.push_back({cube_index, scene::AnimatedProperty::Translation, 0});
    slide.channels.push_back({cube_index, scene::AnimatedProperty::Rotation, 1});
    s.animations.push_back(std::move(slide));

    scene::Animation spin;
    spin.name = "spin";
    spin.samplers.push_back(
        sampler(scene::Interpolation::Step, {0.0f, 0.5f, 1.0f, 1.5f},
                {quat_values(0.0f, {0, 1, 0}), quat_values(kPi / 2.0f, {0, 1, 0}),
                 quat_values(kPi, {0, 1, 0}), quat_values(1.5f * kPi, {0, 1, 0})}));
    spin.samplers.push_back(sampler(scene::Interpolation::Linear, {0.25f, 2.0f},
                                    {{1.0f, 0.9f, 1.0f, 0.0f}, {1.2f, 1.1f, 1.2f, 0.0f}}));
    spin.samplers.push_back(sampler(scene::Interpolation::CubicSpline, {0.0f, 3.0f},
                                    {{0.0f, 0.0f, 0.0f, 0.0f},
                                     {-0.6f, -1.2f, -0.4f, 0.0f},
                                     {0.0f, 0.5f, 0.0f, 0.0f},
                                     {0.0f, -0.5f, 0.0f, 0.0f},
                                     {-0.6f, -0.8f, -0.4f, 0.0f},
                                     {0.0f, 0.0f, 0.0f, 0.0f}}));
    spin.channels.push_back({glass_index, scene::AnimatedProperty::Rotation, 0});
    spin.channels.push_back({glass_index, scene::AnimatedProperty::Scale, 1});
    spin.channels.push_back({glass_index, scene::AnimatedProperty::Translation, 2});
    s.animations.push_back(std::move(spin));
    return s;
}

scene::Scene single_triangle() {
    scene::Scene s;
    Primitive triangle;
    triangle.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    triangle.indices = {0, 1, 2};
    s.meshes.push_back({"", {triangle}});
    scene::Node n;
    n.mesh = 0;
    s.nodes.push_back(n);
    s.roots.push_back(0);
    return s;
}

scene::Scene grid(int cells) {
    scene::Scene s;
    s.name = "grid";
    Primitive p;
    const int row = cells + 1;
    for (int z = 0; z <= cells; ++z) {
        for (int x = 0; x <= cells; ++x) {
            const glm::vec2 uv(static_cast<float>(x) / static_cast<float>(cells),
                               static_cast<float>(z) / static_cast<float>(cells));
            p.positions.push_back(
                {uv.x * 10.0f - 5.0f, 0.1f * std::sin(7.0f * uv.x), uv.y * 10.0f});
            p.normals.push_back({0, 1, 0});
            p.texcoords0.push_back(uv * 4.0f);
            p.texcoords1.push_back(uv);
        }
    }
    for (int z = 0; z < cells; ++z) {
        for (int x = 0; x < cells; ++x) {
            const auto a = static_cast<std::uint32_t>(z * row + x);
            const auto b = a + static_cast<std::uint32_t>(row);
            p.indices.insert(p.indices.end(), {a, b, a + 1, a + 1, b, b + 1});
        }
    }
    s.meshes.push_back({"floor", {p}});
    scene::Node n;
    n.name = "floor";
    n.mesh = 0;
    s.nodes.push_back(n);
    s.roots.push_back(0);
    return s;
}

std::vector<NamedScene> mutation_seed_scenes() {
    std::vector<NamedScene> scenes;
    scenes.push_back({"box-room", box_room()});
    scenes.push_back({"single-triangle", single_triangle()});
    scenes.push_back({"small-grid", grid(6)});
    return scenes;
}

}  // namespace luxel::testing
