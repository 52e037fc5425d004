// Soft shadows from lights with a size (issue 26; docs/METHOD.md §8.8): a 10 cm spherical light
// (a level's extras.luxel.light_radius) over a square card 1 m above the floor casts a penumbra
// 20 cm wide. The frame's direct term over the penumbra, against the reference integrator's
// (which samples the sphere), must be within 10% relRMSE, for a point light (cube shadow map)
// and a spot light (perspective map); the same light drawn with hard shadows is not, so the
// test can tell the two apart. A light without a radius draws exactly as before, with no pass.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>

#include "cube_scene.hpp"
#include "luxel/lighting/reference/reference_frame.hpp"
#include "luxel/lighting/reference/reference_scene.hpp"
#include "luxel/renderer/frame_renderer.hpp"
#include "luxel/runtime/image.hpp"
#include "render_scenes.hpp"

namespace {

using namespace luxel;

constexpr int kSize = 128;
constexpr float kRadius = 0.1f;  // the light's sphere, m
const glm::vec3 kLight(0.0f, 2.0f, 0.0f);
const glm::vec3 kCardCentre(0.5f, 1.0f, 0.0f);
constexpr float kCardHalf = 0.25f;
// Looking down on the card's shadow (x 0.5..1.5, z -0.5..0.5 on the floor) from above its far
// side, so the card hides little of it.
const glm::vec3 kEye(1.1f, 4.0f, 0.8f);
const glm::vec3 kTarget(1.1f, 0.0f, 0.0f);
const float kFov = glm::radians(26.0f);
const glm::vec3 kAlbedo(0.6f);

enum class Kind { Point, Spot };
/// What casts the shadow: a card 1 m above the floor (a penumbra of one width all round), or a
/// box standing on it (from nothing at the contact to its widest at the shadow's far end).
enum class Occluder { Card, Box };

/// A box standing on the floor beside the light's foot, 0.8 m tall, with face normals.
scene::Primitive standing_box() {
    scene::Primitive p;
    luxel::testing::append_box(glm::vec3(0.4f, 0.0f, -0.25f), glm::vec3(0.9f, 0.8f, 0.25f),
                               p.positions, p.indices);
    p.normals.assign(p.positions.size(), glm::vec3(0.0f));
    for (std::size_t t = 0; t + 2 < p.indices.size(); t += 3) {
        const glm::vec3 a = p.positions[p.indices[t]];
        const glm::vec3 n = glm::normalize(
            glm::cross(p.positions[p.indices[t + 1]] - a, p.positions[p.indices[t + 2]] - a));
        for (std::size_t k = 0; k < 3; ++k) {
            p.normals[p.indices[t + k]] = n;  // four corners of their own per face
        }
    }
    return p;
}

/// The floor, the occluder and the light, as a level file would give them: the light's radius
/// in its node's flags (extras.luxel.light_radius), read by world::instantiate.
std::shared_ptr<scene::Scene> penumbra_scene(Kind kind, float radius,
                                             Occluder occluder = Occluder::Card) {
    auto s = std::make_shared<scene::Scene>();
    scene::Material grey;
    grey.name = "grey";
    grey.base_color = glm::vec4(kAlbedo, 1.0f);
    grey.metallic = 0.0f;
    s->materials.push_back(grey);
    scene::Primitive floor = test::horizontal_square(glm::vec3(0.0f), 2.5f);
    floor.material = 0;
    s->meshes.push_back({"floor", {std::move(floor)}});
    scene::Primitive blocker = occluder == Occluder::Card
                                   ? test::horizontal_square(kCardCentre, kCardHalf)
                                   : standing_box();
    blocker.material = 0;
    s->meshes.push_back({occluder == Occluder::Card ? "card" : "box", {std::move(blocker)}});
    // 100 W into every direction below: the point's intensity 100 / 4 pi, the spot's cone wide
    // enough (70 degrees, a perspective map) to light the whole shadow at full intensity.
    s->lights.push_back(kind == Kind::Point
                            ? scene::Light::point_from_power(glm::vec3(100.0f))
                            : scene::Light::spot_from_power(glm::vec3(100.0f), 1.1f, 1.15f));
    for (int mesh = 0; mesh < 2; ++mesh) {
        scene::Node node;
        node.name = s->meshes[static_cast<std::size_t>(mesh)].name;
        node.mesh = mesh;
        s->nodes.push_back(node);
        s->roots.push_back(mesh);
    }
    scene::Node lamp;
    lamp.name = "lamp";
    lamp.light = 0;
    lamp.translation = kLight;
    // Lights shine down their -z axis: turned a quarter about x, -z points down.
    lamp.rotation = glm::angleAxis(-glm::half_pi<float>(), glm::vec3(1.0f, 0.0f, 0.0f));
    lamp.flags.light_radius = radius;
    s->nodes.push_back(lamp);
    s->roots.push_back(2);
    return s;
}

struct Rendered {
    Image direct;
    std::vector<glm::vec4> positions;  ///< rows bottom first (GL order)
    renderer::FrameCounters counters;
    double soft_ms = 0.0;
};

renderer::FrameCamera frame_camera() {
    return renderer::FrameCamera::look_at(kEye, kTarget, {0.0f, 1.0f, 0.0f}, kFov, 1.0f);
}

Rendered render(test::RenderWorld& world, bool soft) {
    renderer::FrameSettings settings;
    settings.width = kSize;
    settings.height = kSize;
    settings.soft_shadows = soft;
    settings.wait_for_timings = true;
    // Edges mix neighbours; the comparison here is of the shadow alone.
    settings.anti_aliasing = false;
    renderer::FrameRenderer renderer(world.registry, *world.lighting, settings);
    const renderer::FrameTimings& timings = renderer.render(frame_camera(), world.time);
    Rendered out;
    out.soft_ms = timings[renderer::RenderPass::SoftShadows];
    out.counters = renderer.counters();
    out.direct = renderer.read(renderer::FrameImage::Direct);
    out.positions = test::read_texture(renderer.position_texture(), kSize, kSize);
    return out;
}

/// The floor point under pixel (x, y) (rows top first), or w = 0 where the floor is not seen
/// there or at a neighbour: the reference's pixels along the card's outline mix in the card's
/// brighter light (it samples the whole pixel, the frame its centre), which is not the shadow.
glm::vec4 floor_at(const Rendered& r, int x, int y) {
    const auto at = [&r](int px, int py) {
        return r.positions[static_cast<std::size_t>((kSize - 1 - py) * kSize + px)];
    };
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            const int px = std::clamp(x + dx, 0, kSize - 1);
            const int py = std::clamp(y + dy, 0, kSize - 1);
            const glm::vec4 q = at(px, py);
            if (q.w == 0.0f || std::abs(q.y) > 1e-3f) {
                return glm::vec4(0.0f);
            }
        }
    }
    return at(x, y);
}

