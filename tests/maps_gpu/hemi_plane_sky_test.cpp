// The hemi-plane gather sees the sky (issue 20): a plane pixel where nothing was drawn looks out
// of the level and reads the sky along its direction, as the CPU gather's escaping rays do.
// Closed forms in open air under a uniform sky of radiance L with a ground of albedo rho: a face
// looking up receives pi L, one looking down pi rho L, one looking sideways pi (L + rho L) / 2.
// In a box open at the top, the floor's centre receives L times the opening's projected solid
// angle, and the GPU gather agrees with the CPU gather there.

#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "gather_scenes.hpp"
#include "luxel/lighting/core/cpu_gather.hpp"
#include "luxel/lighting/core/sky_radiance.hpp"
#include "luxel/lighting/gpu/hemi_plane_gatherer.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;

const glm::vec3 kSky(0.25f, 0.5f, 1.0f);
constexpr float kGround = 0.4f;

class HemiPlaneSky : public ::testing::Test {
  protected:
    void SetUp() override { context_ = test::make_gl_context(); }
    void TearDown() override { context_.reset(); }

    std::unique_ptr<GlContext> context_;
};

/// The uniform sky kSky with the ground kGround, at `scale`.
RadianceAtlas::Sky uniform_sky(float scale = 1.0f) {
    return {std::make_shared<const SkyRadiance>(
                with_ground(SkyRadiance::uniform(kSky), glm::vec3(kGround), glm::vec3(0.0f))),
            scale};
}

std::vector<glm::vec3> gather(IrradianceGatherer& gatherer,
                              const std::vector<GatherTexel>& texels) {
    std::vector<glm::vec3> e(texels.size(), glm::vec3(-1.0f));
    gatherer.gather(texels, e);
    return e;
}

TEST_F(HemiPlaneSky, InOpenAirAFaceReceivesTheSkyAndTheGroundItFaces) {
    // A small box far off to one side, so the scene is not empty; no texel sees it.
    RayScene scene;
    scene.add_object(test::box_mesh(glm::vec3(50.0f), glm::vec3(51.0f), false), glm::mat4(1.0f),
                     false);
    scene.commit();
    RadianceAtlas atlas = test::constant_atlas(6, glm::vec3(0.0f));
    atlas.skies.push_back(uniform_sky());
    const std::vector<GatherTexel> texels = {
        {{0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}},
        {{1.0f, 2.0f, -3.0f}, {0.0f, -1.0f, 0.0f}},
        {{-2.0f, 1.0f, 0.5f}, {1.0f, 0.0f, 0.0f}},
        {{0.5f, 0.5f, 0.5f}, glm::normalize(glm::vec3(0.0f, 0.0f, -1.0f))},
    };
    const double pi = glm::pi<double>();
    const glm::dvec3 sky(kSky);
    const std::vector<glm::dvec3> expected = {pi * sky, pi * kGround * sky,
                                              0.5 * pi * (1.0 + kGround) * sky,
                                              0.5 * pi * (1.0 + kGround) * sky};
    HemiPlaneGatherer gpu(scene, atlas, HemiPlaneSettings{});
    std::vector<glm::vec3> e = gather(gpu, texels);
    for (std::size_t i = 0; i < texels.size(); ++i) {
        std::printf("[ figures  ] open air, texel %zu: %.4f %.4f %.4f (expected %.4f %.4f %.4f)\n",
                    i, e[i].r, e[i].g, e[i].b, expected[i].r, expected[i].g, expected[i].b);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(e[i][c], expected[i][c], 0.01 * expected[i][c])
                << "texel " << i << " channel " << c;
        }
    }
    // Two skies add, each at its scale (the frame's background sums them the same way).
    atlas.skies.push_back(uniform_sky(2.0f));
    e = gather(gpu, texels);
    EXPECT_NEAR(e[0].g, 3.0 * expected[0].g, 0.01 * 3.0 * expected[0].g);
    // No sky: nothing.
    atlas.skies.clear();
    e = gather(gpu, texels);
    for (const glm::vec3& v : e) {
        EXPECT_EQ(v, glm::vec3(0.0f));
    }
}

TEST_F(HemiPlaneSky, TheFloorOfABoxOpenAtTheTopSeesTheOpeningAsTheCpuGatherDoes) {
    // The box [-1, 1]^3 facing inwards without its top (face +y, triangles 6 and 7): black
    // walls, the sky through the opening. From the floor's centre, 1.99 m below it, the
    // opening of half side 1 has projected solid angle 4 (x / s) atan(x / s), x = a / h,
    // s = sqrt(1 + x^2) (docs/METHOD.md §6.11).
    TriangleMesh box = test::box_mesh(glm::vec3(-1.0f), glm::vec3(1.0f), true);
    box.indices.erase(box.indices.begin() + 18, box.indices.begin() + 24);
    box.surface_ids.erase(box.surface_ids.begin() + 6, box.surface_ids.begin() + 8);
    if (box.material_ids.size() > 6) {
        box.material_ids.erase(box.material_ids.begin() + 6, box.material_ids.begin() + 8);
    }
    RayScene scene;
    scene.add_object(std::move(box), glm::mat4(1.0f), false);
    scene.commit();
    RadianceAtlas atlas = test::constant_atlas(6, glm::vec3(0.0f));
    atlas.skies.push_back(uniform_sky());
    const std::vector<GatherTexel> texels = {
        {{0.0f, -0.99f, 0.0f}, {0.0f, 1.0f, 0.0f}},
        {{0.5f, -0.99f, -0.4f}, {0.0f, 1.0f, 0.0f}},
        {{0.99f, 0.0f, 0.0f}, {-1.0f, 0.0f, 0.0f}},
    };
    // A wide plane sees nearly the whole hemisphere (F(8) = 98.5%): the default a = 2 takes
    // the missed horizon band to be as bright as the rest, which black walls are not.
    HemiPlaneSettings settings;
    settings.half_width = 8.0f;
    settings.resolution = 512;
    settings.texels_per_batch = 4;
    HemiPlaneGatherer gpu(scene, atlas, settings);
    const std::vector<glm::vec3> e = gather(gpu, texels);
    const double x = 1.0 / 1.99;
    const double s = std::sqrt(1.0 + x * x);
    const double psa = 4.0 * (x / s) * std::atan(x / s);
    const double expected = psa * kSky.g;
    std::printf("[ figures  ] open box, floor centre: GPU %.4f, closed form %.4f\n", e[0].g,
                expected);
    EXPECT_NEAR(e[0].g, expected, 0.03 * expected);

    CpuGatherSettings cpu_settings;
    cpu_settings.rays_per_texel = 16384;
    CpuGatherer cpu(scene, atlas, cpu_settings);
    for (std::size_t i = 0; i < texels.size(); ++i) {
        const glm::vec3 reference = cpu.gather_one(texels[i]);
        std::printf("[ figures  ] open box, texel %zu: GPU %.4f, CPU %.4f\n", i, e[i].g,
                    reference.g);
        EXPECT_GT(reference.g, 0.0f) << i;
        EXPECT_NEAR(e[i].g, reference.g, 0.04 * reference.g) << "texel " << i;
    }
}

}  // namespace
