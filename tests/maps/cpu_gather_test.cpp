// The CPU final gather against closed forms: a closed box of constant radiance, and one
// glowing wall seen from a point on the opposite wall (the point-to-rectangle form factor).

#include <cmath>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "luxel/lighting/core/cpu_gather.hpp"
#include "luxel/runtime/jobs.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;

/// An axis-aligned box [0, size]^3 whose six faces point inwards, face f being surface f with
/// light-map UVs spread over its own 8 x 8 texel block of a 64-texel page.
TriangleMesh inward_box(const glm::vec3& size) {
    TriangleMesh mesh;
    // Corners of each face, listed clockwise seen from inside; the indices below reverse them
    // so every face winds (and so faces) inwards.
    const glm::vec3 s = size;
    const glm::vec3 faces[6][4] = {
        {{0, 0, 0}, {s.x, 0, 0}, {s.x, 0, s.z}, {0, 0, s.z}},          // floor y = 0
        {{0, s.y, 0}, {0, s.y, s.z}, {s.x, s.y, s.z}, {s.x, s.y, 0}},  // ceiling
        {{0, 0, 0}, {0, 0, s.z}, {0, s.y, s.z}, {0, s.y, 0}},          // x = 0
        {{s.x, 0, 0}, {s.x, s.y, 0}, {s.x, s.y, s.z}, {s.x, 0, s.z}},  // x = max
        {{0, 0, 0}, {0, s.y, 0}, {s.x, s.y, 0}, {s.x, 0, 0}},          // z = 0
        {{0, 0, s.z}, {s.x, 0, s.z}, {s.x, s.y, s.z}, {0, s.y, s.z}},  // z = max
    };
    for (int f = 0; f < 6; ++f) {
        const auto base = static_cast<std::uint32_t>(mesh.positions.size());
        const glm::vec2 block(static_cast<float>(f * 10 + 1), 1.0f);
        const glm::vec2 corner_uv[4] = {{0, 0}, {8, 0}, {8, 8}, {0, 8}};
        for (int k = 0; k < 4; ++k) {
            mesh.positions.push_back(faces[f][k]);
            mesh.lightmap_uvs.push_back((block + corner_uv[k]) / 64.0f);
        }
        mesh.indices.insert(mesh.indices.end(),
                            {base, base + 2, base + 1, base, base + 3, base + 2});
        mesh.surface_ids.insert(mesh.surface_ids.end(), 2, f);
        mesh.material_ids.insert(mesh.material_ids.end(), 2, 0u);
    }
    return mesh;
}

/// Fills the 8 x 8 block (and its one-texel ring) of surface `f` with `radiance`.
void paint(RadiancePage& page, int f, const glm::vec3& radiance) {
    for (int y = 0; y < 10; ++y) {
        for (int x = 0; x < 10; ++x) {
            page.at(f * 10 + x, y) = radiance;
        }
    }
}

struct Box {
    RayScene scene;
    RadianceAtlas atlas;

    explicit Box(const glm::vec3& size) {
        scene.add_object(inward_box(size), glm::mat4(1.0f), false);
        scene.commit();
        atlas.pages.emplace_back(64);
        atlas.surface_page.assign(6, 0);
    }
};

TEST(CpuGather, ClosedBoxOfConstantRadianceGivesPiL) {
    Box box(glm::vec3(2.0f, 1.5f, 3.0f));
    const glm::vec3 radiance(0.7f, 1.3f, 2.0f);
    for (int f = 0; f < 6; ++f) {
        paint(box.atlas.pages[0], f, radiance);
    }
    ASSERT_EQ(box.scene.triangle_count(), 12u);
    // With the raycasting wrong the orientation check would drop hits: test the faces face in.
    JobSystem jobs(2);
    CpuGatherer gatherer(box.scene, box.atlas, {64, 1e6f}, &jobs);
    const std::vector<GatherTexel> texels = {
        {{1.0f, 0.0f, 1.5f}, {0, 1, 0}},
        {{0.1f, 0.0f, 0.1f}, {0, 1, 0}},
        {{1.0f, 1.5f, 1.5f}, {0, -1, 0}},
        {{0.0f, 0.75f, 2.9f}, {1, 0, 0}},
        {{2.0f, 1.4f, 0.05f}, {-1, 0, 0}},
        {{1.0f, 0.75f, 3.0f}, {0, 0, -1}},
        {{1.0f, 0.7f, 1.2f}, glm::normalize(glm::vec3(1, 2, 3))},
    };
    std::vector<glm::vec3> irradiance(texels.size());
    gatherer.gather(texels, irradiance);
    for (std::size_t i = 0; i < texels.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(irradiance[i][c], glm::pi<float>() * radiance[c],
                        0.01f * glm::pi<float>() * radiance[c])
                << "texel " << i << " channel " << c;
        }
    }
    EXPECT_EQ(gatherer.rays_traced(), 64u * texels.size());
}

