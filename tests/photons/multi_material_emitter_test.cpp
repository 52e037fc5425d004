// An area light whose mesh has several emissive materials emits each one's radiance from its
// own triangles (issue 21: the photons once took the first material's radiance for the whole
// mesh), and triangles of a material that does not emit emit nothing.

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "luxel/ecs/transform_system.hpp"
#include "luxel/lighting/components.hpp"
#include "luxel/lighting/core/photon_world.hpp"
#include "luxel/scene/components.hpp"

namespace {

using namespace luxel;

/// A quad in the z = 0 plane facing +z over [x0, x0 + w] x [0, h].
scene::Primitive quad(float x0, float w, float h, int material) {
    scene::Primitive p;
    p.positions = {{x0, 0.0f, 0.0f}, {x0 + w, 0.0f, 0.0f}, {x0 + w, h, 0.0f}, {x0, h, 0.0f}};
    p.indices = {0, 1, 2, 0, 2, 3};
    p.material = material;
    return p;
}

scene::Material emitting(const glm::vec3& radiance) {
    scene::Material m;
    m.base_color = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
    m.emissive = radiance;
    return m;
}

TEST(MultiMaterialEmitter, EachMaterialEmitsItsOwnRadianceFromItsOwnTriangles) {
    // One mesh: a 1 x 1 m red quad (2 W/(m^2 sr)) at x in [0, 1], a 1 x 0.5 m blue quad
    // (3 W/(m^2 sr)) at x in [2, 3] and a grey quad that does not emit at x in [4, 5].
    const glm::vec3 red(2.0f, 0.0f, 0.0f);
    const glm::vec3 blue(0.0f, 0.0f, 3.0f);
    auto source = std::make_shared<scene::Scene>();
    source->materials = {emitting(red), emitting(blue), emitting(glm::vec3(0.0f))};
    source->meshes.push_back(
        {"sign",
         {quad(0.0f, 1.0f, 1.0f, 0), quad(2.0f, 1.0f, 0.5f, 1), quad(4.0f, 1.0f, 1.0f, 2)}});

    ecs::Registry registry;
    const ecs::Entity sign = registry.create();
    registry.emplace<scene::MeshInstance>(sign, source, 0);
    registry.emplace<ecs::Transform>(sign, glm::vec3(0.0f));
    registry.emplace<lighting::AreaLight>(sign);
    ecs::TransformSystem transforms(registry);
    transforms.update();
    lighting::PhotonWorld world(registry);
    world.sync();

    const auto lights = world.active_lights();
    ASSERT_EQ(lights.size(), 1u);
    const lighting::PhotonEmitter& emitter = lights[0]->emitter();
    // pi L A for each material: red 2 pi x 1 m^2, blue 3 pi x 0.5 m^2; the grey quad adds none.
    const glm::dvec3 flux(2.0 * glm::pi<double>(), 0.0, 1.5 * glm::pi<double>());
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(emitter.total_power()[c], flux[c], 1e-5 * glm::pi<double>()) << "channel " << c;
    }

    std::mt19937_64 random(7);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    constexpr int kPhotons = 4000;
    glm::dvec3 sum(0.0);
    int from_red = 0;
    int from_blue = 0;
    for (int i = 0; i < kPhotons; ++i) {
        const lighting::EmittedPhoton photon =
            emitter.emit({unit(random), unit(random)}, {unit(random), unit(random)}, kPhotons);
        ASSERT_TRUE(std::isfinite(photon.power.x) && std::isfinite(photon.power.z));
        sum += glm::dvec3(photon.power);
        const float x = photon.origin.x;
        ASSERT_LT(x, 3.0f + 1e-4f) << "a photon left the quad that does not emit";
        if (x <= 1.0f + 1e-4f) {
            ++from_red;
            EXPECT_GT(photon.power.x, 0.0f);
            EXPECT_EQ(photon.power.z, 0.0f) << "a photon of the red quad carries blue";
        } else {
            ASSERT_GE(x, 2.0f - 1e-4f) << "a photon left the gap between the quads";
            ++from_blue;
            EXPECT_EQ(photon.power.x, 0.0f) << "a photon of the blue quad carries red";
            EXPECT_GT(photon.power.z, 0.0f);
        }
    }
    EXPECT_GT(from_red, kPhotons / 4);
    EXPECT_GT(from_blue, kPhotons / 4);
    // The photons sum to each material's flux (a Monte Carlo sum over which quad each photon
    // leaves: a few percent at 4,000 photons).
    EXPECT_NEAR(sum.x, flux.x, 0.05 * flux.x);
    EXPECT_NEAR(sum.z, flux.z, 0.05 * flux.z);
    EXPECT_EQ(sum.y, 0.0);
}

}  // namespace
