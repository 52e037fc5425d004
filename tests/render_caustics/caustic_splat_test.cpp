// The splat: photons behind an occluder are not splatted while photons on any visible
// surface are, however steep; PhotonWorld-style lists upload only their retraced slices and
// splat the same as one flat upload of their photons.

#include <cmath>

#include <gtest/gtest.h>

#include "caustic_test_scenes.hpp"
#include "caustic_test_support.hpp"
#include "luxel/runtime/jobs.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;

class CausticSplat : public ::testing::Test {
  protected:
    void SetUp() override { context_ = test::make_caustic_gl_context(); }
    void TearDown() override { context_.reset(); }
    std::unique_ptr<GlContext> context_;
};

TEST_F(CausticSplat, PhotonsBehindAnOccluderAreNotSplatted) {
    const glm::ivec2 size(200, 200);
    // A wall at z = 0 and, 1 m in front of it, an occluder covering x < 0 (screen's left half).
    const test::RectScene scene(
        test::look_at({0, 0, 3}, {0, 0, 0}, size),
        {{{0, 0, 0}, {5, 0, 0}, {0, 5, 0}}, {{-2.5f, 0, 1}, {2.5f, 0, 0}, {0, 5, 0}}});
    std::vector<CausticPhoton> photons;
    std::size_t visible = 0;
    for (int i = 0; i < 2000; ++i) {
        const float x = -0.8f + 1.6f * static_cast<float>(i % 40) / 39.0f;
        const float y = -0.8f + 1.6f * static_cast<float>(i / 40) / 49.0f;
        if (std::abs(x) < 0.05f) {
            continue;  // not at the occluder's edge
        }
        CausticPhoton p;
        p.position = {x, y, 0.0f};
        p.power = {0.0f, 1e-3f, 0.0f};  // the wall's photons are green
        photons.push_back(p);
        visible += x > 0.0f ? 1 : 0;
        // And red photons on the occluder itself, which must pass.
        if (x < 0.0f) {
            p.position = {x * 2.0f / 3.0f, y * 2.0f / 3.0f, 1.0f};
            p.power = {1e-3f, 0.0f, 0.0f};
            photons.push_back(p);
            ++visible;
        }
    }
    CausticPass pass(CausticPassSettings{}, size);
    pass.upload(photons);
    pass.render(scene.camera(), scene.depth_texture().id());
    EXPECT_EQ(pass.stats().photons_splatted, visible);
    const std::vector<glm::vec4> splat = test::read_rgba(pass.splat_texture(), size);
    double green_left = 0.0;
    double red_right = 0.0;
    double green_right = 0.0;
    for (int y = 0; y < size.y; ++y) {
        for (int x = 0; x < size.x; ++x) {
            const glm::vec4& e = splat[static_cast<std::size_t>(y * size.x + x)];
            (x < size.x / 2 ? green_left : green_right) += static_cast<double>(e.g);
            red_right += x >= size.x / 2 ? static_cast<double>(e.r) : 0.0;
        }
    }
    EXPECT_EQ(green_left, 0.0);
    EXPECT_EQ(red_right, 0.0);
    EXPECT_GT(green_right, 0.0);
}

TEST_F(CausticSplat, PhotonsOnSteepSurfacesPass) {
    const glm::ivec2 size(200, 200);
    for (const float degrees : {0.0f, 45.0f, 75.0f, 85.0f}) {
        const float a = glm::radians(degrees);
        // A plane through the origin tilted by `degrees` about the y axis, seen from +z.
        const glm::vec3 u(std::cos(a), 0.0f, -std::sin(a));
        const test::RectScene scene(test::look_at({0, 0, 3}, {0, 0, 0}, size),
                                    {{{0, 0, 0}, 5.0f * u, {0, 5, 0}}});
        const std::vector<CausticPhoton> photons =
            test::disc_photons({0, 0, 0}, u, {0, 1, 0}, 0.5f, 3000, glm::vec3(1.0f));
        CausticPass pass(CausticPassSettings{}, size);
        pass.upload(photons);
        pass.render(scene.camera(), scene.depth_texture().id());
        EXPECT_EQ(pass.stats().photons_splatted, photons.size()) << degrees << " degrees";
    }
}