/// The irradiance at a point from a Lambertian rectangle of radiance L parallel to its plane,
/// at height h, the point under one corner, sides a and b: E = pi L F with the classic form
/// factor F = (1 / 2pi) (x / sqrt(1 + x^2) atan(y / sqrt(1 + x^2)) + y / sqrt(1 + y^2)
/// atan(x / sqrt(1 + y^2))), x = a / h, y = b / h.
double corner_rectangle_irradiance(double radiance, double a, double b, double h) {
    const double x = a / h;
    const double y = b / h;
    const double f = (x / std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) +
                      y / std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y))) /
                     (2.0 * glm::pi<double>());
    return glm::pi<double>() * radiance * f;
}

TEST(CpuGather, GlowingCeilingMatchesTheFormFactor) {
    Box box(glm::vec3(2.0f, 1.0f, 2.0f));
    paint(box.atlas.pages[0], 1, glm::vec3(3.0f));  // the ceiling only
    CpuGatherer gatherer(box.scene, box.atlas, {4096, 1e6f});
    for (const glm::vec2 p :
         {glm::vec2(1.0f, 1.0f), glm::vec2(0.5f, 1.5f), glm::vec2(0.2f, 0.3f)}) {
        // Sum of the four corner rectangles the point splits the ceiling into.
        double expected = 0.0;
        for (const double a : {static_cast<double>(p.x), 2.0 - p.x}) {
            for (const double b : {static_cast<double>(p.y), 2.0 - p.y}) {
                expected += corner_rectangle_irradiance(3.0, a, b, 1.0);
            }
        }
        const glm::vec3 e = gatherer.gather_one({{p.x, 0.0f, p.y}, {0.0f, 1.0f, 0.0f}});
        EXPECT_NEAR(e.x, expected, 0.01 * expected) << "at " << p.x << ", " << p.y;
    }
}

TEST(CpuGather, BackFacesAndMissesAreBlackAndBadInputIsZero) {
    Box box(glm::vec3(1.0f));
    for (int f = 0; f < 6; ++f) {
        paint(box.atlas.pages[0], f, glm::vec3(1.0f));
    }
    CpuGatherer gatherer(box.scene, box.atlas, {256, 1e6f});
    // Outside the box looking at it: every face seen from outside is a back face.
    const glm::vec3 outside = gatherer.gather_one({{0.5f, 2.0f, 0.5f}, {0.0f, -1.0f, 0.0f}});
    EXPECT_EQ(outside, glm::vec3(0.0f));
    EXPECT_EQ(gatherer.gather_one({{0.5f, 0.5f, 0.5f}, {0.0f, 0.0f, 0.0f}}), glm::vec3(0.0f));
    EXPECT_EQ(gatherer.gather_one({{NAN, 0.5f, 0.5f}, {0.0f, 1.0f, 0.0f}}), glm::vec3(0.0f));
}

TEST(HemiPlaneCoverage, MatchesTheClosedForm) {
    EXPECT_NEAR(hemi_plane_coverage(1.0), 0.554, 0.001);
    EXPECT_NEAR(hemi_plane_coverage(2.0), 0.831, 0.001);
    EXPECT_DOUBLE_EQ(hemi_plane_coverage(0.0), 0.0);
    EXPECT_GT(hemi_plane_coverage(1e3), 0.998);
    EXPECT_LE(hemi_plane_coverage(1e9), 1.0);
}

}  // namespace
