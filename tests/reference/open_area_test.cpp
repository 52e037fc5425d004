// The reference's texel area counts only the part of a texel a camera can see: a box resting on
// a floor hides the texels under it, and those its edge crosses count the part beside it
// (ReferenceTexel::area). Photons landing on the hidden part are not binned (open_texel_at), so
// a bin holds the light on the visible part, which is what a light map beside the box must show.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "cube_scene.hpp"
#include "luxel/lighting/reference/reference_scene.hpp"
#include "scene_builder.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;
using namespace luxel::lighting::reference;

constexpr float kHalf = 2.0f;  // the floor spans 4 x 4 m
constexpr int kSize = 16;      // texels per edge: 0.25 m texels
constexpr double kTexelArea = 0.0625;

/// A closed box [-a, a] x [bottom, top] x [-a, a], faces outward, not light-mapped.
TriangleMesh box(float a, float bottom, float top) {
    TriangleMesh mesh;
    luxel::testing::append_box({-a, bottom, -a}, {a, top, a}, mesh.positions, mesh.indices);
    mesh.surface_ids.assign(12, -1);
    mesh.material_ids.assign(12, 0);
    return mesh;
}

/// The floor as `cells` x `cells` quads (two triangles each) with the quad's light-map UVs: a
/// finely meshed floor whose triangles cut the texels into slivers.
TriangleMesh meshed_floor(int cells) {
    TriangleMesh mesh;
    for (int j = 0; j <= cells; ++j) {
        for (int i = 0; i <= cells; ++i) {
            const float u = static_cast<float>(i) / static_cast<float>(cells);
            const float v = static_cast<float>(j) / static_cast<float>(cells);
            mesh.positions.emplace_back((2.0f * u - 1.0f) * kHalf, 0.0f, (2.0f * v - 1.0f) * kHalf);
            mesh.lightmap_uvs.emplace_back(u, v);
            mesh.normals.emplace_back(0.0f, 1.0f, 0.0f);
        }
    }
    const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(j * (cells + 1) + i); };
    for (int j = 0; j < cells; ++j) {
        for (int i = 0; i < cells; ++i) {
            // Wound towards +y, as horizontal_quad's top.
            mesh.indices.insert(mesh.indices.end(), {at(i, j), at(i, j + 1), at(i + 1, j + 1),
                                                     at(i, j), at(i + 1, j + 1), at(i + 1, j)});
        }
    }
    mesh.surface_ids.assign(mesh.indices.size() / 3, 0);
    mesh.material_ids.assign(mesh.indices.size() / 3, 0);
    return mesh;
}

/// The floor's texel areas with `extra` in the scene.
std::vector<double> floor_areas(
    const std::vector<TriangleMesh>& extra,
    const TriangleMesh& floor = luxel::testing::horizontal_quad(0.0f, kHalf, true, 0, 0)) {
    RayScene rays;
    rays.add_object(floor, glm::mat4(1.0f), false);
    for (const TriangleMesh& mesh : extra) {
        rays.add_object(mesh, glm::mat4(1.0f), false);
    }
    rays.commit();
    const ReferenceScene scene(rays, {TraceMaterial{}}, {},
                               {luxel::testing::quad_texels(0, 0.0f, kHalf, true, kSize)});
    return scene.texel_areas();
}

/// The share of the texel at page (x, y) under [-a, a]^2, texels 0.25 m from -2 m.
double covered(int x, int y, double a) {
    const auto overlap = [&](int i) {
        const double lo = -2.0 + 0.25 * i;
        return std::max(0.0, std::min(lo + 0.25, a) - std::max(lo, -a)) / 0.25;
    };
    return overlap(x) * overlap(y);
}

void expect_open_areas(const std::vector<double>& areas, double a, const char* what) {
    ASSERT_EQ(areas.size(), static_cast<std::size_t>(kSize * kSize));
    int partial = 0;
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
            const double open = 1.0 - covered(x, y, a);
            partial += open > 0.0 && open < 1.0 ? 1 : 0;
            EXPECT_NEAR(areas[static_cast<std::size_t>(y * kSize + x)], open * kTexelArea, 1e-9)
                << what << ": texel " << x << ", " << y;
        }
    }
    EXPECT_EQ(partial, 20) << what;  // 4 x 4 under it, a ring of 16 halves and 4 corners
}

TEST(ReferenceOpenArea, ABoxOnTheFloorHidesWhatItStandsOnAndHalfOfWhatItsEdgeCrosses) {
    // 1.25 m box: its edges run through the middle of texels (x = +-0.625 m), so 4 x 4 texels
    // lie wholly under it, 16 half and 4 corner texels three quarters open.
    expect_open_areas(floor_areas({box(0.625f, 0.0f, 0.5f)}), 0.625, "bottom in the floor");
    // The same box 5 mm above the floor (a bumpy floor's gap): hidden as well.
    expect_open_areas(floor_areas({box(0.625f, 0.005f, 0.5f)}), 0.625, "5 mm gap");
}

