// The Embree ray scene: hits report what the tracer needs, dynamic objects move by transform
// only, and ray offsets avoid self-intersection at any scene scale.

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "luxel/lighting/core/halton.hpp"
#include "luxel/lighting/core/ray_scene.hpp"
#include "luxel/runtime/error.hpp"

namespace {

using namespace luxel::lighting;

/// A square in the plane y = 0 from (-h, 0, -h) to (h, 0, h), facing +y, with light-map UVs
/// equal to (x, z) mapped to [0, 1].
TriangleMesh square(float h, std::int32_t surface, std::uint32_t material) {
    TriangleMesh mesh;
    mesh.positions = {{-h, 0, h}, {h, 0, h}, {h, 0, -h}, {-h, 0, -h}};
    mesh.normals = {{0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}};
    mesh.lightmap_uvs = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    mesh.indices = {0, 1, 2, 0, 2, 3};
    mesh.surface_ids = {surface, surface};
    mesh.material_ids = {material, material};
    return mesh;
}

TEST(RayScene, HitReportsPositionNormalsSurfaceMaterialAndLightmapUv) {
    RayScene scene;
    const ObjectId floor = scene.add_object(square(1.0f, 7, 3), glm::mat4(1.0f), false);
    scene.commit();
    const auto hit = scene.intersect({0.5f, 2.0f, -0.5f}, {0.0f, -1.0f, 0.0f});
    ASSERT_TRUE(hit.has_value());
    EXPECT_NEAR(hit->distance, 2.0f, 1e-6f);
    EXPECT_NEAR(hit->position.x, 0.5f, 1e-6f);
    EXPECT_NEAR(hit->position.y, 0.0f, 1e-6f);
    EXPECT_NEAR(hit->geometric_normal.y, 1.0f, 1e-6f);
    EXPECT_NEAR(hit->shading_normal.y, 1.0f, 1e-6f);
    EXPECT_EQ(hit->surface, 7);
    EXPECT_EQ(hit->material, 3u);
    EXPECT_EQ(hit->object, floor);
    EXPECT_NEAR(hit->lightmap_uv.x, 0.75f, 1e-6f);
    EXPECT_NEAR(hit->lightmap_uv.y, 0.25f, 1e-6f);
    EXPECT_FALSE(scene.intersect({0.0f, 2.0f, 0.0f}, {0.0f, 1.0f, 0.0f}).has_value());
    EXPECT_TRUE(scene.occluded({0.0f, 2.0f, 0.0f}, {0.0f, -1.0f, 0.0f}, 3.0f));
    EXPECT_FALSE(scene.occluded({0.0f, 2.0f, 0.0f}, {0.0f, -1.0f, 0.0f}, 1.5f));
}

TEST(RayScene, StaticGeometryIsBakedIntoWorldSpace) {
    RayScene scene;
    const glm::mat4 tilt = glm::translate(glm::mat4(1.0f), {0, 1, 0}) *
                           glm::rotate(glm::mat4(1.0f), glm::half_pi<float>(), {1, 0, 0});
    scene.add_object(square(1.0f, 0, 0), tilt, false);  // now the plane z = 0 facing +z
    scene.commit();
    const auto hit = scene.intersect({0.2f, 1.3f, 5.0f}, {0.0f, 0.0f, -1.0f});
    ASSERT_TRUE(hit.has_value());
    EXPECT_NEAR(hit->position.z, 0.0f, 1e-6f);
    EXPECT_NEAR(hit->geometric_normal.z, 1.0f, 1e-6f);
    EXPECT_NEAR(hit->shading_normal.z, 1.0f, 1e-6f);
}

TEST(RayScene, DynamicObjectsMoveWithoutRebuildingStaticGeometry) {
    RayScene scene;
    scene.add_object(square(10.0f, 0, 0), glm::mat4(1.0f), false);
    const ObjectId lid =
        scene.add_object(square(0.5f, 1, 1), glm::translate(glm::mat4(1.0f), {0, 1, 0}), true);
    scene.commit();
    EXPECT_EQ(scene.static_rebuilds(), 1u);
    auto hit = scene.intersect({0.0f, 5.0f, 0.0f}, {0.0f, -1.0f, 0.0f});
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->object, lid);
    EXPECT_NEAR(hit->position.y, 1.0f, 1e-6f);

