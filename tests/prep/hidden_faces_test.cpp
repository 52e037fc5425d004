// Surfaces no one can see (tools/prep hidden_faces.hpp, issue 22): the outside of a closed room
// of slabs and faces pressed against other geometry get coarse texels; an opening, a dynamic
// object, or a level the test cannot judge leave everything as it was.

#include <algorithm>
#include <array>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "luxel/prep/hidden_faces.hpp"
#include "mesh_builders.hpp"
#include "prep_test_support.hpp"

namespace {

using namespace luxel;
using prep::VisibilityTriangle;

/// The six faces of the box [lo, hi], each its own surface (first .. first + 5 in the order
/// -x, +x, -y, +y, -z, +z), wound to face outwards.
void add_box(std::vector<VisibilityTriangle>& out, glm::dvec3 lo, glm::dvec3 hi,
             std::uint32_t first, bool dynamic = false) {
    const auto corner = [&](int i) {
        return glm::dvec3((i & 1) != 0 ? hi.x : lo.x, (i & 2) != 0 ? hi.y : lo.y,
                          (i & 4) != 0 ? hi.z : lo.z);
    };
    // Quads by corner index, counter-clockwise seen from outside.
    constexpr std::array<std::array<int, 4>, 6> kFaces{
        {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}}};
    for (std::uint32_t f = 0; f < 6; ++f) {
        const auto& q = kFaces[f];
        out.push_back({corner(q[0]), corner(q[1]), corner(q[2]), first + f, dynamic});
        out.push_back({corner(q[0]), corner(q[2]), corner(q[3]), first + f, dynamic});
    }
}

enum Side : std::uint32_t { kMinusX, kPlusX, kMinusY, kPlusY, kMinusZ, kPlusZ };

/// A 6 x 3 x 5 m room of 10 cm slabs around the origin's floor (y from 0 to 3), each slab a box
/// of six surfaces: slab k's surfaces are 6k .. 6k + 5. Slab order: floor, ceiling, -x, +x, -z,
/// +z wall. Without `with_front_wall` the +z wall is left out (an open side).
std::vector<VisibilityTriangle> slab_room(bool with_front_wall) {
    std::vector<VisibilityTriangle> t;
    const double w = 0.1;
    add_box(t, {-3.0 - w, -w, -2.5 - w}, {3.0 + w, 0.0, 2.5 + w}, 0);       // floor
    add_box(t, {-3.0 - w, 3.0, -2.5 - w}, {3.0 + w, 3.0 + w, 2.5 + w}, 6);  // ceiling
    add_box(t, {-3.0 - w, 0.0, -2.5}, {-3.0, 3.0, 2.5}, 12);                // -x wall
    add_box(t, {3.0, 0.0, -2.5}, {3.0 + w, 3.0, 2.5}, 18);                  // +x wall
    add_box(t, {-3.0, 0.0, -2.5 - w}, {3.0, 3.0, -2.5}, 24);                // -z wall
    if (with_front_wall) {
        add_box(t, {-3.0, 0.0, 2.5}, {3.0, 3.0, 2.5 + w}, 30);  // +z wall
    }
    return t;
}

constexpr double kTexel = 0.05;
const std::vector<glm::dvec3> kCamera{{0.0, 1.6, 1.0}};

