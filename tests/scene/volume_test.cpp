// Transmissive solids (scene/volume.hpp): Beer-Lambert absorption as KHR_materials_volume
// states it, and which primitives close up (a ray through them crosses two surfaces).

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "cube_scene.hpp"
#include "luxel/scene/volume.hpp"

namespace {

using namespace luxel;

constexpr float kInf = std::numeric_limits<float>::infinity();

scene::Material smoked_glass() {
    scene::Material m;
    m.transmission = 1.0f;
    m.thickness = 0.1f;
    m.attenuation_distance = 0.5f;
    m.attenuation_color = {0.25f, 0.5f, 1.0f};
    return m;
}

TEST(Volume, BeerLambertKeepsTheColourOverTheAttenuationDistance) {
    const scene::Material glass = smoked_glass();
    const glm::vec3 at_distance = scene::volume_transmittance(glass, 0.5f);
    EXPECT_FLOAT_EQ(at_distance.r, 0.25f);
    EXPECT_FLOAT_EQ(at_distance.g, 0.5f);
    EXPECT_FLOAT_EQ(at_distance.b, 1.0f);
    // Twice the distance squares it; half of it takes the square root.
    EXPECT_NEAR(scene::volume_transmittance(glass, 1.0f).r, 0.0625f, 1e-6f);
    EXPECT_NEAR(scene::volume_transmittance(glass, 0.25f).g, std::sqrt(0.5f), 1e-6f);
    EXPECT_EQ(scene::volume_transmittance(glass, 0.0f), glm::vec3(1.0f));
}

TEST(Volume, OnlyATransmissiveSolidWithAColourAbsorbs) {
    scene::Material thin = smoked_glass();
    thin.thickness = 0.0f;  // glTF's thin wall has no inside
    EXPECT_FALSE(scene::absorbs_inside(thin));
    EXPECT_EQ(scene::volume_transmittance(thin, 1.0f), glm::vec3(1.0f));
    scene::Material opaque = smoked_glass();
    opaque.transmission = 0.0f;
    EXPECT_FALSE(scene::absorbs_inside(opaque));
    scene::Material clear = smoked_glass();
    clear.attenuation_distance = kInf;  // the extension's default
    EXPECT_FALSE(scene::absorbs_inside(clear));
    scene::Material white = smoked_glass();
    white.attenuation_color = glm::vec3(1.0f);
    EXPECT_FALSE(scene::absorbs_inside(white));
    EXPECT_TRUE(scene::absorbs_inside(smoked_glass()));
}

TEST(Volume, ExtremeValuesStayInTheUnitInterval) {
    const float tiny = std::numeric_limits<float>::denorm_min();
    const float huge = std::numeric_limits<float>::max();
    const glm::vec3 colours[] = {glm::vec3(0.0f), glm::vec3(1.0f), glm::vec3(0.5f, 0.0f, 1e-30f)};
    for (const glm::vec3& colour : colours) {
        for (const float attenuation : {tiny, 1e-20f, 1.0f, huge, kInf}) {
            for (const float distance : {0.0f, tiny, 1.0f, huge, kInf, -1.0f}) {
                const glm::vec3 kept = scene::beer_lambert(colour, attenuation, distance);
                for (int c = 0; c < 3; ++c) {
                    EXPECT_TRUE(kept[c] >= 0.0f && kept[c] <= 1.0f)
                        << kept[c] << " for colour " << colour[c] << ", attenuation distance "
                        << attenuation << ", distance " << distance;
                }
            }
        }
    }
    // A black colour passes nothing over any positive distance, everything over none.
    EXPECT_EQ(scene::beer_lambert(glm::vec3(0.0f), 1.0f, 1e-6f), glm::vec3(0.0f));
    EXPECT_EQ(scene::beer_lambert(glm::vec3(0.0f), 1.0f, 0.0f), glm::vec3(1.0f));
    // A NaN colour channel (never from a validated scene) passes nothing rather than NaN.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(scene::beer_lambert(glm::vec3(nan, 1.0f, 1.0f), 1.0f, 1.0f).r, 0.0f);
}

/// A unit cube as an exporter writes it: four corners per face (each face its own normals),
/// so no two faces share a vertex index, only positions.
scene::Primitive split_cube() {
    scene::Primitive p;
    luxel::testing::append_box(glm::vec3(-0.5f), glm::vec3(0.5f), p.positions, p.indices);
    return p;
}

TEST(Volume, ACubeWithSplitVerticesIsClosed) {
    EXPECT_TRUE(scene::is_closed_surface(split_cube()));
    // A degenerate triangle (exporters leave them at poles) neither opens nor closes it.
    scene::Primitive with_sliver = split_cube();
    with_sliver.indices.insert(with_sliver.indices.end(), {0u, 0u, 1u});
    EXPECT_TRUE(scene::is_closed_surface(with_sliver));
}

TEST(Volume, ASeamARoundingApartIsClosedAGapIsNot) {
    // The +x face's corners moved as cos(2 pi) and sin(2 pi) move a generated sphere's seam.
    scene::Primitive rounded = split_cube();
    for (std::size_t i = 0; i < 4; ++i) {
        rounded.positions[i] += glm::vec3(6e-8f, -1.7e-7f, 1e-7f);
    }
    EXPECT_TRUE(scene::is_closed_surface(rounded));
    scene::Primitive gap = split_cube();
    for (std::size_t i = 0; i < 4; ++i) {
        gap.positions[i].x += 1e-3f;  // a millimetre off a 1 m cube: a crack
    }
    EXPECT_FALSE(scene::is_closed_surface(gap));
}

TEST(Volume, OpenSheetsAndBrokenIndicesAreNotClosed) {
    scene::Primitive open_box = split_cube();
    open_box.indices.resize(open_box.indices.size() - 6);  // one face missing
    EXPECT_FALSE(scene::is_closed_surface(open_box));

    scene::Primitive quad;
    quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    quad.indices = {0, 1, 2, 0, 2, 3};
    EXPECT_FALSE(scene::is_closed_surface(quad));

    // A face listed twice: its edges are shared by four triangles, not two.
    scene::Primitive doubled = split_cube();
    doubled.indices.insert(doubled.indices.end(), doubled.indices.begin(),
                           doubled.indices.begin() + 6);
    EXPECT_FALSE(scene::is_closed_surface(doubled));

    scene::Primitive out_of_range = split_cube();
    out_of_range.indices.back() = 1000;
    EXPECT_FALSE(scene::is_closed_surface(out_of_range));
    EXPECT_FALSE(scene::is_closed_surface(scene::Primitive{}));
}

}  // namespace
