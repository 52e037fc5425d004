// Sky photons through a portal (issue 20): the emitter's photons that cross a window carry
// exactly the sky's flux through it, for a uniform sky (a closed form) and a daylight sky (its
// own integral), with every photon finite and bounded; and the tracer drops a portal photon
// whose way back to the sky is blocked.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "luxel/lighting/core/halton.hpp"
#include "luxel/lighting/core/light_source.hpp"
#include "luxel/lighting/core/photon_map.hpp"
#include "luxel/lighting/core/photon_tracer.hpp"
#include "luxel/lighting/core/ray_scene.hpp"
#include "luxel/lighting/core/sky_radiance.hpp"

namespace {

using namespace luxel::lighting;

constexpr double kPi = glm::pi<double>();

/// A 1.2 x 1.0 m window in the plane z = 0 between x in [-0.6, 0.6] and y in [1, 2]: the room
/// is on the -z side, the sky on the +z side.
std::vector<glm::vec3> window() {
    return {{-0.6f, 1.0f, 0.0f}, {0.6f, 1.0f, 0.0f}, {0.6f, 2.0f, 0.0f},
            {-0.6f, 1.0f, 0.0f}, {0.6f, 2.0f, 0.0f}, {-0.6f, 2.0f, 0.0f}};
}

/// A parallelogram from `corner` along `a` and `b` (two triangles, both windings: seen from
/// either side), light-mapped surface `surface`.
TriangleMesh quad(const glm::vec3& corner, const glm::vec3& a, const glm::vec3& b,
                  std::int32_t surface) {
    TriangleMesh mesh;
    mesh.positions = {corner, corner + a, corner + a + b, corner + b};
    mesh.indices = {0, 1, 2, 0, 2, 3, 0, 2, 1, 0, 3, 2};
    mesh.surface_ids.assign(4, surface);
    mesh.material_ids.assign(4, 0);
    return mesh;
}

LightSource sky_through_window(SkyRadiance sky) {
    LightSource light;
    light.kind = LightKind::Sky;
    light.sky = std::make_shared<const SkyRadiance>(std::move(sky));
    light.portals = window();
    return light;
}

/// What the emitter's photons carry into the room (travelling towards -z), summed over
/// `count` photons, and the largest one.
struct Crossing {
    glm::dvec3 into_room{0.0};
    double largest = 0.0;
    bool finite = true;
    bool all_from_portal = true;
};

Crossing emit_all(const PhotonEmitter& emitter, std::uint64_t count) {
    Crossing out;
    for (std::uint64_t i = 1; i <= count; ++i) {
        const EmittedPhoton photon =
            emitter.emit({photon_sample(i, 0, 1), photon_sample(i, 1, 1)},
                         {photon_sample(i, 2, 1), photon_sample(i, 3, 1)}, count);
        out.finite = out.finite && std::isfinite(photon.power.r + photon.power.g + photon.power.b);
        out.all_from_portal = out.all_from_portal && photon.from_portal;
        out.largest = std::max(out.largest, static_cast<double>(photon.power.g));
        if (photon.direction.z < 0.0f) {
            out.into_room += glm::dvec3(photon.power);
        }
    }
    return out;
}

TEST(SkyPortal, AUniformSkysPhotonsCarryItsFluxThroughTheWindow) {
    // Radiance L from every direction above the horizon: through a vertical opening of area A
    // from the side facing the sky, the flux is L A times the integral of cos over the quarter
    // sphere above the horizon on that side, pi / 2.
    const float radiance = 0.8f;
    const PhotonEmitter emitter(sky_through_window(SkyRadiance::uniform(glm::vec3(radiance))), {});
    const std::uint64_t count = 1 << 16;
    const Crossing crossing = emit_all(emitter, count);
    const double area = 1.2;
    const double expected = radiance * area * kPi / 2.0;
    std::printf(
        "[ figures  ] uniform sky through a window, 65,536 portal photons: %.5f W into the "
        "room, L A pi / 2 = %.5f (%+.3f%%)\n",
        crossing.into_room.g, expected, 100.0 * (crossing.into_room.g / expected - 1.0));
    EXPECT_TRUE(crossing.finite);
    EXPECT_TRUE(crossing.all_from_portal);
    EXPECT_NEAR(crossing.into_room.g, expected, 0.01 * expected);
    // One-sample MIS with the |cos| strategy bounds every photon by 4 pi L A / N.
    EXPECT_LE(crossing.largest, 4.0 * kPi * radiance * area / static_cast<double>(count) * 1.001);
}

TEST(SkyPortal, ADaylightSkysPhotonsCarryItsOwnIntegralThroughTheWindow) {
    // A sky brightest by a low sun in front of the window: the flux into the room is A times
    // the integral of L cos over the directions on the sky's side, estimated here from the
    // sky's own samples (L cos+ / pdf, a million of them).
    const SkyRadiance sky = daylight_sky(glm::normalize(glm::vec3(0.3f, 0.4f, 1.0f)), 3.0f, 1.0f);
    glm::dvec3 integral(0.0);
    const std::uint64_t samples = 1 << 20;
    for (std::uint64_t i = 1; i <= samples; ++i) {
        const SkyRadiance::Sample s = sky.sample(halton2(i));
        if (s.pdf > 0.0 && s.direction.z > 0.0f) {
            integral += glm::dvec3(s.radiance) * (static_cast<double>(s.direction.z) / s.pdf);
        }
    }
    integral /= static_cast<double>(samples);
    const PhotonEmitter emitter(sky_through_window(sky), {});
    const Crossing crossing = emit_all(emitter, 1 << 16);
    const double area = 1.2;
    std::printf(
        "[ figures  ] daylight sky through a window: %.5f W (green) into the room, the "
        "sky's integral %.5f (%+.3f%%)\n",
        crossing.into_room.g, integral.g * area,
        100.0 * (crossing.into_room.g / (integral.g * area) - 1.0));
    EXPECT_TRUE(crossing.finite);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(crossing.into_room[c], integral[c] * area, 0.02 * integral[c] * area)
            << "channel " << c;
    }
}