TEST(HiddenFaces, AClosedRoomOfSlabsHidesItsOutsideAndKeepsItsInside) {
    const auto triangles = slab_room(true);
    const prep::Visibility v = prep::find_seen_surfaces(triangles, 36, kCamera, kTexel, 0.2);
    ASSERT_EQ(v.skipped, "");
    ASSERT_EQ(v.seen.size(), 36u);
    // The faces towards the room: the floor's top, the ceiling's bottom, each wall's inner face.
    EXPECT_TRUE(v.seen[0 + kPlusY]);
    EXPECT_TRUE(v.seen[6 + kMinusY]);
    EXPECT_TRUE(v.seen[12 + kPlusX]);
    EXPECT_TRUE(v.seen[18 + kMinusX]);
    EXPECT_TRUE(v.seen[24 + kPlusZ]);
    EXPECT_TRUE(v.seen[30 + kMinusZ]);
    // The outside, and the walls' ends pressed into the neighbouring slabs.
    EXPECT_FALSE(v.seen[0 + kMinusY]);
    EXPECT_FALSE(v.seen[6 + kPlusY]);
    EXPECT_FALSE(v.seen[12 + kMinusX]);
    EXPECT_FALSE(v.seen[18 + kPlusX]);
    EXPECT_FALSE(v.seen[24 + kMinusZ]);
    EXPECT_FALSE(v.seen[30 + kPlusZ]);
    EXPECT_FALSE(v.seen[12 + kMinusY]) << "the -x wall's foot stands on the floor";
    EXPECT_FALSE(v.seen[12 + kPlusY]) << "and its head holds the ceiling";
    int seen = 0;
    for (const bool s : v.seen) {
        seen += s ? 1 : 0;
    }
    EXPECT_EQ(seen, 6) << "only the six faces towards the room";
}

TEST(HiddenFaces, AnOpenSideShowsTheOutsideAndARestingCrateHidesOnlyItsBottom) {
    auto triangles = slab_room(false);
    add_box(triangles, {-0.25, 0.0, -0.25}, {0.25, 0.5, 0.25}, 30);  // a crate on the floor
    const prep::Visibility open = prep::find_seen_surfaces(triangles, 36, kCamera, kTexel, 0.2);
    ASSERT_EQ(open.skipped, "");
    EXPECT_TRUE(open.seen[0 + kMinusY]) << "the floor's underside, reached around the open side";
    EXPECT_TRUE(open.seen[12 + kMinusX]) << "the -x wall's outer face";
    EXPECT_FALSE(open.seen[30 + kMinusY]) << "the crate's bottom lies on the floor";
    for (const Side side : {kMinusX, kPlusX, kPlusY, kMinusZ, kPlusZ}) {
        EXPECT_TRUE(open.seen[30 + side]) << side;
    }

    // A crate that moves shows its bottom when it does: never hidden, never a barrier.
    auto moving = slab_room(true);
    add_box(moving, {-0.25, 0.0, -0.25}, {0.25, 0.5, 0.25}, 36, true);
    const prep::Visibility v = prep::find_seen_surfaces(moving, 42, kCamera, kTexel, 0.2);
    EXPECT_TRUE(v.seen[36 + kMinusY]);
}

TEST(HiddenFaces, WhatCannotBeJudgedIsSeen) {
    const auto room = slab_room(true);
    // No viewpoint, a level too large for the cells and broken coordinates: every surface
    // stays seen, with the reason. A viewpoint inside geometry starts from a free cell beside
    // it, if there is one.
    prep::Visibility v = prep::find_seen_surfaces(room, 36, {}, kTexel, 0.2);
    EXPECT_NE(v.skipped, "");
    EXPECT_EQ(std::count(v.seen.begin(), v.seen.end(), true), 36);

    std::vector<VisibilityTriangle> block;
    add_box(block, {-1.0, -1.0, -1.0}, {1.0, 1.0, 1.0}, 0);
    const std::vector<glm::dvec3> buried{{0.0, 0.0, 0.0}};
    v = prep::find_seen_surfaces(block, 6, buried, 0.001, 1.0);
    EXPECT_EQ(v.skipped, "");
    EXPECT_EQ(std::count(v.seen.begin(), v.seen.end(), true), 0)
        << "inside a closed box every face looks away from the viewpoint";
    const std::vector<glm::dvec3> on_floor{{0.0, 0.0, 0.0}};
    v = prep::find_seen_surfaces(room, 36, on_floor, kTexel, 0.2);
    EXPECT_EQ(v.seen, prep::find_seen_surfaces(room, 36, kCamera, kTexel, 0.2).seen)
        << "a light standing on the floor (its cell solid) floods the room above it";

    v = prep::find_seen_surfaces(room, 36, kCamera, kTexel, 0.001);
    EXPECT_NE(v.skipped.find("too large"), std::string::npos) << v.skipped;
    EXPECT_EQ(std::count(v.seen.begin(), v.seen.end(), true), 36);

    auto broken = room;
    broken[0].a = glm::dvec3(std::numeric_limits<double>::quiet_NaN());
    broken[1].b = glm::dvec3(std::numeric_limits<double>::infinity());
    broken[2].surface = 999;  // past the count: ignored
    v = prep::find_seen_surfaces(broken, 36, kCamera, kTexel, 0.2);
    EXPECT_EQ(v.seen.size(), 36u);
    EXPECT_TRUE(v.seen[0]) << "a surface with a broken triangle is never hidden";
}