    // Move it aside: the ray now reaches the floor; only the top level was recommitted.
    for (int frame = 0; frame < 10; ++frame) {
        scene.set_transform(lid,
                            glm::translate(glm::mat4(1.0f), {3.0f, 1.0f + 0.1f * frame, 0.0f}));
        scene.commit();
    }
    hit = scene.intersect({0.0f, 5.0f, 0.0f}, {0.0f, -1.0f, 0.0f});
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->surface, 0);
    EXPECT_EQ(scene.static_rebuilds(), 1u);
    EXPECT_EQ(scene.top_level_commits(), 11u);
    // A rotated and scaled instance reports world-space normals.
    scene.set_transform(lid, glm::translate(glm::mat4(1.0f), {0, 2, 0}) *
                                 glm::rotate(glm::mat4(1.0f), glm::pi<float>(), {1, 0, 0}) *
                                 glm::scale(glm::mat4(1.0f), {2.0f, 1.0f, 0.5f}));
    scene.commit();
    hit = scene.intersect({0.0f, 5.0f, 0.0f}, {0.0f, -1.0f, 0.0f});
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->object, lid);
    EXPECT_NEAR(hit->geometric_normal.y, -1.0f, 1e-5f);  // flipped over: faces down
    EXPECT_NEAR(glm::length(hit->shading_normal), 1.0f, 1e-5f);
    EXPECT_THROW(scene.set_transform(0, glm::mat4(1.0f)), luxel::Error);

    scene.remove_object(lid);
    scene.commit();
    hit = scene.intersect({0.0f, 5.0f, 0.0f}, {0.0f, -1.0f, 0.0f});
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->surface, 0);
}

TEST(RayScene, ADynamicObjectDeformsInPlaceWithItsBvhRefitted) {
    RayScene scene;
    scene.add_object(square(10.0f, 0, 0), glm::mat4(1.0f), false);
    const ObjectId sheet = scene.add_object(square(0.5f, 1, 1), glm::mat4(1.0f), true);
    std::vector<glm::vec3> positions = scene.mesh(sheet).positions;
    for (glm::vec3& p : positions) {
        p.y += 1.0f;  // lifted
    }
    positions[2] = {4.0f, 3.0f, -0.5f};  // and one corner pulled far out
    std::vector<glm::vec3> normals = scene.mesh(sheet).normals;
    scene.commit();
    scene.deform(sheet, positions, normals);
    scene.commit();
    EXPECT_EQ(scene.static_rebuilds(), 1u) << "the static BVH is left alone";
    // The sheet is hit at its new height, and on the part the pulled corner stretched out.
    auto hit = scene.intersect({-0.4f, 5.0f, 0.4f}, {0.0f, -1.0f, 0.0f});
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->object, sheet);
    EXPECT_GE(hit->position.y, 1.0f - 1e-5f);  // lifted, and tilted up towards the far corner
    EXPECT_LE(hit->position.y, 3.0f);
    hit = scene.intersect({3.0f, 5.0f, -0.4f}, {0.0f, -1.0f, 0.0f});
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->object, sheet) << "the refitted BVH holds the pulled corner";
    EXPECT_NEAR(scene.bounds_max().x, 10.0f, 1e-5f);
    EXPECT_NEAR(scene.bounds_max().y, 3.0f, 1e-5f);
    EXPECT_EQ(scene.mesh(sheet).positions[2], glm::vec3(4.0f, 3.0f, -0.5f));

    positions.pop_back();
    EXPECT_THROW(scene.deform(sheet, positions, normals), luxel::Error);
    positions.push_back({0.0f, NAN, 0.0f});
    EXPECT_THROW(scene.deform(sheet, positions, normals), luxel::Error);
    EXPECT_THROW(scene.deform(0, scene.mesh(0).positions, scene.mesh(0).normals), luxel::Error);
}