/// The share of the sphere's disc seen from floor point p that the card leaves visible, by
/// 256 rays to points spread over the disc (square to the direction of its centre): the
/// penumbra from neither image.
double visible_share(const lighting::RayScene& rays, const glm::vec3& p) {
    const glm::vec3 from = p + glm::vec3(0.0f, 1e-3f, 0.0f);
    const glm::vec3 axis = glm::normalize(kLight - from);
    const glm::vec3 u = glm::normalize(glm::cross(axis, glm::vec3(0.0f, 0.0f, 1.0f)));
    const glm::vec3 v = glm::cross(axis, u);
    int seen = 0;
    constexpr int kRays = 256;
    for (int i = 0; i < kRays; ++i) {
        const float r = kRadius * std::sqrt((static_cast<float>(i) + 0.5f) / kRays);
        const float a = static_cast<float>(i) * 2.39996323f;
        const glm::vec3 target = kLight + r * (std::cos(a) * u + std::sin(a) * v);
        const glm::vec3 to = target - from;
        const float distance = glm::length(to);
        seen += rays.occluded(from, to / distance, distance) ? 0 : 1;
    }
    return static_cast<double>(seen) / kRays;
}

struct PenumbraError {
    double relrmse = 0.0;
    int pixels = 0;
};

/// relRMSE of `frame` against `reference` over `pixels` (x, y pairs), in 2 x 2 blocks' worth of
/// noise: each pixel against the reference's mean over it.
PenumbraError penumbra_error(const Image& frame, const Image& reference,
                             const std::vector<glm::ivec2>& pixels) {
    double error = 0.0;
    double norm = 0.0;
    for (const glm::ivec2& q : pixels) {
        const double got = frame.pixel(q.x, q.y).g;
        const double want = reference.pixel(q.x, q.y).g;
        error += (got - want) * (got - want);
        norm += want * want;
    }
    return {norm > 0.0 ? std::sqrt(error / norm) : 1.0, static_cast<int>(pixels.size())};
}

