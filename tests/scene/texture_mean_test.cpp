// The mean of a texture over a triangle's UVs (scene::mean_over_uv_triangle), which decides what
// each piece of an emissive surface emits: exact for triangles covering whole texels, with
// REPEAT wrap, bounded for hostile UVs.

#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "luxel/scene/texture_mean.hpp"

namespace {

using namespace luxel::scene;

/// 8 x 4 texels: 1 in column 0..1 of row 0 (two texels), 0 elsewhere, except texel (7, 3) = 4.
LinearImage test_image() {
    std::vector<glm::vec3> texels(32, glm::vec3(0.0f));
    texels[0] = glm::vec3(1.0f, 0.5f, 0.25f);
    texels[1] = glm::vec3(1.0f, 0.5f, 0.25f);
    texels[3 * 8 + 7] = glm::vec3(4.0f);
    return LinearImage(8, 4, texels);
}

void expect_near(const glm::vec3& a, const glm::vec3& b, float tolerance) {
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(a[c], b[c], tolerance) << "channel " << c;
    }
}

TEST(TextureMean, TwoTrianglesOverTheWholeImageAverageToItsMean) {
    const LinearImage image = test_image();
    const glm::vec3 mean = (2.0f * glm::vec3(1.0f, 0.5f, 0.25f) + glm::vec3(4.0f)) / 32.0f;
    // The two halves of the unit square, each half of the area.
    const glm::vec3 lower = mean_over_uv_triangle(image, {0, 0}, {1, 0}, {0, 1});
    const glm::vec3 upper = mean_over_uv_triangle(image, {1, 1}, {0, 1}, {1, 0});
    expect_near(0.5f * (lower + upper), mean, 1e-6f);
}

TEST(TextureMean, ATriangleInsideOneTexelIsThatTexel) {
    const LinearImage image = test_image();
    // Inside texel (0, 0): u in [0, 1/8], v in [0, 1/4].
    expect_near(mean_over_uv_triangle(image, {0.01, 0.01}, {0.1, 0.02}, {0.02, 0.2}),
                glm::vec3(1.0f, 0.5f, 0.25f), 1e-6f);
    // A triangle covering texels (0, 0) and (1, 0) exactly half each.
    expect_near(mean_over_uv_triangle(image, {0.0, 0.0}, {0.25, 0.0}, {0.125, 0.25}),
                glm::vec3(1.0f, 0.5f, 0.25f), 1e-6f);
}

TEST(TextureMean, RepeatWrapMapsEveryTileToTheSameTexels) {
    const LinearImage image = test_image();
    const glm::vec3 base = mean_over_uv_triangle(image, {0.8, 0.6}, {1.0, 0.7}, {0.9, 1.0});
    for (const glm::dvec2 shift :
         {glm::dvec2(3.0, -2.0), glm::dvec2(-5.0, 7.0), glm::dvec2(1000.0, 1000.0)}) {
        expect_near(
            mean_over_uv_triangle(image, glm::dvec2(0.8, 0.6) + shift, glm::dvec2(1.0, 0.7) + shift,
                                  glm::dvec2(0.9, 1.0) + shift),
            base, 1e-5f);
    }
    EXPECT_GT(base.x, 0.0f) << "the triangle reaches texel (7, 3)";
}

TEST(TextureMean, ATriangleTilingTheImageManyTimesIsEstimatedWithinAPercent) {
    const LinearImage image = test_image();
    const glm::vec3 mean = (2.0f * glm::vec3(1.0f, 0.5f, 0.25f) + glm::vec3(4.0f)) / 32.0f;
    // 200 x 200 tiles: far beyond kMaxExactTexels, so the stratified estimate.
    const glm::vec3 tiled = mean_over_uv_triangle(image, {0, 0}, {200, 0}, {0, 200});
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(tiled[c], mean[c], 0.05f * mean[c]) << "channel " << c;
    }
}

TEST(TextureMean, HostileUvsGiveZeroOrATexelAndNoHang) {
    const LinearImage image = test_image();
    const double inf = std::numeric_limits<double>::infinity();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    expect_near(mean_over_uv_triangle(image, {inf, 0}, {1, 0}, {0, 1}), glm::vec3(0.0f), 0.0f);
    expect_near(mean_over_uv_triangle(image, {nan, 0}, {1, 0}, {0, 1}), glm::vec3(0.0f), 0.0f);
    // No area: the texel under the first corner.
    expect_near(mean_over_uv_triangle(image, {0.05, 0.1}, {0.05, 0.1}, {0.05, 0.1}),
                glm::vec3(1.0f, 0.5f, 0.25f), 0.0f);
    // Enormous but finite: the stratified path, finite and in range.
    const glm::vec3 huge = mean_over_uv_triangle(image, {-1e12, 0}, {1e12, 3}, {0, 1e12});
    for (int c = 0; c < 3; ++c) {
        EXPECT_TRUE(std::isfinite(huge[c]));
        EXPECT_GE(huge[c], 0.0f);
        EXPECT_LE(huge[c], 4.0f);
    }
    expect_near(mean_over_uv_triangle(LinearImage{}, {0, 0}, {1, 0}, {0, 1}), glm::vec3(0.0f),
                0.0f);
}

TEST(TextureMean, TriangleEmissionIsTheFactorTimesTheTexturePerTriangle) {
    Primitive quad;
    quad.positions = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}};
    quad.texcoords0 = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    quad.indices = {0, 1, 2, 0, 2, 3};
    Material material;
    material.emissive = {1.0f, 1.0f, 0.5f};
    material.emissive_strength = 2.0f;
    const LinearImage image = test_image();
    const auto per_triangle = triangle_emission(quad, material, image);
    ASSERT_EQ(per_triangle.size(), 2u);
    const glm::vec3 factor = material.emitted_radiance();
    expect_near(per_triangle[0], factor * mean_over_uv_triangle(image, {0, 0}, {1, 0}, {1, 1}),
                1e-6f);
    // The mean over the quad is the factor times the image's mean (equal areas).
    const glm::vec3 mean = (2.0f * glm::vec3(1.0f, 0.5f, 0.25f) + glm::vec3(4.0f)) / 32.0f;
    expect_near(mean_emission(quad, per_triangle), factor * mean, 1e-5f);
    // Untextured: the factor everywhere.
    for (const glm::vec3& e : triangle_emission(quad, material, LinearImage{})) {
        expect_near(e, factor, 0.0f);
    }
}

}  // namespace