TEST(ReferenceOpenArea, AFinelyMeshedFloorUnderTheBoxIsHiddenToo) {
    // 37 x 37 cells of 10.8 cm over 25 cm texels: many triangle-texel overlaps are slivers
    // holding no sub-point, which take the sub-point nearest them. Under the box nothing is
    // left open; the ring's areas come out within a sixteenth of a texel of the exact ones.
    const std::vector<double> areas = floor_areas({box(0.625f, 0.0f, 0.5f)}, meshed_floor(37));
    ASSERT_EQ(areas.size(), static_cast<std::size_t>(kSize * kSize));
    double total = 0.0;
    double exact = 0.0;
    double worst = 0.0;
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
            const double want = (1.0 - covered(x, y, 0.625)) * kTexelArea;
            const double got = areas[static_cast<std::size_t>(y * kSize + x)];
            worst = std::max(worst, std::abs(got - want) / kTexelArea);
            if (want == 0.0) {
                EXPECT_EQ(got, 0.0) << "texel " << x << ", " << y << " lies under the box";
            }
            EXPECT_NEAR(got, want, kTexelArea / 16.0) << "texel " << x << ", " << y;
            total += got;
            exact += want;
        }
    }
    EXPECT_NEAR(total, exact, 0.01 * exact);
    std::printf(
        "[ figures  ] finely meshed floor under a box: open area worst texel off by %.3f of a "
        "texel, in all %+.3f%%\n",
        worst, 100.0 * (total / exact - 1.0));
}

TEST(ReferenceOpenArea, AFloorUnderARoofSeenFromBehindOrATableTopStaysOpen) {
    // A 1 m roof patch 1 m up facing the sky (its back towards the floor), and a table top
    // 0.7 m up facing the floor: neither rests on the floor.
    TriangleMesh roof = luxel::testing::horizontal_quad(1.0f, 0.5f, true, -1, 0);
    roof.surface_ids.assign(2, -1);
    TriangleMesh table = luxel::testing::horizontal_quad(0.7f, 0.5f, false, -1, 0);
    table.surface_ids.assign(2, -1);
    for (const TriangleMesh& above : {roof, table}) {
        for (double area : floor_areas({above})) {
            EXPECT_NEAR(area, kTexelArea, 1e-9);
        }
    }
}

TEST(ReferenceOpenArea, PhotonsOnTheHiddenPartAreNotBinned) {
    RayScene rays;
    rays.add_object(luxel::testing::horizontal_quad(0.0f, kHalf, true, 0, 0), glm::mat4(1.0f),
                    false);
    rays.add_object(box(0.625f, 0.0f, 0.5f), glm::mat4(1.0f), false);
    rays.commit();
    const ReferenceScene scene(rays, {TraceMaterial{}}, {},
                               {luxel::testing::quad_texels(0, 0.0f, kHalf, true, kSize)});
    // Texel (5, 8) spans x in [-0.75, -0.5]: the box covers its right half (x > -0.625).
    const auto uv = [](double x, double z) {
        return glm::vec2(static_cast<float>((x + 2.0) / 4.0), static_cast<float>((z + 2.0) / 4.0));
    };
    const std::int64_t texel = scene.texel_at(0, uv(-0.70, 0.1));
    ASSERT_EQ(texel, 8 * kSize + 5);
    EXPECT_EQ(scene.open_texel_at(0, uv(-0.70, 0.1)), texel);  // beside the box
    EXPECT_EQ(scene.open_texel_at(0, uv(-0.55, 0.1)), -1);     // under it
    EXPECT_EQ(scene.texel_at(0, uv(-0.55, 0.1)), texel);
    EXPECT_EQ(scene.open_texel_at(0, uv(1.5, 1.5)), scene.texel_at(0, uv(1.5, 1.5)));
    EXPECT_EQ(scene.open_texel_at(1, uv(1.5, 1.5)), -1);  // no such surface
}

/// The floor's open area (m^2, of 16) under a 3 x 3 m sheet 0.4 m above it, facing up, of
/// `scattering`: the floor's centre sees the sheet from behind straight up and 60 degrees off.
double open_under_sheet(Scattering scattering) {
    RayScene rays;
    rays.add_object(luxel::testing::horizontal_quad(0.0f, kHalf, true, 0, 0), glm::mat4(1.0f),
                    false);
    rays.add_object(luxel::testing::horizontal_quad(0.4f, 1.5f, true, -1, 1), glm::mat4(1.0f),
                    false);
    rays.commit();
    TraceMaterial sheet;
    sheet.scattering = scattering;
    const ReferenceScene scene(rays, {TraceMaterial{}, sheet}, {},
                               {luxel::testing::quad_texels(0, 0.0f, kHalf, true, kSize)});
    double open = 0.0;
    for (const double area : scene.texel_areas()) {
        open += area;
    }
    return open;
}

TEST(ReferenceOpenArea, AFloorUnderWaterIsOpen) {
    // Light passes through glass and water: the floor of a pool is lit all over. An opaque
    // sheet in the same place reads as a closed object's inside around the centre, as the
    // hidden-point test means it to (a crate with a bottom face seen from within).
    EXPECT_NEAR(open_under_sheet(Scattering::Dielectric), 16.0, 1e-9);
    EXPECT_LT(open_under_sheet(Scattering::Diffuse), 15.0);
}

}  // namespace