class SoftShadows : public ::testing::TestWithParam<std::tuple<Kind, Occluder>> {
  protected:
    void SetUp() override { context_ = test::make_render_context(); }
    void TearDown() override { context_.reset(); }
    std::unique_ptr<GlContext> context_;
};

TEST_P(SoftShadows, APenumbraMatchesTheReferencesSphericalLight) {
    const auto [kind, occluder] = GetParam();
    const std::string name = std::string(kind == Kind::Point ? "point" : "spot") +
                             (occluder == Occluder::Card ? "-card" : "-box");
    test::RenderWorld world;
    world::instantiate(world.registry, penumbra_scene(kind, kRadius, occluder));
    world.start();
    world.update(1.0, 0.0);  // the ray scene; the direct term needs no more
    const lighting::PointLight* point = nullptr;
    const lighting::SpotLight* spot = nullptr;
    for (auto [entity, light] : world.registry.view<lighting::PointLight>()) {
        point = &light;
    }
    for (auto [entity, light] : world.registry.view<lighting::SpotLight>()) {
        spot = &light;
    }
    ASSERT_NE(kind == Kind::Point ? static_cast<const void*>(point) : spot, nullptr);
    EXPECT_EQ(kind == Kind::Point ? point->radius : spot->radius, kRadius)
        << "the node's light_radius reaches the light component";

    const Rendered soft = render(world, true);
    const Rendered hard = render(world, false);
    EXPECT_EQ(soft.counters.soft_lights, 1u);
    EXPECT_EQ(hard.counters.soft_lights, 0u);
    EXPECT_GT(soft.soft_ms, 0.0) << "the pass is timed (the HUD's soft_shadows)";
    EXPECT_EQ(hard.soft_ms, 0.0);

    const lighting::reference::ReferenceScene reference_scene =
        lighting::reference::ReferenceScene::from_world(world.lighting->photons(),
                                                        world.lighting->maps());
    lighting::reference::ReferenceFrameSettings reference_settings;
    reference_settings.samples_per_pass = 256;
    reference_settings.paths.max_vertices = 1;  // direct light only
    const auto camera =
        lighting::reference::ReferenceCamera::look_at(kEye, kTarget, kFov, kSize, kSize);
    lighting::reference::ReferenceFrame reference(reference_scene, camera, reference_settings);
    // 1,024 samples a pixel; 256 under the sanitizers, where the four passes took most of the
    // test's 75-84 s: the reference's noise over the penumbra doubles to about 4% there (1.9%
    // measured at 1,024), within the 10% goal with the frame's 4-5.5%. The plain build judges
    // at full count.
#ifdef LUXEL_SANITIZE
    constexpr int kReferencePasses = 1;
#else
    constexpr int kReferencePasses = 4;
#endif
    for (int pass = 0; pass < kReferencePasses; ++pass) {
        reference.run_pass(world.jobs);
    }
    const Image reference_image = reference.image();
    if (const char* dump = std::getenv("LUXEL_RENDER_OUT")) {
        const std::string stem = std::string(dump) + "/soft-shadow-" + name;
        write_exr(stem + "-frame.exr", soft.direct);
        write_exr(stem + "-hard.exr", hard.direct);
        write_exr(stem + "-reference.exr", reference_image);
        // One picture at one exposure, twice the size: soft | hard | reference.
        constexpr int kScale = 2;
        constexpr int kGap = 4;
        Image picture(3 * kSize * kScale + 2 * kGap, kSize * kScale, glm::vec4(0, 0, 0, 1));
        const Image* panels[] = {&soft.direct, &hard.direct, &reference_image};
        for (int panel = 0; panel < 3; ++panel) {
            for (int y = 0; y < kSize * kScale; ++y) {
                for (int x = 0; x < kSize * kScale; ++x) {
                    picture.set_pixel(panel * (kSize * kScale + kGap) + x, y,
                                      panels[panel]->pixel(x / kScale, y / kScale));
                }
            }
        }
        write_png(stem + ".png", picture, ToneMapSettings{.exposure = 3.0f});
    }

    // The penumbra: floor pixels from which the card hides part of the sphere, not all of it.
    const lighting::RayScene& rays = world.lighting->photons().ray_scene();
    std::vector<glm::ivec2> penumbra;
    std::vector<glm::ivec2> lit;
    std::vector<glm::ivec2> umbra;
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
            const glm::vec4 p = floor_at(soft, x, y);
            if (p.w == 0.0f) {
                continue;
            }
            const double share = visible_share(rays, glm::vec3(p));
            (share >= 1.0 ? lit : share <= 0.0 ? umbra : penumbra).push_back({x, y});
        }
    }
    ASSERT_GT(penumbra.size(), 600u) << "a penumbra up to 20 cm wide around the shadow";
    ASSERT_GT(umbra.size(), 300u);

    const PenumbraError soft_error = penumbra_error(soft.direct, reference_image, penumbra);
    const PenumbraError hard_error = penumbra_error(hard.direct, reference_image, penumbra);
    const PenumbraError lit_error = penumbra_error(soft.direct, reference_image, lit);
    // The reference's own noise over the penumbra (its standard errors against its values).
    const Image standard_error = reference.standard_error_image();
    double noise_sum = 0.0;
    double value_sum = 0.0;
    for (const glm::ivec2& q : penumbra) {
        const double se = standard_error.pixel(q.x, q.y).g;
        const double value = reference_image.pixel(q.x, q.y).g;
        noise_sum += se * se;
        value_sum += value * value;
    }
    const double noise = value_sum > 0.0 ? std::sqrt(noise_sum / value_sum) : 1.0;
    std::printf(
        "[ figures  ] %s, r = %.2f m: penumbra (%d pixels) relRMSE soft %.2f%%, hard "
        "%.2f%%; lit floor %.2f%%; the reference's own noise there %.2f%%; the soft pass "
        "%.2f ms\n",
        name.c_str(), kRadius, soft_error.pixels, 100.0 * soft_error.relrmse,
        100.0 * hard_error.relrmse, 100.0 * lit_error.relrmse, 100.0 * noise, soft.soft_ms);
    // Issue 26's goal: the direct term within the penumbra at most 10% from the reference.
    EXPECT_LT(soft_error.relrmse, 0.10) << name;
    // Hard shadows cut the penumbra in two: twice the error at least, or the test could not
    // tell soft from hard.
    EXPECT_GT(hard_error.relrmse, 2.0 * soft_error.relrmse) << name;
    // Where the whole sphere is seen, the sphere delivers what the point did.
    EXPECT_LT(lit_error.relrmse, 0.02) << name;
    // The umbra stays dark. Under the card, black; at the box's foot the shadow map knows only
    // the box's top (the surface the light sees), whose distance sizes the penumbra there as
    // if the box's far edge were as far: a faint leak a few centimetres into the umbra along
    // the contact (docs/METHOD.md §8.8), bounded here at 2% of the lit floor's light.
    const auto mean_of = [](const Image& image, const std::vector<glm::ivec2>& pixels) {
        double sum = 0.0;
        for (const glm::ivec2& q : pixels) {
            sum += image.pixel(q.x, q.y).g;
        }
        return pixels.empty() ? 0.0 : sum / static_cast<double>(pixels.size());
    };
    std::printf("[ figures  ] umbra mean soft %.5f hard %.5f reference %.5f, lit %.5f\n",
                mean_of(soft.direct, umbra), mean_of(hard.direct, umbra),
                mean_of(reference_image, umbra), mean_of(soft.direct, lit));
    EXPECT_LT(mean_of(soft.direct, umbra),
              (occluder == Occluder::Card ? 0.001 : 0.02) * mean_of(soft.direct, lit))
        << name;
}