TEST(SkyPortal, ASunsPhotonsCarryItsIrradianceThroughTheWindow) {
    // A sun of irradiance E shining in down 39 degrees: the flux through the opening is
    // E |cos| A, every photon starting on the window and travelling the sun's way.
    LightSource light;
    light.kind = LightKind::Directional;
    light.direction = glm::normalize(glm::vec3(0.0f, -0.8f, -1.0f));
    light.power = glm::vec3(3.0f);
    light.portals = window();
    const PhotonEmitter emitter(light, {});
    const Crossing crossing = emit_all(emitter, 1 << 12);
    const double expected = 3.0 * std::abs(static_cast<double>(light.direction.z)) * 1.2;
    EXPECT_TRUE(crossing.finite);
    EXPECT_TRUE(crossing.all_from_portal);
    EXPECT_NEAR(crossing.into_room.g, expected, 1e-4 * expected);
    EXPECT_NEAR(static_cast<double>(emitter.total_power().g), 3.0 * 1.2, 1e-5);
}

TEST(SkyPortal, APhotonWhoseWayBackToTheSkyIsBlockedCarriesNothing) {
    // One photon from the window into the room, traced twice: with nothing outside it lands
    // on the floor; with a wall standing outside the window it is dropped before it moves.
    EmittedPhoton photon;
    photon.origin = {0.0f, 1.5f, -1e-5f};
    photon.direction = glm::normalize(glm::vec3(0.0f, -1.0f, -1.0f));
    photon.power = glm::vec3(1.0f);
    photon.from_portal = true;
    const std::vector<TraceMaterial> materials(1);
    auto trace = [&](bool blocked) {
        RayScene scene;
        // The room's floor (light-mapped surface 0).
        scene.add_object(quad({-5.0f, 0.0f, -5.0f}, {10.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 5.0f}, 0),
                         glm::mat4(1.0f), false);
        if (blocked) {
            // A wall 1 m outside the window, as tall as the room.
            scene.add_object(quad({-5.0f, 0.0f, 1.0f}, {10.0f, 0.0f, 0.0f}, {0.0f, 5.0f, 0.0f}, -1),
                             glm::mat4(1.0f), false);
        }
        scene.commit();
        std::vector<TracedHop> hops;
        TraceCounters counters;
        trace_photon(scene, materials, photon, 1, 1, TraceLimits{}, hops, counters);
        return hops.size();
    };
    EXPECT_GE(trace(false), 1u);
    EXPECT_EQ(trace(true), 0u);
}

}  // namespace