TEST(RayScene, MalformedMeshesAreRejected) {
    RayScene scene;
    TriangleMesh mesh = square(1.0f, 0, 0);
    mesh.indices.push_back(9);
    EXPECT_THROW(scene.add_object(mesh, glm::mat4(1.0f), false), luxel::Error);
    mesh = square(1.0f, 0, 0);
    mesh.surface_ids.pop_back();
    EXPECT_THROW(scene.add_object(mesh, glm::mat4(1.0f), true), luxel::Error);
    mesh = square(1.0f, 0, 0);
    mesh.positions[0].x = NAN;
    EXPECT_THROW(scene.add_object(mesh, glm::mat4(1.0f), false), luxel::Error);
}

/// From many points of a plane, rays leave at every angle (down to 0.1 degrees from grazing)
/// after offset_ray_origin: none may hit the plane it left, at scene scales from a millimetre
/// to ten kilometres, and a ray sent back through the plane (side -1) must not re-hit it either.
class RayOffsetAtScale : public ::testing::TestWithParam<float> {};

TEST_P(RayOffsetAtScale, LeavingRaysNeverHitTheirOwnSurface) {
    const float scale = GetParam();
    RayScene scene;
    // A tilted plane far from the origin, so coordinates have large magnitudes.
    const glm::mat4 placement =
        glm::translate(glm::mat4(1.0f), glm::vec3(3.7f, -2.1f, 5.3f) * scale) *
        glm::rotate(glm::mat4(1.0f), 0.4f, glm::normalize(glm::vec3(1, 0.2f, 0.5f)));
    scene.add_object(square(scale, 0, 0), placement, false);
    scene.commit();
    const glm::vec3 normal = glm::normalize(glm::vec3(placement * glm::vec4(0, 1, 0, 0)));
    const glm::vec3 tangent = glm::normalize(glm::vec3(placement * glm::vec4(1, 0, 0, 0)));
    const glm::vec3 bitangent = glm::cross(normal, tangent);
    int self_hits = 0;
    int tested = 0;
    for (std::uint64_t i = 1; i <= 2000; ++i) {
        const glm::dvec2 u = halton2(i);
        // A point on the plane found by a ray from above, as the tracer would find it.
        const glm::vec3 target =
            glm::vec3(placement * glm::vec4((float(u.x) - 0.5f) * 1.8f * scale, 0.0f,
                                            (float(u.y) - 0.5f) * 1.8f * scale, 1.0f));
        const auto hit = scene.intersect(target + normal * scale, -normal);
        ASSERT_TRUE(hit);
        // Leave at an elevation from 0.1 to 90 degrees, on both sides.
        const float elevation = glm::radians(0.1f + 89.9f * float(radical_inverse(5, i)));
        const float azimuth = glm::two_pi<float>() * float(radical_inverse(7, i));
        const glm::vec3 along = std::cos(azimuth) * tangent + std::sin(azimuth) * bitangent;
        for (float side : {1.0f, -1.0f}) {
            const glm::vec3 direction =
                std::cos(elevation) * along + side * std::sin(elevation) * normal;
            const glm::vec3 origin = offset_ray_origin(hit->position, hit->geometric_normal, side);
            ++tested;
            self_hits += scene.intersect(origin, direction).has_value() ? 1 : 0;
            // The offset is small against the scene: well under a millionth of its size.
            ASSERT_LT(glm::length(origin - hit->position), 1e-4f * scale);
        }
    }
    EXPECT_EQ(self_hits, 0) << "of " << tested << " rays at scale " << scale;
}

