// EmissionPieces: the regular subdivision of an emitting triangle that lets a textured emitter
// emit from where its texture is bright, and the TriangleSampler that picks points by power.

#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <memory>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "luxel/lighting/core/emission_pieces.hpp"
#include "luxel/lighting/core/light_source.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/runtime/image.hpp"
#include "temp_dir.hpp"

namespace {

using namespace luxel::lighting;

double signed_area(const std::array<glm::dvec2, 3>& c) {
    return 0.5 * ((c[1].x - c[0].x) * (c[2].y - c[0].y) - (c[1].y - c[0].y) * (c[2].x - c[0].x));
}

TEST(EmissionPieces, PiecesTileTheTriangleAndEachHoldsItsOwnPoints) {
    for (std::uint32_t level = 1; level <= 9; ++level) {
        double area = 0.0;
        for (std::uint32_t piece = 0; piece < level * level; ++piece) {
            const auto corners = EmissionPieces::corners(level, piece);
            const double a = signed_area(corners);
            EXPECT_NEAR(a, 0.5 / (level * level), 1e-12) << "level " << level << " piece " << piece;
            area += a;
            // Points inside the piece (its centroid, and near each corner) map back to it.
            const glm::dvec2 centre = (corners[0] + corners[1] + corners[2]) / 3.0;
            EXPECT_EQ(EmissionPieces::piece_at(level, centre), piece);
            for (const glm::dvec2& corner : corners) {
                EXPECT_EQ(EmissionPieces::piece_at(level, corner + 0.01 * (centre - corner)), piece)
                    << "level " << level << " piece " << piece;
            }
        }
        EXPECT_NEAR(area, 0.5, 1e-12);
    }
    // Outside the triangle or not finite: clamped onto it, never out of range.
    for (const glm::dvec2 sq :
         {glm::dvec2(2.0, 2.0), glm::dvec2(-1.0, 0.5), glm::dvec2(std::nan(""), 0.2)}) {
        EXPECT_LT(EmissionPieces::piece_at(5, sq), 25u);
    }
}

TEST(EmissionPieces, AddRefusesTheWrongNumberOfPieces) {
    EmissionPieces pieces;
    EXPECT_THROW(pieces.add(2, std::vector<glm::vec3>(3)), luxel::Error);
    EXPECT_THROW(pieces.add(0, {}), luxel::Error);
    pieces.add(2, std::vector<glm::vec3>(4, glm::vec3(1.0f)));
    EXPECT_EQ(pieces.piece_count(), 4u);
    EXPECT_TRUE(pieces.uniform());
}

/// A unit right triangle at z = 0 facing +z, cut into 4 pieces of which only `lit` emits.
LightSource one_lit_piece(std::uint32_t lit, const glm::vec3& radiance) {
    auto pieces = std::make_shared<EmissionPieces>();
    std::vector<glm::vec3> values(4, glm::vec3(0.0f));
    values[lit] = radiance;
    pieces->add(2, values);
    LightSource light;
    light.kind = LightKind::Area;
    light.triangles = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    light.pieces = pieces;
    light.power = radiance / 4.0f;  // the mean over the triangle
    return light;
}

TEST(EmissionPieces, PhotonsLeaveOnlyTheLitPieceAndSumToItsFlux) {
    const glm::vec3 radiance(2.0f, 1.0f, 0.5f);
    for (std::uint32_t lit = 0; lit < 4; ++lit) {
        const LightSource light = one_lit_piece(lit, radiance);
        const PhotonEmitter emitter(light, BoundingSphere{glm::vec3(0.0f), 2.0f});
        // pi L x the piece's area (1/8 m^2).
        const glm::dvec3 flux = glm::dvec3(radiance) * (glm::pi<double>() / 8.0);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(emitter.total_power()[c], flux[c], 1e-6 * flux[c]);
        }
        std::mt19937_64 random(lit);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        constexpr int kPhotons = 2000;
        glm::dvec3 sum(0.0);
        for (int i = 0; i < kPhotons; ++i) {
            const EmittedPhoton photon =
                emitter.emit({unit(random), unit(random)}, {unit(random), unit(random)}, kPhotons);
            sum += glm::dvec3(photon.power);
            EXPECT_EQ(EmissionPieces::piece_at(2, glm::dvec2(photon.origin)), lit)
                << "a photon left an unlit piece";
            EXPECT_GT(photon.direction.z, 0.0f);
        }
        // Every photon of one colour carries the same power: the sum is exact.
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(sum[c], flux[c], 1e-5 * flux[c]) << "lit piece " << lit;
        }
    }
}