TEST_F(CausticSplat, ListsUploadOnlyRetracedSlices) {
    // The mirror world of tests/photons: a point light, a mirror and a diffuse floor.
    RayScene rays;
    const std::vector<TraceMaterial> materials = {
        {Scattering::Diffuse, glm::vec3(0.5f), glm::vec3(1.0f), 1.5f},
        {Scattering::Mirror, glm::vec3(0.0f), glm::vec3(0.8f), 1.5f}};
    rays.add_object(luxel::testing::quad_mesh({-10, 0, 10}, {20, 0, 0}, {0, 0, -20}, 0, 0),
                    glm::mat4(1.0f), false);
    const TriangleMesh mirror =
        luxel::testing::quad_mesh({0.0f, 0.4f, 0.5f}, {0, 0, -1}, {0, 1, 0}, -1, 1);
    rays.add_object(mirror, glm::mat4(1.0f), false);
    rays.commit();
    LightSource light;
    light.position = {0.8f, 1.2f, 0.15f};
    light.power = glm::vec3(100.0f);
    std::vector<CausticPair> pairs;
    // Without stand-ins (CausticSettings::stand_in), which rewrite slices they did not retrace.
    pairs.push_back({ecs::Entity{}, ecs::Entity{}, CausticPhotonList(4000, 4, 2, false)});
    pairs[0].photons.set_emitter(
        CausticEmitter(light, luxel::testing::bounding_sphere(mirror), {{0, 0, 0}, 15.0f}));
    JobSystem jobs(2);
    for (std::uint32_t k = 0; k < 4; ++k) {
        pairs[0].photons.retrace_slice(rays, materials, k, 16, jobs);
    }
    ASSERT_GT(pairs[0].photons.stored_count(), 100u);

    const glm::ivec2 size(160, 160);
    const test::RectScene scene(test::look_at({-1.0f, 3.0f, 0.01f}, {-1.0f, 0, 0}, size),
                                {{{0, 0, 0}, {10, 0, 0}, {0, 0, 10}}});
    CausticPass pass(CausticPassSettings{}, size);
    pass.upload(pairs);
    EXPECT_EQ(pass.stats().slices_uploaded, 4u);
    pass.upload(pairs);  // nothing retraced: nothing written
    EXPECT_EQ(pass.stats().slices_uploaded, 4u);
    pairs[0].photons.invalidate();
    pairs[0].photons.retrace_slice(rays, materials, 2, 16, jobs);
    pass.upload(pairs);
    EXPECT_EQ(pass.stats().slices_uploaded, 5u);
    pass.render(scene.camera(), scene.depth_texture().id());
    const std::uint32_t splatted = pass.stats().photons_splatted;
    EXPECT_EQ(pass.stats().photons_drawn, pairs[0].photons.stored_count());
    EXPECT_GT(splatted, 100u);

    std::vector<CausticPhoton> flat;
    for (std::uint32_t k = 0; k < 4; ++k) {
        flat.insert(flat.end(), pairs[0].photons.slice(k).begin(), pairs[0].photons.slice(k).end());
    }
    CausticPass reference(CausticPassSettings{}, size);
    reference.upload(flat);
    reference.render(scene.camera(), scene.depth_texture().id());
    EXPECT_EQ(reference.stats().photons_splatted, splatted);
    const std::vector<glm::vec4> a = test::read_rgba(pass.irradiance_texture(), size);
    const std::vector<glm::vec4> b = test::read_rgba(reference.irradiance_texture(), size);
    float worst = 0.0f;
    for (std::size_t i = 0; i < a.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            worst = std::max(worst, std::abs(a[i][c] - b[i][c]) / std::max(b[i][c], 1e-30f));
        }
    }
    EXPECT_LT(worst, 1e-5f);
}

}  // namespace