INSTANTIATE_TEST_SUITE_P(Scales, RayOffsetAtScale, ::testing::Values(1e-3f, 1.0f, 1e4f));

}  // namespace

namespace {

/// Two unit quads back to back in the plane x = 0: one facing -x, one facing +x (a
/// zero-thickness wall between two rooms), with surface ids 1 and 2.
luxel::lighting::TriangleMesh back_to_back_wall() {
    luxel::lighting::TriangleMesh mesh;
    mesh.positions = {{0, -1, -1}, {0, 1, -1}, {0, 1, 1}, {0, -1, 1}};
    // Facing -x: (0,1,0)x(0,0,1) order reversed; facing +x: the other winding.
    mesh.indices = {0, 2, 1, 0, 3, 2, 0, 1, 2, 0, 2, 3};
    mesh.surface_ids = {1, 1, 2, 2};
    mesh.material_ids = {0, 0, 0, 0};
    return mesh;
}

TEST(RaySceneCoincidentFaces, EachSideSeesTheFaceTurnedTowardsIt) {
    luxel::lighting::RayScene scene;
    scene.add_object(back_to_back_wall(), glm::mat4(1.0f), false);
    scene.commit();
    for (int i = 0; i < 50; ++i) {
        const float y = -0.9f + 0.036f * static_cast<float>(i);
        const auto from_west = scene.intersect({-2.0f, y, 0.1f}, {1.0f, 0.0f, 0.0f});
        const auto from_east = scene.intersect({2.0f, y, -0.1f}, {-1.0f, 0.0f, 0.0f});
        ASSERT_TRUE(from_west && from_east);
        // Whichever Embree reports first, the face the ray meets from its own side wins.
        EXPECT_LT(glm::dot(from_west->geometric_normal, glm::vec3(1, 0, 0)), 0.0f);
        EXPECT_GT(glm::dot(from_east->geometric_normal, glm::vec3(1, 0, 0)), 0.0f);
        EXPECT_NE(from_west->surface, from_east->surface);
    }
}

/// Every field intersect_from reports must be what intersect gives for the same ray: the stream
/// is a faster way to ask, not another answer.
void expect_same_hit(const std::optional<RayHit>& stream, const std::optional<RayHit>& single) {
    ASSERT_EQ(stream.has_value(), single.has_value());
    if (!single) {
        return;
    }
    EXPECT_EQ(stream->object, single->object);
    EXPECT_EQ(stream->triangle, single->triangle);
    EXPECT_EQ(stream->surface, single->surface);
    EXPECT_EQ(stream->material, single->material);
    EXPECT_NEAR(stream->distance, single->distance, 1e-5f * single->distance);
    EXPECT_LT(glm::length(stream->position - single->position), 1e-5f);
    EXPECT_LT(glm::length(stream->geometric_normal - single->geometric_normal), 1e-5f);
    EXPECT_LT(glm::length(stream->shading_normal - single->shading_normal), 1e-5f);
    EXPECT_LT(glm::length(stream->lightmap_uv - single->lightmap_uv), 1e-5f);
}

TEST(RaySceneStream, IntersectFromAnswersEveryRayAsIntersectDoes) {
    RayScene scene;
    scene.add_object(square(4.0f, 0, 0), glm::mat4(1.0f), false);   // floor
    scene.add_object(back_to_back_wall(), glm::mat4(1.0f), false);  // x = 0, both sides
    const ObjectId box =
        scene.add_object(square(0.4f, 5, 2),
                         glm::translate(glm::mat4(1.0f), {1.5f, 0.6f, 0.3f}) *
                             glm::rotate(glm::mat4(1.0f), 0.7f, glm::vec3(1.0f, 0.0f, 0.0f)),
                         true);
    const ObjectId gone = scene.add_object(
        square(0.5f, 9, 1), glm::translate(glm::mat4(1.0f), {-1.5f, 0.5f, 0.0f}), true);
    scene.commit();

    const auto compare_from = [&](const glm::vec3& origin, std::size_t rays, std::uint64_t salt) {
        std::vector<glm::vec3> directions;
        for (std::size_t i = 0; i < rays; ++i) {
            // Directions over the whole sphere (some miss everything, some meet the wall's two
            // coincident faces, the moving square or the floor from below).
            const double z = 1.0 - 2.0 * radical_inverse(2, i + salt);
            const double phi = glm::two_pi<double>() * radical_inverse(3, i + salt);
            const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
            directions.emplace_back(static_cast<float>(r * std::cos(phi)), static_cast<float>(z),
                                    static_cast<float>(r * std::sin(phi)));
        }
        std::vector<std::optional<RayHit>> hits(rays);
        scene.intersect_from(origin, directions, 20.0f, hits);
        std::size_t found = 0;
        for (std::size_t i = 0; i < rays; ++i) {
            expect_same_hit(hits[i], scene.intersect(origin, directions[i], 20.0f));
            found += hits[i] ? 1 : 0;
        }
        return found;
    };
    // From both sides of the wall, above and below the floor.
    EXPECT_GT(compare_from({-1.0f, 0.3f, 0.1f}, 64, 1), 32u);
    EXPECT_GT(compare_from({1.0f, 0.3f, -0.1f}, 200, 7), 100u);
    EXPECT_GT(compare_from({0.5f, -1.0f, 0.2f}, 37, 11), 0u);

    // Straight at the coincident faces: the face turned towards the ray, as intersect says.
    std::vector<glm::vec3> at_wall(16, glm::vec3(1.0f, 0.0f, 0.0f));
    std::vector<std::optional<RayHit>> hits(at_wall.size());
    scene.intersect_from({-2.0f, 0.25f, 0.1f}, at_wall, 20.0f, hits);
    for (const auto& hit : hits) {
        ASSERT_TRUE(hit);
        EXPECT_LT(glm::dot(hit->geometric_normal, glm::vec3(1, 0, 0)), 0.0f);
    }

    // A moved object is met where it is now; a removed one, not even before the commit.
    scene.set_transform(box, glm::translate(glm::mat4(1.0f), {2.5f, 0.6f, 0.3f}));
    scene.remove_object(gone);
    scene.commit();
    EXPECT_GT(compare_from({1.0f, 0.3f, -0.1f}, 128, 3), 64u);
    std::vector<glm::vec3> down(4, glm::vec3(0.0f, -1.0f, 0.0f));
    hits.assign(down.size(), std::nullopt);
    scene.intersect_from({-1.5f, 2.0f, 0.0f}, down, 20.0f, hits);
    for (const auto& hit : hits) {
        ASSERT_TRUE(hit);
        EXPECT_EQ(hit->surface, 0);  // the floor, not the removed square
    }

    // No rays, or fewer hit slots than rays: only as many answers as slots.
    scene.intersect_from({0.0f, 1.0f, 0.0f}, {}, 20.0f, hits);
    std::vector<std::optional<RayHit>> one(1);
    scene.intersect_from({-1.5f, 2.0f, 0.0f}, down, 20.0f, one);
    EXPECT_TRUE(one[0].has_value());
}

TEST(RaySceneStream, AnEmptySceneHitsNothing) {
    RayScene scene;
    std::vector<glm::vec3> directions(8, glm::vec3(0.0f, -1.0f, 0.0f));
    std::vector<std::optional<RayHit>> hits(8, RayHit{});
    scene.intersect_from({0.0f, 1.0f, 0.0f}, directions, 10.0f, hits);  // never committed
    for (const auto& hit : hits) {
        EXPECT_FALSE(hit.has_value());
    }
    scene.commit();
    hits.assign(8, RayHit{});
    scene.intersect_from({0.0f, 1.0f, 0.0f}, directions, 10.0f, hits);
    for (const auto& hit : hits) {
        EXPECT_FALSE(hit.has_value());
    }
}

/// The moving objects (instances in a top level of their own, traced after the static BVH with
/// the ray cut at the static hit) are found as the same objects added as static geometry (one
/// flat BVH) are found. Rays aim at points inside flat squares, from all around, with 3 and 12
/// moving objects, before and after they move; intersect, occluded and the streamed query alike.
TEST(RaySceneMovingObjects, RaysFindThemAsAFlatStaticSceneDoes) {
    for (const std::uint32_t count : {3u, 12u}) {
        auto place = [&](std::uint32_t k, float shift) {
            return glm::translate(glm::mat4(1.0f),
                                  {-2.0f + 0.37f * float(k) + shift, 0.3f + 0.11f * float(k % 5),
                                   -1.0f + 0.23f * float(k % 7)}) *
                   glm::rotate(glm::mat4(1.0f), 0.4f * float(k), glm::vec3(1.0f, 0.3f, 0.2f));
        };
        RayScene moving;
        moving.add_object(square(4.0f, 0, 0), glm::mat4(1.0f), false);
        std::vector<ObjectId> ids;
        for (std::uint32_t k = 0; k < count; ++k) {
            ids.push_back(moving.add_object(square(0.15f, 0, k + 1), place(k, 0.0f), true));
        }
        moving.commit();
        for (const float shift : {0.0f, 0.8f}) {
            RayScene flat;
            flat.add_object(square(4.0f, 0, 0), glm::mat4(1.0f), false);
            for (std::uint32_t k = 0; k < count; ++k) {
                flat.add_object(square(0.15f, 0, k + 1), place(k, shift), false);
                moving.set_transform(ids[k], place(k, shift));
            }
            flat.commit();
            moving.commit();
            std::size_t compared = 0;
            std::size_t met = 0;
            for (std::uint32_t k = 0; k < count; ++k) {
                for (std::uint64_t i = 1; i <= 40; ++i) {
                    // A point inside the square (corners kept 2% in), from a point 3 m away.
                    const glm::vec2 uv(-0.147f + 0.294f * float(radical_inverse(2, i)),
                                       -0.147f + 0.294f * float(radical_inverse(3, i)));
                    const glm::vec3 target =
                        glm::vec3(place(k, shift) * glm::vec4(uv.x, 0.0f, uv.y, 1.0f));
                    const double z = 1.0 - 2.0 * radical_inverse(5, i + 100 * k);
                    const double phi = glm::two_pi<double>() * radical_inverse(7, i + 100 * k);
                    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
                    const glm::vec3 origin =
                        target + 3.0f * glm::vec3(float(r * std::cos(phi)), float(z),
                                                  float(r * std::sin(phi)));
                    const glm::vec3 direction = glm::normalize(target - origin);
                    const auto expected = flat.intersect(origin, direction, 10.0f);
                    const auto found = moving.intersect(origin, direction, 10.0f);
                    ASSERT_EQ(expected.has_value(), found.has_value());
                    if (expected) {
                        EXPECT_EQ(found->material, expected->material);
                        EXPECT_NEAR(found->distance, expected->distance, 1e-4f);
                        met += found->material == k + 1 ? 1 : 0;
                    }
                    EXPECT_EQ(moving.occluded(origin, direction, 10.0f),
                              flat.occluded(origin, direction, 10.0f));
                    std::optional<RayHit> streamed;
                    moving.intersect_from(origin, std::span<const glm::vec3>(&direction, 1), 10.0f,
                                          std::span<std::optional<RayHit>>(&streamed, 1));
                    ASSERT_EQ(streamed.has_value(), expected.has_value());
                    if (expected) {
                        EXPECT_EQ(streamed->material, expected->material);
                    }
                    ++compared;
                }
            }
            // Most rays reach the square they aim at (the rest meet another square first).
            EXPECT_GT(met, compared / 2) << count << " objects, shift " << shift;
        }
    }
}

}  // namespace