TEST(EmissionPieces, SamplerDensityIsZeroOnDarkPiecesAndIntegratesToOne) {
    const LightSource light = one_lit_piece(1, glm::vec3(1.0f));
    const TriangleSampler sampler(light.triangles, light.pieces);
    double integral = 0.0;
    for (std::uint32_t piece = 0; piece < 4; ++piece) {
        const double density = sampler.density(0, piece);
        EXPECT_EQ(density > 0.0, piece == 1);
        integral += density * (0.5 / 4.0);
    }
    EXPECT_NEAR(integral, 1.0, 1e-12);
    // Without pieces: uniform over the area.
    const TriangleSampler plain(light.triangles);
    EXPECT_NEAR(plain.density(0, 0), 2.0, 1e-12);
    EXPECT_THROW(TriangleSampler({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}},
                                 light.pieces),
                 luxel::Error);
}

/// A 64 x 64 PNG checker of 8 x 8 black and white blocks: half white.
std::vector<std::uint8_t> checker_png() {
    luxel::testing::TempDir dir("luxel-pieces");
    luxel::Image image(64, 64, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    for (int y = 0; y < 64; ++y) {
        for (int x = 0; x < 64; ++x) {
            if (((x / 8) + (y / 8)) % 2 == 0) {
                image.set_pixel(x, y, glm::vec4(1.0f));
            }
        }
    }
    luxel::write_png(dir / "checker.png", image);
    std::ifstream stream(dir / "checker.png", std::ios::binary);
    return {std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()};
}

TEST(EmissionPieces, HostileUvsOnManyTrianglesStayWithinThePieceBudget) {
    // 20,000 triangles whose UVs each tile the texture a million times: every one wants the
    // finest level. The pieces stay within kMaxPieces, each piece's mean within its share of
    // the work (nothing here may take long: the test's own timeout is the guard), and the
    // radiance stays finite and within the texture's range.
    luxel::scene::Scene scene;
    scene.images.push_back({"checker", "image/png", checker_png()});
    luxel::scene::Material material;
    material.emissive = glm::vec3(1.0f);
    material.emissive_image = 0;
    scene.materials.push_back(material);
    luxel::scene::Primitive primitive;
    primitive.material = 0;
    constexpr std::uint32_t kTriangles = 20000;
    for (std::uint32_t t = 0; t < kTriangles; ++t) {
        const auto x = static_cast<float>(t);
        primitive.positions.insert(primitive.positions.end(),
                                   {{x, 0.0f, 0.0f}, {x + 1.0f, 0.0f, 0.0f}, {x, 1.0f, 0.0f}});
        primitive.texcoords0.insert(primitive.texcoords0.end(),
                                    {{0.0f, 0.0f}, {1000.0f, 0.0f}, {0.0f, 1000.0f}});
        primitive.indices.insert(primitive.indices.end(), {3 * t, 3 * t + 1, 3 * t + 2});
    }
    scene.meshes.push_back({"hostile", {primitive}});
    const EmissionPieces pieces = EmissionPieces::of_mesh(scene, scene.meshes[0]);
    ASSERT_EQ(pieces.triangle_count(), kTriangles);
    EXPECT_LE(pieces.piece_count(), EmissionPieces::kMaxPieces);
    double sum = 0.0;
    for (std::size_t t = 0; t < pieces.triangle_count(); ++t) {
        for (std::uint32_t k = 0; k < pieces.level(t) * pieces.level(t); ++k) {
            const glm::vec3& r = pieces.radiance(t, k);
            for (int c = 0; c < 3; ++c) {
                ASSERT_TRUE(std::isfinite(r[c]));
                ASSERT_GE(r[c], 0.0f);
                ASSERT_LE(r[c], 1.0f);
            }
            sum += r.x;
        }
    }
    // On average the texture's mean, 1/2, within what a few dozen points per piece estimate.
    const double mean = sum / static_cast<double>(pieces.piece_count());
    EXPECT_NEAR(mean, 0.5, 0.15);
}

}  // namespace
