// Tile culling changes nothing: the full-screen filter, the early-out filter and the
// compacted (indirect) filter give bit-identical images, and the filter runs only on the
// tiles that hold photons and their neighbours within the kernel's reach.

#include <gtest/gtest.h>

#include "caustic_test_support.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;

class CausticTiles : public ::testing::Test {
  protected:
    void SetUp() override { context_ = test::make_caustic_gl_context(); }
    void TearDown() override { context_.reset(); }
    std::unique_ptr<GlContext> context_;
};

/// Photons through the centres of the pixels [x0, x1) x [y0, y1), on the scene's surface.
std::vector<CausticPhoton> block_photons(const test::RectScene& scene, glm::ivec2 lo,
                                         glm::ivec2 hi) {
    std::vector<CausticPhoton> photons;
    for (int y = lo.y; y < hi.y; ++y) {
        for (int x = lo.x; x < hi.x; ++x) {
            if (const auto p = scene.hit(x, y)) {
                CausticPhoton photon;
                photon.position = *p;
                photon.power =
                    glm::vec3(1e-3f * static_cast<float>(1 + (x * 7 + y * 3) % 5), 2e-3f, 1e-3f);
                photons.push_back(photon);
            }
        }
    }
    return photons;
}

struct Case {
    glm::ivec2 lo;
    glm::ivec2 hi;
    int kernel_radius;
    std::uint32_t marked;
    std::uint32_t filtered;
};

TEST_F(CausticTiles, TiledAndFullScreenFilteringAgreeAndOnlyReachableTilesRun) {
    const glm::ivec2 size(256, 240);  // 16 x 15 tiles
    const test::RectScene scene(test::look_at({0, 0, 3}, {0, 0, 0}, size),
                                {{{0, 0, 0}, {5, 0, 0}, {0, 5, 0}}});
    const std::vector<Case> cases = {
        // Tiles x 5..7, y 4..5 marked (6); with their neighbours x 4..8, y 3..6 (20).
        {{80, 64}, {128, 96}, 3, 6, 20},
        // A single pixel at a tile's corner: one tile marked, its 3 x 3 block filtered.
        {{160, 160}, {161, 161}, 3, 1, 9},
        // k = 8 still reaches one tile.
        {{160, 160}, {161, 161}, 8, 1, 9},
        // In the screen's corner tile: the neighbours are clipped to 2 x 2.
        {{0, 0}, {5, 5}, 3, 1, 4},
        // The last, partial tile row (y 224..239) and column.
        {{250, 230}, {256, 240}, 3, 1, 4},
    };
    for (const Case& c : cases) {
        const std::vector<CausticPhoton> photons = block_photons(scene, c.lo, c.hi);
        std::vector<std::vector<glm::vec4>> images;
        for (const CausticTileMode mode :
             {CausticTileMode::Full, CausticTileMode::EarlyOut, CausticTileMode::Indirect}) {
            CausticPassSettings settings;
            settings.tile_mode = mode;
            settings.kernel_radius = c.kernel_radius;
            CausticPass pass(settings, size);
            pass.upload(photons);
            pass.render(scene.camera(), scene.depth_texture().id());
            const CausticPassStats& stats = pass.stats();
            const int m = static_cast<int>(mode);
            EXPECT_EQ(stats.photons_splatted, photons.size()) << "mode " << m;
            EXPECT_EQ(stats.tiles_total, 16u * 15u);
            EXPECT_EQ(stats.tiles_marked, c.marked) << "mode " << m << " block " << c.lo.x;
            EXPECT_EQ(stats.tiles_filtered,
                      mode == CausticTileMode::Full ? stats.tiles_total : c.filtered)
                << "mode " << m << " block " << c.lo.x;
            images.push_back(test::read_rgba(pass.irradiance_texture(), size));
        }
        std::size_t differing = 0;
        std::size_t non_zero = 0;
        for (std::size_t i = 0; i < images[0].size(); ++i) {
            non_zero += images[0][i] != glm::vec4(0.0f) ? 1 : 0;
            differing += images[1][i] != images[0][i] || images[2][i] != images[0][i] ? 1 : 0;
        }
        EXPECT_GT(non_zero, 0u);
        EXPECT_EQ(differing, 0u) << "block at " << c.lo.x << ", " << c.lo.y;
    }
}

}  // namespace
