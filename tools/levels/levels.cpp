#include "levels.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/constants.hpp>

#include "level_builder.hpp"
#include "mesh_builders.hpp"
#include "walker.hpp"

namespace luxel::levels {
namespace {

using scene::AnimatedProperty;
using scene::Interpolation;

constexpr float kPi = glm::pi<float>();

glm::quat yaw(float radians) {
    return glm::angleAxis(radians, glm::vec3(0.0f, 1.0f, 0.0f));
}

/// Rotation that points a light's -z axis along `direction`.
glm::quat aim(glm::vec3 direction) {
    const glm::vec3 forward = glm::normalize(direction);
    const glm::vec3 from(0.0f, 0.0f, -1.0f);
    const float cos_angle = glm::dot(from, forward);
    if (cos_angle < -0.9999f) {
        return glm::angleAxis(kPi, glm::vec3(0.0f, 1.0f, 0.0f));
    }
    return glm::normalize(glm::quat(1.0f + cos_angle, glm::cross(from, forward)));
}

scene::Material glass(const std::string& name, float ior, glm::vec3 tint = glm::vec3(1.0f)) {
    scene::Material material;
    material.name = name;
    material.base_color = glm::vec4(tint, 1.0f);
    material.metallic = 0.0f;
    material.roughness = 0.0f;
    material.transmission = 1.0f;
    material.ior = ior;
    material.double_sided = true;
    return material;
}

scene::Light point_light(const std::string& name, float watts, glm::vec3 colour = glm::vec3(1.0f)) {
    scene::Light light = scene::Light::point_from_power(watts * colour);
    light.name = name;
    return light;
}

/// Marks a light node as switched by the level's light-switch system: on for `on_seconds`
/// of every `period_seconds`, starting at `phase_seconds` (see docs/LEVELS.md).
void add_switch(scene::Node& node, float period_seconds, float on_seconds, float phase_seconds) {
    node.flags.raw["switch"] = {
        {"period", period_seconds}, {"on", on_seconds}, {"phase", phase_seconds}};
}

/// A wall in the plane x = `x` spanning z in [-half_depth, half_depth] and y in [0, height],
/// with a doorway |z| < door_half, y < door_height, in three pieces around it. It faces -x when
/// `faces_negative_x`, else +x.
scene::Primitive doorway_wall(float x, bool faces_negative_x, float half_depth, float door_half,
                              float door_height, float height) {
    auto face = [&](float z_low, float z_high, float y_low, float y_high) {
        const glm::vec3 up(0.0f, y_high - y_low, 0.0f);
        return faces_negative_x ? make_quad({x, y_low, z_low}, {0, 0, z_high - z_low}, up, 4, 4)
                                : make_quad({x, y_low, z_high}, {0, 0, z_low - z_high}, up, 4, 4);
    };
    scene::Primitive wall;
    append(wall, face(door_half, half_depth, 0.0f, height));
    append(wall, face(-half_depth, -door_half, 0.0f, height));
    append(wall, face(-door_half, door_half, door_height, height));
    return wall;
}

/// A wall from `corner` spanning `along` and `up` (its normal along x up, as make_quad), with
/// a window: the hole [u0, u1] x [v0, v1] in metres along the two edges, left open in four
/// pieces around it.
scene::Primitive window_wall(glm::vec3 corner, glm::vec3 along, glm::vec3 up, glm::vec2 hole_low,
                             glm::vec2 hole_high) {
    const float width = glm::length(along);
    const float height = glm::length(up);
    const glm::vec3 u = along / width;
    const glm::vec3 v = up / height;
    auto piece = [&](float u0, float u1, float v0, float v1) {
        // About two cells a metre, as the walls around it.
        const int cells_u = std::max(1, static_cast<int>(std::lround(2.0f * (u1 - u0))));
        const int cells_v = std::max(1, static_cast<int>(std::lround(2.0f * (v1 - v0))));
        return make_quad(corner + u * u0 + v * v0, u * (u1 - u0), v * (v1 - v0), cells_u, cells_v);
    };
    scene::Primitive wall;
    append(wall, piece(0.0f, width, 0.0f, hole_low.y));              // below the sill
    append(wall, piece(0.0f, width, hole_high.y, height));           // above the lintel
    append(wall, piece(0.0f, hole_low.x, hole_low.y, hole_high.y));  // beside the window
    append(wall, piece(hole_high.x, width, hole_low.y, hole_high.y));
    return wall;
}

/// A sky portal (docs/LEVELS.md, "Sky") filling the hole `window_wall` left in the same wall.
int add_window_portal(LevelBuilder& level, const std::string& name, int material, glm::vec3 corner,
                      glm::vec3 along, glm::vec3 up, glm::vec2 hole_low, glm::vec2 hole_high) {
    const glm::vec3 u = glm::normalize(along);
    const glm::vec3 v = glm::normalize(up);
    const int node = level.add_mesh_node(
        name,
        make_quad(corner + u * hole_low.x + v * hole_low.y, u * (hole_high.x - hole_low.x),
                  v * (hole_high.y - hole_low.y)),
        material);
    level.node(node).flags.raw["portal"] = true;
    return node;
}

}  // namespace

scene::Scene make_cornell(const std::string& name, int floor_cells) {
    LevelBuilder level(name);
    // A 2 m box open towards +z, reflectances after the classic Cornell box measurements.
    constexpr float w = 1.0f;  // half width
    constexpr float height = 2.0f;
    const int white = level.add_diffuse("white", glm::vec3(0.73f));
    const int red = level.add_diffuse("red", glm::vec3(0.63f, 0.065f, 0.05f));
    const int green = level.add_diffuse("green", glm::vec3(0.14f, 0.45f, 0.091f));
    const int box_white = level.add_diffuse("cube", glm::vec3(0.70f, 0.70f, 0.66f));
    const int sphere_glass = level.add_material(glass("glass", 1.5f));

    // The bumpy floor: gentle bumps 1.5 cm high, 40 cm apart, with analytic normals.
    constexpr float amplitude = 0.015f;
    const float frequency = 2.0f * kPi / 0.4f;
    auto bump = [=](float x, float z) {
        return amplitude * std::sin(frequency * x) * std::sin(frequency * z);
    };
    auto bump_slope = [=](float x, float z) {
        return glm::vec2(amplitude * frequency * std::cos(frequency * x) * std::sin(frequency * z),
                         amplitude * frequency * std::sin(frequency * x) * std::cos(frequency * z));
    };
    level.add_mesh_node(
        "floor", make_height_field(-w, w, -w, w, 0.0f, floor_cells, floor_cells, bump, bump_slope),
        white);
    level.add_mesh_node("ceiling", make_quad({-w, height, -w}, {2 * w, 0, 0}, {0, 0, 2 * w}, 4, 4),
                        white);
    level.add_mesh_node("back wall", make_quad({-w, 0, -w}, {2 * w, 0, 0}, {0, height, 0}, 4, 4),
                        white);
    level.add_mesh_node("left wall", make_quad({-w, 0, w}, {0, 0, -2 * w}, {0, height, 0}, 4, 4),
                        red);
    level.add_mesh_node("right wall", make_quad({w, 0, -w}, {0, 0, 2 * w}, {0, height, 0}, 4, 4),
                        green);

    // A diffuse cube sliding left and right, and a glass sphere circling above the floor.
    const int cube = level.add_mesh_node("moving cube", make_box(glm::vec3(0.5f)), box_white, -1,
                                         {-0.4f, 0.25f, -0.3f});
    level.node(cube).rotation = yaw(0.3f);
    level.animate("cube slide", cube, AnimatedProperty::Translation, Interpolation::Linear,
                  {0.0f, 3.0f, 6.0f},
                  {as_key(glm::vec3(-0.4f, 0.25f, -0.3f)), as_key(glm::vec3(0.3f, 0.25f, -0.3f)),
                   as_key(glm::vec3(-0.4f, 0.25f, -0.3f))});
    const int sphere = level.add_mesh_node("glass sphere", make_sphere(0.25f, 32, 16), sphere_glass,
                                           -1, {0.35f, 0.45f, 0.35f});
    std::vector<float> times;
    std::vector<glm::vec4> path;
    for (int k = 0; k <= 8; ++k) {
        const float angle = 2.0f * kPi * static_cast<float>(k) / 8.0f;
        times.push_back(static_cast<float>(k));
        path.push_back(as_key(glm::vec3(0.35f * std::cos(angle), 0.45f + 0.1f * std::sin(2 * angle),
                                        0.35f * std::sin(angle))));
    }
    level.animate("sphere orbit", sphere, AnimatedProperty::Translation, Interpolation::Linear,
                  times, path);

    level.add_light(point_light("ceiling light", 40.0f, glm::vec3(1.0f, 0.92f, 0.8f)),
                    {0.0f, height - 0.1f, 0.0f});
    level.add_camera("camera", {0.0f, 1.0f, 3.4f}, {0.0f, 0.9f, 0.0f}, glm::radians(40.0f));
    return level.finish();
}

scene::Scene make_two_rooms() {
    LevelBuilder level("two-rooms");
    // Two 4 x 3 x 4 m rooms side by side along x, sharing the wall x = 0 with a doorway
    // 1 m wide and 2.1 m high at z in [-0.5, 0.5].
    constexpr float depth = 2.0f;  // half depth (z)
    constexpr float room = 4.0f;   // width of each room (x)
    constexpr float height = 3.0f;
    constexpr float door_half = 0.5f;
    constexpr float door_height = 2.1f;
    const int plaster = level.add_diffuse("plaster", glm::vec3(0.78f, 0.76f, 0.72f));
    const int blue = level.add_diffuse("blue plaster", glm::vec3(0.35f, 0.45f, 0.70f));
    const int floor_wood = level.add_diffuse("wood floor", glm::vec3(0.55f, 0.38f, 0.22f));
    const int door_paint = level.add_diffuse("door", glm::vec3(0.65f, 0.15f, 0.12f));

    for (int side = 0; side < 2; ++side) {
        const float x0 = side == 0 ? -room : 0.0f;
        const float x1 = x0 + room;
        const std::string prefix = side == 0 ? "west " : "east ";
        const int walls = side == 0 ? plaster : blue;
        level.add_mesh_node(prefix + "floor",
                            make_quad({x0, 0, depth}, {room, 0, 0}, {0, 0, -2 * depth}, 8, 8),
                            floor_wood);
        level.add_mesh_node(prefix + "ceiling",
                            make_quad({x0, height, -depth}, {room, 0, 0}, {0, 0, 2 * depth}, 8, 8),
                            plaster);
        level.add_mesh_node(prefix + "north wall",
                            make_quad({x0, 0, -depth}, {room, 0, 0}, {0, height, 0}, 8, 6), walls);
        level.add_mesh_node(prefix + "south wall",
                            make_quad({x1, 0, depth}, {-room, 0, 0}, {0, height, 0}, 8, 6), walls);
        // The outer end wall, facing into the room.
        if (side == 0) {
            level.add_mesh_node(prefix + "end wall",
                                make_quad({x0, 0, depth}, {0, 0, -2 * depth}, {0, height, 0}, 8, 6),
                                walls);
        } else {
            level.add_mesh_node(prefix + "end wall",
                                make_quad({x1, 0, -depth}, {0, 0, 2 * depth}, {0, height, 0}, 8, 6),
                                walls);
        }
        // This room's face of the shared wall, in three pieces around the doorway; it faces -x
        // in the west room and +x in the east room.
        level.add_mesh_node(prefix + "shared wall",
                            doorway_wall(0.0f, side == 0, depth, door_half, door_height, height),
                            walls);
    }

    // The door hangs on a hinge at (0, 0, -0.5) and swings open by 100 degrees and back.
    const int hinge = level.add_node("door hinge", -1, {0.0f, 0.0f, -door_half});
    scene::Primitive leaf = make_box({0.04f, door_height - 0.02f, 2 * door_half - 0.02f});
    level.add_mesh_node("door", std::move(leaf), door_paint, hinge,
                        {0.0f, door_height / 2, door_half});
    const glm::quat closed = yaw(0.0f);
    const glm::quat open = yaw(glm::radians(100.0f));
    level.animate("door swing", hinge, AnimatedProperty::Rotation, Interpolation::Linear,
                  {0.0f, 2.0f, 4.0f, 6.0f, 8.0f},
                  {as_key(closed), as_key(closed), as_key(open), as_key(open), as_key(closed)});

    // Two lights per room; one in each switches on and off.
    level.add_light(point_light("west lamp", 60.0f, {1.0f, 0.85f, 0.7f}), {-2.5f, 2.6f, -1.0f});
    const int west_switched = level.add_light(
        point_light("west switched lamp", 30.0f, {1.0f, 0.95f, 0.9f}), {-1.2f, 2.6f, 1.2f});
    add_switch(level.node(west_switched), 6.0f, 3.5f, 0.0f);
    scene::Light spot =
        scene::Light::spot_from_power(glm::vec3(50.0f), glm::radians(20.0f), glm::radians(35.0f));
    spot.name = "east spot";
    level.add_light(spot, {2.0f, 2.9f, 0.0f}, aim({0.0f, -1.0f, 0.0f}));
    const int east_switched = level.add_light(
        point_light("east switched lamp", 40.0f, {0.8f, 0.9f, 1.0f}), {3.2f, 2.4f, -1.4f});
    add_switch(level.node(east_switched), 5.0f, 2.5f, 1.0f);
    level.add_camera("camera", {-3.5f, 1.7f, 1.7f}, {0.5f, 1.2f, -0.3f}, glm::radians(60.0f));
    return level.finish();
}

scene::Scene make_caustics() {
    LevelBuilder level("caustics");
    const int floor_white = level.add_diffuse("floor", glm::vec3(0.8f));
    const int box_white = level.add_diffuse("box", glm::vec3(0.75f));
    const int pool_tiles = level.add_diffuse("pool tiles", glm::vec3(0.55f, 0.75f, 0.8f));
    scene::Material brass;
    brass.name = "brass";
    brass.base_color = glm::vec4(0.91f, 0.78f, 0.42f, 1.0f);
    brass.metallic = 1.0f;
    brass.roughness = 0.05f;
    brass.double_sided = true;  // the ring's inside is the mirror that focuses the cardioid
    const int brass_material = level.add_material(brass);
    const int sphere_glass = level.add_material(glass("glass", 1.5f));
    const int water = level.add_material(glass("water", 1.33f, {0.9f, 0.97f, 1.0f}));

    // The floor, 6 x 6 m, with the pool's 2 x 2 m opening (x in [-1, 1], z in [0.5, 2.5]) left
    // out: four strips around it.
    scene::Primitive floor;
    append(floor, make_quad({-3, 0, 0.5f}, {6, 0, 0}, {0, 0, -3.5f}, 12, 7));  // behind
    append(floor, make_quad({-3, 0, 3}, {6, 0, 0}, {0, 0, -0.5f}, 12, 1));     // in front
    append(floor, make_quad({-3, 0, 2.5f}, {2, 0, 0}, {0, 0, -2}, 4, 4));      // left
    append(floor, make_quad({1, 0, 2.5f}, {2, 0, 0}, {0, 0, -2}, 4, 4));       // right
    level.add_mesh_node("floor", std::move(floor), floor_white);
    // The brass ring: an open cylinder 1 m across on the floor.
    level.add_mesh_node("brass ring", make_open_cylinder(0.5f, 0.3f, 96), brass_material, -1,
                        {-1.5f, 0.0f, -0.5f});
    // A 1.2 m box open to the front and top, with a glass sphere inside.
    scene::Primitive box;
    append(box, make_quad({-0.6f, 0, -0.6f}, {1.2f, 0, 0}, {0, 1.2f, 0}, 4, 4));  // back
    append(box, make_quad({-0.6f, 0, 0.6f}, {0, 0, -1.2f}, {0, 1.2f, 0}, 4, 4));  // left
    append(box, make_quad({0.6f, 0, -0.6f}, {0, 0, 1.2f}, {0, 1.2f, 0}, 4, 4));   // right
    level.add_mesh_node("box", std::move(box), box_white, -1, {1.5f, 0.0f, -1.0f});
    level.add_mesh_node("glass sphere", make_sphere(0.3f, 48, 24), sphere_glass, -1,
                        {1.5f, 0.3f, -1.0f});
    // A pool: a tiled basin 40 cm deep under a 2 x 2 m water surface whose waves are driven
    // by the wave system from the node's extras (docs/LEVELS.md).
    scene::Primitive pool;
    append(pool, make_quad({-1.0f, -0.4f, 2.5f}, {2, 0, 0}, {0, 0, -2}, 8, 8));    // floor
    append(pool, make_quad({-1.0f, -0.4f, 0.5f}, {2, 0, 0}, {0, 0.4f, 0}, 8, 2));  // walls,
    append(pool, make_quad({1.0f, -0.4f, 2.5f}, {-2, 0, 0}, {0, 0.4f, 0}, 8, 2));  // facing in
    append(pool, make_quad({-1.0f, -0.4f, 2.5f}, {0, 0, -2}, {0, 0.4f, 0}, 8, 2));
    append(pool, make_quad({1.0f, -0.4f, 0.5f}, {0, 0, 2}, {0, 0.4f, 0}, 8, 2));
    level.add_mesh_node("pool", std::move(pool), pool_tiles, -1, {0.0f, 0.0f, 0.0f});
    const int surface = level.add_mesh_node(
        "water surface", make_quad({-1.0f, 0, 2.5f}, {2, 0, 0}, {0, 0, -2}, 48, 48), water);
    level.node(surface).flags.dynamic = true;
    level.node(surface).flags.raw["wave"] = {
        {"amplitude", 0.02}, {"wavelength", 0.5}, {"speed", 0.4}, {"direction", {1.0, 0.3}}};
    level.animate("water bob", surface, AnimatedProperty::Translation, Interpolation::CubicSpline,
                  {0.0f, 2.0f, 4.0f},
                  {as_key(glm::vec3(0)), as_key(glm::vec3(0.0f, -0.02f, 0.0f)),
                   as_key(glm::vec3(0.0f, 0.01f, 0.0f)), as_key(glm::vec3(0)),
                   as_key(glm::vec3(0.0f, 0.02f, 0.0f)), as_key(glm::vec3(0)),
                   as_key(glm::vec3(0.0f, 0.01f, 0.0f)), as_key(glm::vec3(0.0f, -0.02f, 0.0f)),
                   as_key(glm::vec3(0))});

    // The ring spot grazes the ring at 10.6 degrees: light that clears the near rim (0.3 m)
    // reaches the far inside wall and is thrown back across the ring's floor at the same low
    // slope, where the reflections of the curved wall focus into the nephroid (the coffee-cup
    // caustic). From higher up the reflections land in a thin band at the foot of the wall.
    scene::Light spot =
        scene::Light::spot_from_power(glm::vec3(120.0f), glm::radians(20.0f), glm::radians(35.0f));
    spot.name = "ring spot";
    level.add_light(spot, {-3.4f, 0.6f, -0.5f}, aim({2.4f, -0.45f, 0.0f}));
    // Above the box's back wall: the sphere's focus lands on the floor in front of the sphere,
    // where the camera sees it (from straight above it would hide under the sphere).
    level.add_light(point_light("box light", 30.0f), {1.5f, 1.6f, -1.5f});
    scene::Light sun = scene::Light::directional_from_irradiance(glm::vec3(3.0f));
    sun.name = "sun";
    level.add_light(sun, {0.0f, 5.0f, 0.0f}, aim({0.3f, -1.0f, -0.2f}));
    // High enough to see the floor inside the ring.
    level.add_camera("camera", {0.0f, 3.6f, 4.4f}, {-0.2f, 0.0f, -0.3f}, glm::radians(55.0f));
    return level.finish();
}

scene::Scene make_sandbox() {
    LevelBuilder level("sandbox");
    // Two 4 x 3 x 4 m rooms joined along x by a corridor 3 m long, as wide (1 m) and high
    // (2.2 m) as the doorways at its ends:
    //   west room x in [-4, 0], corridor x in [0, 3], east room x in [3, 7]; z in [-2, 2].
    constexpr float depth = 2.0f;
    constexpr float height = 3.0f;
    constexpr float door_half = 0.5f;
    constexpr float door_height = 2.2f;
    constexpr float corridor_end = 3.0f;
    constexpr float window_width = 1.6f;
    constexpr float window_sill = 0.9f;
    constexpr float window_top = 2.3f;
    const int plaster = level.add_diffuse("plaster", glm::vec3(0.78f, 0.76f, 0.72f));
    const int sage = level.add_diffuse("sage plaster", glm::vec3(0.55f, 0.68f, 0.52f));
    const int terracotta = level.add_diffuse("terracotta", glm::vec3(0.72f, 0.42f, 0.30f));
    const int floor_wood = level.add_diffuse("wood floor", glm::vec3(0.55f, 0.38f, 0.22f));
    const int stone = level.add_diffuse("stone", glm::vec3(0.6f, 0.6f, 0.58f));
    const int door_paint = level.add_diffuse("door", glm::vec3(0.20f, 0.30f, 0.55f));
    const int ball_paint = level.add_diffuse("ball", glm::vec3(0.85f, 0.15f, 0.10f));
    const int shade = level.add_diffuse("lamp shade", glm::vec3(0.9f, 0.85f, 0.7f));
    const int overalls = level.add_diffuse("overalls", glm::vec3(0.80f, 0.55f, 0.20f));
    const int sculpture_glass = level.add_material(glass("sculpture glass", 1.5f));

    auto room = [&](const std::string& prefix, float x0, float x1, int walls, bool west) {
        const float width = x1 - x0;
        level.add_mesh_node(prefix + "floor",
                            make_quad({x0, 0, depth}, {width, 0, 0}, {0, 0, -2 * depth}, 8, 8),
                            floor_wood);
        level.add_mesh_node(prefix + "ceiling",
                            make_quad({x0, height, -depth}, {width, 0, 0}, {0, 0, 2 * depth}, 8, 8),
                            plaster);
        // A window in the north wall, the sun and the sky outside it (west: by the lamp;
        // east: behind the sculpture, so the sun's beam crosses the glass).
        const glm::vec3 north_corner(x0, 0, -depth);
        const glm::vec3 along(width, 0, 0);
        const glm::vec3 up(0, height, 0);
        const glm::vec2 hole_low(west ? 1.6f : 1.2f, window_sill);
        const glm::vec2 hole_high(hole_low.x + window_width, window_top);
        level.add_mesh_node(prefix + "north wall",
                            window_wall(north_corner, along, up, hole_low, hole_high), walls);
        add_window_portal(level, prefix + "window", walls, north_corner, along, up, hole_low,
                          hole_high);
        level.add_mesh_node(prefix + "south wall",
                            make_quad({x1, 0, depth}, {-width, 0, 0}, {0, height, 0}, 8, 6), walls);
        if (west) {
            level.add_mesh_node(prefix + "end wall",
                                make_quad({x0, 0, depth}, {0, 0, -2 * depth}, {0, height, 0}, 8, 6),
                                walls);
            level.add_mesh_node(prefix + "doorway wall",
                                doorway_wall(x1, true, depth, door_half, door_height, height),
                                walls);
        } else {
            level.add_mesh_node(prefix + "end wall",
                                make_quad({x1, 0, -depth}, {0, 0, 2 * depth}, {0, height, 0}, 8, 6),
                                walls);
            level.add_mesh_node(prefix + "doorway wall",
                                doorway_wall(x0, false, depth, door_half, door_height, height),
                                walls);
        }
    };
    room("west ", -4.0f, 0.0f, sage, true);
    room("east ", corridor_end, corridor_end + 4.0f, terracotta, false);
    // The corridor: floor, ceiling and its two side walls.
    level.add_mesh_node(
        "corridor floor",
        make_quad({0, 0, door_half}, {corridor_end, 0, 0}, {0, 0, -2 * door_half}, 6, 2), stone);
    level.add_mesh_node(
        "corridor ceiling",
        make_quad({0, door_height, -door_half}, {corridor_end, 0, 0}, {0, 0, 2 * door_half}, 6, 2),
        plaster);
    level.add_mesh_node(
        "corridor north wall",
        make_quad({0, 0, -door_half}, {corridor_end, 0, 0}, {0, door_height, 0}, 6, 4), plaster);
    level.add_mesh_node(
        "corridor south wall",
        make_quad({corridor_end, 0, door_half}, {-corridor_end, 0, 0}, {0, door_height, 0}, 6, 4),
        plaster);

    // The door between the west room and the corridor: hinged at (0, 0, -0.5), it swings
    // 100 degrees into the west room and back on an 8 s loop.
    const int hinge = level.add_node("door hinge", -1, {-0.03f, 0.0f, -door_half});
    level.add_mesh_node("door", make_box({0.04f, door_height - 0.02f, 2 * door_half - 0.02f}),
                        door_paint, hinge, {0.0f, door_height / 2, door_half});
    level.animate("door swing", hinge, AnimatedProperty::Rotation, Interpolation::Linear,
                  {0.0f, 2.0f, 4.0f, 6.0f, 8.0f},
                  {as_key(yaw(0.0f)), as_key(yaw(0.0f)), as_key(yaw(glm::radians(-100.0f))),
                   as_key(yaw(glm::radians(-100.0f))), as_key(yaw(0.0f))});

    // The east room: a glass sculpture turning on a stone plinth under a lamp.
    level.add_mesh_node("plinth", make_box({0.5f, 0.6f, 0.5f}), stone, -1, {5.0f, 0.3f, 0.0f});
    const int sculpture = level.add_mesh_node("glass sculpture", make_box({0.3f, 0.5f, 0.3f}),
                                              sculpture_glass, -1, {5.0f, 0.85f, 0.0f});
    std::vector<float> turn_times;
    std::vector<glm::vec4> turn;
    for (int k = 0; k <= 4; ++k) {
        turn_times.push_back(2.5f * static_cast<float>(k));
        turn.push_back(as_key(yaw(0.5f * kPi * static_cast<float>(k)) *
                              glm::angleAxis(0.35f, glm::vec3(1.0f, 0.0f, 0.0f))));
    }
    level.animate("sculpture turn", sculpture, AnimatedProperty::Rotation, Interpolation::Linear,
                  turn_times, turn);
    level.add_light(point_light("sculpture lamp", 60.0f, {1.0f, 0.95f, 0.85f}), {5.6f, 2.4f, 0.6f});
    level.add_light(point_light("east lamp", 40.0f, {0.9f, 0.95f, 1.0f}), {6.2f, 2.7f, -1.5f});

    // The west room: a lamp swinging on a 0.9 m cord, and a ball that a game system bounces.
    const int pivot = level.add_node("lamp pivot", -1, {-2.0f, height, -0.6f});
    const glm::quat left = glm::angleAxis(glm::radians(30.0f), glm::vec3(0.0f, 0.0f, 1.0f));
    const glm::quat right = glm::angleAxis(glm::radians(-30.0f), glm::vec3(0.0f, 0.0f, 1.0f));
    level.animate("lamp swing", pivot, AnimatedProperty::Rotation, Interpolation::Linear,
                  {0.0f, 1.5f, 3.0f}, {as_key(left), as_key(right), as_key(left)});
    level.add_mesh_node("lamp shade", make_open_cylinder(0.12f, 0.1f, 24), shade, pivot,
                        {0.0f, -0.85f, 0.0f});
    level.add_light(point_light("swinging lamp", 50.0f, {1.0f, 0.85f, 0.65f}), {0.0f, -0.9f, 0.0f},
                    glm::quat(1, 0, 0, 0), pivot);
    const int ball =
        level.add_mesh_node("ball", make_sphere(0.2f, 32, 16), ball_paint, -1, {-1.2f, 0.2f, 0.9f});
    level.node(ball).flags.dynamic = true;
    level.node(ball).flags.raw["bounce"] = {{"height", 1.0}, {"period", 1.2}};

    // A figure (a skinned mesh, issue 29) that walks from the west room's end wall through the
    // corridor to the east room's north side and back on a 16 s loop, twice the door's, passing
    // the doorway at 4.9 s and 13 s while the door stands open (4-6 s of its 8 s loop), along
    // z = 0: clear of the open door leaf (z < -0.5), the ball (z = 0.9) and the lamp's cord.
    add_walker(level, "walker", overalls,
               {{0.0f, {-3.4f, 0.0f}},
                {1.6f, {-3.4f, 0.0f}},
                {4.9f, {0.0f, 0.0f}},
                {7.4f, {3.0f, 0.0f}},
                {8.9f, {4.3f, -1.2f}},
                {9.2f, {4.3f, -1.2f}},
                {10.6f, {3.0f, 0.0f}},
                {13.0f, {0.0f, 0.0f}},
                {15.6f, {-3.4f, 0.0f}},
                {16.0f, {-3.4f, 0.0f}}});

    // The corridor light switches on for 2 s of every 4.
    const int corridor_light =
        level.add_light(point_light("corridor light", 15.0f, {1.0f, 0.9f, 0.75f}),
                        {1.5f, door_height - 0.15f, 0.0f});
    add_switch(level.node(corridor_light), 4.0f, 2.0f, 0.0f);
    // Outside: a sun beyond the north walls, 37 degrees up, shining in through both windows
    // (the east room's beam crosses the glass sculpture), a clear daylight sky and a grassy
    // ground below the horizon (the level has no ground of its own outside).
    scene::Light sun = scene::Light::directional_from_irradiance(glm::vec3(4.0f, 3.8f, 3.4f));
    sun.name = "sun";
    level.add_light(sun, {2.0f, 6.0f, -6.0f}, aim({0.25f, -0.6f, 0.75f}));
    scene::SkySpec sky;
    sky.kind = scene::SkySpec::Kind::Daylight;
    sky.irradiance = 1.5f;
    sky.turbidity = 3.0f;
    sky.ground = glm::vec3(0.22f, 0.26f, 0.16f);
    level.sky() = sky;
    level.add_camera("camera", {-3.5f, 1.6f, 1.6f}, {1.0f, 1.1f, -0.2f}, glm::radians(60.0f));
    return level.finish();
}

scene::Scene make_sky_room() {
    LevelBuilder level("sky-room");
    // A closed 5 x 4 m room, 2.8 m high (x in [-2.5, 2.5], z in [-2, 2]), lit only from outside
    // through a 1.6 x 1.2 m window in its east wall: a uniform blue sky with a ground below the
    // horizon, and a low sun whose beam crosses a block on the floor. Every face is one-sided,
    // facing into the room, so light reaches the inside through the window alone (issue 20's
    // built-in sky room; tests/levels/blender/sky-window.py is Blender's).
    constexpr float half_width = 2.5f;
    constexpr float depth = 2.0f;
    constexpr float height = 2.8f;
    const int plaster = level.add_diffuse("plaster", glm::vec3(0.75f, 0.74f, 0.70f));
    const int sage = level.add_diffuse("sage plaster", glm::vec3(0.50f, 0.64f, 0.48f));
    const int floor_wood = level.add_diffuse("wood floor", glm::vec3(0.52f, 0.36f, 0.22f));
    const int block_paint = level.add_diffuse("block", glm::vec3(0.70f, 0.30f, 0.22f));
    level.add_mesh_node(
        "floor",
        make_quad({-half_width, 0, depth}, {2 * half_width, 0, 0}, {0, 0, -2 * depth}, 10, 8),
        floor_wood);
    level.add_mesh_node(
        "ceiling",
        make_quad({-half_width, height, -depth}, {2 * half_width, 0, 0}, {0, 0, 2 * depth}, 10, 8),
        plaster);
    level.add_mesh_node(
        "north wall",
        make_quad({-half_width, 0, -depth}, {2 * half_width, 0, 0}, {0, height, 0}, 10, 6),
        plaster);
    level.add_mesh_node(
        "south wall",
        make_quad({half_width, 0, depth}, {-2 * half_width, 0, 0}, {0, height, 0}, 10, 6), plaster);
    level.add_mesh_node(
        "west wall", make_quad({-half_width, 0, depth}, {0, 0, -2 * depth}, {0, height, 0}, 8, 6),
        sage);
    // The east wall faces -x; its window spans z in [-0.8, 0.8], y in [0.9, 2.1].
    const glm::vec3 east_corner(half_width, 0, -depth);
    const glm::vec3 along(0, 0, 2 * depth);
    const glm::vec3 up(0, height, 0);
    const glm::vec2 hole_low(1.2f, 0.9f);
    const glm::vec2 hole_high(2.8f, 2.1f);
    level.add_mesh_node("east wall", window_wall(east_corner, along, up, hole_low, hole_high),
                        plaster);
    add_window_portal(level, "window", plaster, east_corner, along, up, hole_low, hole_high);
    level.add_mesh_node("block", make_box({0.8f, 0.75f, 0.8f}), block_paint, -1,
                        {0.3f, 0.375f, -0.5f});
    // The sun, 28 degrees up in the east: its patch falls on the floor 0.8-3.9 m from the
    // window, across the block.
    scene::Light sun = scene::Light::directional_from_irradiance(glm::vec3(3.0f, 2.9f, 2.6f));
    sun.name = "sun";
    level.add_light(sun, {6.0f, 3.5f, 0.0f}, aim({-1.0f, -0.55f, 0.12f}));
    scene::SkySpec sky;
    sky.kind = scene::SkySpec::Kind::Uniform;
    sky.radiance = glm::vec3(0.25f, 0.33f, 0.48f);
    sky.ground = glm::vec3(0.2f);
    level.sky() = sky;
    level.add_camera("camera", {-2.2f, 1.5f, 1.5f}, {2.5f, 1.3f, -0.3f}, glm::radians(60.0f));
    return level.finish();
}

scene::Scene make_furnace(float albedo, float emitted_radiance) {
    LevelBuilder level("furnace");
    scene::Material inside;
    inside.name = "furnace wall";
    inside.base_color = glm::vec4(glm::vec3(albedo), 1.0f);
    inside.metallic = 0.0f;
    inside.roughness = 1.0f;
    inside.emissive = glm::vec3(1.0f);
    inside.emissive_strength = emitted_radiance;
    const int material = level.add_material(inside);
    const int sphere =
        level.add_mesh_node("furnace", make_sphere(1.0f, 64, 32, /*inside=*/true), material);
    level.node(sphere).flags.raw["furnace"] = true;
    level.add_camera("camera", {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, glm::radians(70.0f));
    return level.finish();
}

std::vector<LevelRecipe> built_in_levels() {
    return {
        {"cornell", "Cornell box, bumpy floor ~8k triangles, moving cube and glass sphere",
         [] { return make_cornell("cornell", 62); }},
        {"cornell-13k", "the Cornell box with a ~13k-triangle floor",
         [] { return make_cornell("cornell-13k", 80); }},
        {"cornell-133k", "the Cornell box with a ~133k-triangle floor",
         [] { return make_cornell("cornell-133k", 257); }},
        {"two-rooms", "two rooms, a swinging door, four lights of which two switch",
         [] { return make_two_rooms(); }},
        {"caustics", "brass ring, glass sphere in a box, water surface over a pool",
         [] { return make_caustics(); }},
        {"sandbox",
         "the sandbox game level: two rooms and a corridor, windows with the sun and a "
         "daylight sky outside, door, glass sculpture, bouncing ball, swinging lamp, switched "
         "light",
         [] { return make_sandbox(); }},
        {"sky-room", "a closed room lit only through one window, by a uniform sky and a low sun",
         [] { return make_sky_room(); }},
        {"furnace", "closed sphere, uniform albedo 0.5 and emission 1 W/(m^2 sr)",
         [] { return make_furnace(); }},
    };
}

}  // namespace luxel::levels