/// The slab room as a level: six box nodes and a camera inside.
scene::Scene slab_room_level() {
    const float w = 0.1f;
    scene::Scene s = luxel::testing::single_mesh_scene(
        levels::make_box({6.0f + 2 * w, w, 5.0f + 2 * w}), "floor");
    s.nodes[0].translation = {0.0f, -w / 2, 0.0f};
    luxel::testing::add_mesh_node(s, "ceiling", levels::make_box({6.0f + 2 * w, w, 5.0f + 2 * w}),
                                  {0.0f, 3.0f + w / 2, 0.0f});
    luxel::testing::add_mesh_node(s, "west", levels::make_box({w, 3.0f, 5.0f}),
                                  {-3.0f - w / 2, 1.5f, 0.0f});
    luxel::testing::add_mesh_node(s, "east", levels::make_box({w, 3.0f, 5.0f}),
                                  {3.0f + w / 2, 1.5f, 0.0f});
    luxel::testing::add_mesh_node(s, "north", levels::make_box({6.0f, 3.0f, w}),
                                  {0.0f, 1.5f, -2.5f - w / 2});
    luxel::testing::add_mesh_node(s, "south", levels::make_box({6.0f, 3.0f, w}),
                                  {0.0f, 1.5f, 2.5f + w / 2});
    s.cameras.emplace_back();
    scene::Node camera;
    camera.name = "camera";
    camera.camera = 0;
    camera.translation = {0.0f, 1.6f, 1.0f};
    s.nodes.push_back(camera);
    return s;
}

TEST(HiddenFaces, ARoomOfSlabsSpendsItsTexelsInside) {
    const scene::Scene level = slab_room_level();
    prep::PrepOptions off;
    off.hidden_texel_scale = 1.0;
    const prep::PrepResult all = luxel::testing::run_prep(level, off);
    const prep::PrepResult coarse = luxel::testing::run_prep(level);
    EXPECT_EQ(all.report.hidden_surfaces, 0u);
    EXPECT_GT(coarse.report.hidden_surfaces, 0u);
    EXPECT_EQ(coarse.report.visibility_skipped, "");
    // The inside (floor and ceiling 6.2 x 5.2 m each, walls 2 x (5 + 6) x 3 m) keeps 5 cm
    // texels; the outside (about as much again) gets 40 cm ones.
    const double inside_texels = (2.0 * 6.2 * 5.2 + 2.0 * (5.0 + 6.0) * 3.0) / (0.05 * 0.05);
    EXPECT_GT(static_cast<double>(coarse.report.texels), 0.98 * inside_texels);
    EXPECT_LT(static_cast<double>(coarse.report.texels), 1.1 * inside_texels);
    EXPECT_LT(static_cast<double>(coarse.report.texels),
              0.6 * static_cast<double>(all.report.texels));
    std::printf(
        "[ figures  ] slab room: %lld texels, %lld with hidden surfaces coarse (%zu of "
        "them, %.1f m^2)\n",
        static_cast<long long>(all.report.texels), static_cast<long long>(coarse.report.texels),
        coarse.report.hidden_surfaces, coarse.report.hidden_area);
    const luxel::testing::PageCheck check =
        luxel::testing::check_light_map_pages(coarse.scene, coarse.padding);
    EXPECT_TRUE(check.failures.empty()) << check.failures.front();
}

}  // namespace