INSTANTIATE_TEST_SUITE_P(Lights, SoftShadows,
                         ::testing::Combine(::testing::Values(Kind::Point, Kind::Spot),
                                            ::testing::Values(Occluder::Card, Occluder::Box)),
                         [](const ::testing::TestParamInfo<std::tuple<Kind, Occluder>>& light) {
                             return std::string(std::get<0>(light.param) == Kind::Point ? "Point"
                                                                                        : "Spot") +
                                    (std::get<1>(light.param) == Occluder::Card ? "Card" : "Box");
                         });

// A light without a radius: the soft pass neither runs nor changes a pixel.
TEST(SoftShadowsOff, APointLightDrawsAsBeforeWithoutThePass) {
    const auto context = test::make_render_context();
    test::RenderWorld world;
    world::instantiate(world.registry, penumbra_scene(Kind::Point, 0.0f));
    world.start();
    world.update(1.0, 0.0);
    const Rendered with = render(world, true);
    const Rendered without = render(world, false);
    EXPECT_EQ(with.counters.soft_lights, 0u);
    EXPECT_EQ(with.soft_ms, 0.0);
    int differing = 0;
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
            differing += with.direct.pixel(x, y) != without.direct.pixel(x, y) ? 1 : 0;
        }
    }
    EXPECT_EQ(differing, 0);
}

}  // namespace
