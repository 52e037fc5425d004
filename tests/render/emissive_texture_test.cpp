// Emissive textures end to end, in a level Blender's glTF exporter wrote
// (tests/levels/blender/emissive-sign.py): a sign 1.2 m x 0.6 m whose 64x64 emissive texture is
// black but for a warm white rectangle and a red square, with emissive strength 4, the only
// light of a closed room. The frame shows the texture per pixel; the photons leave from the
// bright texels only and carry the texture's integral; the reference emits the same.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "luxel/lighting/reference/reference_scene.hpp"
#include "luxel/renderer/frame_renderer.hpp"
#include "luxel/scene/gltf.hpp"
#include "luxel/world/scene_instance.hpp"
#include "render_scenes.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;

constexpr double kStrength = 4.0;
constexpr int kTexels = 64;
// The sign in the level (glTF, metres): x in [-0.6, 0.6], y in [1.0, 1.6] at z = -1.48 facing
// +z; u runs along +x, v = 0 at its top edge.
constexpr double kSignZ = -1.48;

/// The exact IEC 61966-2-1 decoding of an 8-bit code (independent of the runtime's).
double srgb_to_linear_exact(int code) {
    const double x = code / 255.0;
    return x <= 0.04045 ? x / 12.92 : std::pow((x + 0.055) / 1.055, 2.4);
}

/// A bright patch of the texture: texels [x0, x1) x [y0, y1) (row 0 at v = 0) of one colour.
struct Patch {
    int x0, x1, y0, y1;
    std::array<int, 3> srgb;

    [[nodiscard]] glm::dvec3 linear() const {
        return {srgb_to_linear_exact(srgb[0]), srgb_to_linear_exact(srgb[1]),
                srgb_to_linear_exact(srgb[2])};
    }
    [[nodiscard]] double texels() const { return static_cast<double>((x1 - x0) * (y1 - y0)); }
    /// Inside the patch by at least `margin` texels.
    [[nodiscard]] bool holds(const glm::dvec2& uv, double margin) const {
        const glm::dvec2 t = uv * static_cast<double>(kTexels);
        return t.x >= x0 + margin && t.x <= x1 - margin && t.y >= y0 + margin && t.y <= y1 - margin;
    }
};
// What emissive-sign.py paints (its comment gives the same rectangles).
const std::array<Patch, 2> kPatches = {Patch{8, 24, 16, 48, {255, 230, 179}},
                                       Patch{40, 56, 24, 40, {255, 0, 0}}};

glm::dvec2 sign_uv(const glm::dvec3& p) {
    return {(p.x + 0.6) / 1.2, (1.6 - p.y) / 0.6};
}

/// The patch holding uv by `margin` texels, or -1; -2 when uv is within `margin` of a patch's
/// edge (neither clearly inside nor clearly outside).
int patch_at(const glm::dvec2& uv, double margin) {
    for (std::size_t i = 0; i < kPatches.size(); ++i) {
        if (kPatches[i].holds(uv, margin)) {
            return static_cast<int>(i);
        }
        if (kPatches[i].holds(uv, -margin)) {
            return -2;
        }
    }
    return -1;
}

/// The texture's integral over the sign: pi x strength x sum of patch colour x patch area.
glm::dvec3 expected_flux() {
    const double texel_area = (1.2 / kTexels) * (0.6 / kTexels);
    glm::dvec3 flux(0.0);
    for (const Patch& patch : kPatches) {
        flux += patch.linear() * patch.texels() * texel_area;
    }
    return flux * (glm::pi<double>() * kStrength);
}

std::shared_ptr<const scene::Scene> sign_level() {
    return std::make_shared<scene::Scene>(scene::load_gltf(test::prepared_level("emissive-sign")));
}

TEST(EmissiveTextures, BlendersExportKeepsTheTextureThroughPrep) {
    const auto level = sign_level();
    int textured = 0;
    for (const scene::Material& material : level->materials) {
        if (material.emissive_image >= 0) {
            ++textured;
            EXPECT_FLOAT_EQ(material.emissive_strength * material.emissive.r,
                            static_cast<float>(kStrength))
                << material.name;
            ASSERT_LT(static_cast<std::size_t>(material.emissive_image), level->images.size());
        }
    }
    EXPECT_EQ(textured, 1) << "the sign's material, and only it, has an emissive texture";
}

class EmissiveSign : public ::testing::Test {
  protected:
    void SetUp() override {
        context_ = test::make_render_context();
        world::instantiate(world_.registry, sign_level());
        world_.start();
        world_.update(1e9);
    }
    void TearDown() override { context_.reset(); }

    /// The sign's photon emitter (the level's only light).
    const PhotonEmitter& emitter() {
        const auto lights = world_.lighting->photons().active_lights();
        EXPECT_EQ(lights.size(), 1u);
        return lights.at(0)->emitter();
    }

    std::unique_ptr<GlContext> context_;
    test::RenderWorld world_;
};

TEST_F(EmissiveSign, PhotonsCarryTheTexturesIntegralFromItsBrightTexelsOnly) {
    const PhotonEmitter& light = emitter();
    const glm::dvec3 expected = expected_flux();
    const glm::dvec3 total(light.total_power());
    std::printf("[ figures  ] sign flux %.4f %.4f %.4f W (texture's integral %.4f %.4f %.4f W)\n",
                total.r, total.g, total.b, expected.r, expected.g, expected.b);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(total[c], expected[c], 0.01 * expected[c]) << "channel " << c;
    }

    constexpr int kPhotons = 20000;
    std::mt19937_64 random(7);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    glm::dvec3 sum(0.0);
    std::array<int, 2> in_patch = {0, 0};  // within 1.5 texels of the patch
    int outside = 0;                       // further from every patch
    for (int i = 0; i < kPhotons; ++i) {
        const EmittedPhoton photon =
            light.emit({unit(random), unit(random)}, {unit(random), unit(random)}, kPhotons);
        sum += glm::dvec3(photon.power);
        // A piece covers about one texel and may straddle a patch's edge: 1.5 texels of margin.
        const glm::dvec2 uv = sign_uv(glm::dvec3(photon.origin));
        bool near_patch = false;
        for (std::size_t p = 0; p < kPatches.size(); ++p) {
            if (kPatches[p].holds(uv, -1.5)) {
                ++in_patch[p];
                near_patch = true;
            }
        }
        outside += near_patch ? 0 : 1;
    }
    std::printf("[ figures  ] %d photons: %d from the white patch, %d from the red, %d elsewhere\n",
                kPhotons, in_patch[0], in_patch[1], outside);
    EXPECT_EQ(outside, 0) << "photons left from black texels";
    // By power: the red square holds 1024 of the texture's 5616 summed channel-texels.
    const double white = kPatches[0].texels() *
                         (kPatches[0].linear().r + kPatches[0].linear().g + kPatches[0].linear().b);
    const double red = kPatches[1].texels();
    const double red_share = red / (red + white);
    EXPECT_NEAR(static_cast<double>(in_patch[1]) / kPhotons, red_share, 0.02);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(sum[c], expected[c], 0.03 * expected[c]) << "photon power, channel " << c;
    }
}

TEST_F(EmissiveSign, TheFrameShowsTheTexturePerPixel) {
    renderer::FrameSettings settings;
    settings.width = 192;
    settings.height = 96;
    renderer::FrameRenderer renderer(world_.registry, *world_.lighting, settings);
    // Straight at the sign from 1 m, the sign filling most of the view.
    const renderer::FrameCamera camera = renderer::FrameCamera::look_at(
        {0.0f, 1.3f, -0.48f}, {0.0f, 1.3f, -1.48f}, {0.0f, 1.0f, 0.0f}, 0.7f, 2.0f);
    renderer.render(camera, world_.time);
    const Image frame = renderer.read(renderer::FrameImage::Frame);
    const auto positions =
        test::read_texture(renderer.position_texture(), settings.width, settings.height);
    std::array<int, 2> inside = {0, 0};
    int dark = 0;
    double worst_inside = 0.0;
    double worst_dark = 0.0;
    for (int y = 0; y < settings.height; ++y) {
        for (int x = 0; x < settings.width; ++x) {
            const glm::vec4 p =
                positions[static_cast<std::size_t>((settings.height - 1 - y) * settings.width + x)];
            if (p.w == 0.0f || std::abs(p.z - kSignZ) > 1e-3) {
                continue;  // not the sign
            }
            const glm::dvec2 uv = sign_uv(glm::dvec3(p));
            if (uv.x < 0.0 || uv.x > 1.0 || uv.y < 0.0 || uv.y > 1.0) {
                continue;
            }
            // The sign's base colour is black: its pixels show its emission alone.
            const glm::dvec3 shown(glm::vec3(frame.pixel(x, y)));
            const int patch = patch_at(uv, 1.0);
            if (patch >= 0) {
                const glm::dvec3 want =
                    kPatches[static_cast<std::size_t>(patch)].linear() * kStrength;
                for (int c = 0; c < 3; ++c) {
                    worst_inside = std::max(worst_inside, std::abs(shown[c] - want[c]) / kStrength);
                }
                ++inside[static_cast<std::size_t>(patch)];
            } else if (patch == -1) {
                worst_dark = std::max(worst_dark, std::max(shown.r, std::max(shown.g, shown.b)));
                ++dark;
            }
        }
    }
    std::printf(
        "[ figures  ] sign pixels: %d white, %d red, %d black; worst error inside %.4f "
        "(of the strength), brightest black pixel %.4g W/(m^2 sr)\n",
        inside[0], inside[1], dark, worst_inside, worst_dark);
    ASSERT_GT(inside[0], 200);
    ASSERT_GT(inside[1], 100);
    ASSERT_GT(dark, 1000);
    // Half-float targets and sRGB texture decoding: well within 2% of the strength.
    EXPECT_LT(worst_inside, 0.02);
    EXPECT_LT(worst_dark, 1e-3) << "a black texel emits: the factor lit the whole sign";
}

TEST_F(EmissiveSign, TheReferenceEmitsWhereTheTextureIsBright) {
    const reference::ReferenceScene scene =
        reference::ReferenceScene::from_world(world_.lighting->photons(), world_.lighting->maps());
    ASSERT_EQ(scene.lights().size(), 1u);
    const auto& light = scene.lights()[0];
    const auto& vertices = light.triangles.vertices();
    ASSERT_EQ(vertices.size() % 3, 0u);
    // Points on a grid over the sign, each found on the light's triangles.
    int checked = 0;
    for (int j = 0; j < 48; ++j) {
        for (int i = 0; i < 96; ++i) {
            const glm::dvec2 uv((i + 0.5) / 96.0, (j + 0.5) / 48.0);
            const int patch = patch_at(uv, 1.5);
            if (patch == -2) {
                continue;
            }
            const glm::vec3 point(static_cast<float>(uv.x * 1.2 - 0.6),
                                  static_cast<float>(1.6 - uv.y * 0.6), static_cast<float>(kSignZ));
            for (std::uint32_t t = 0; 3 * t + 2 < vertices.size(); ++t) {
                // On triangle t: same side of its three edges (it faces +z).
                const glm::vec3* v = &vertices[3 * t];
                bool in = true;
                for (int k = 0; k < 3; ++k) {
                    const glm::vec3 e = v[(k + 1) % 3] - v[k];
                    const glm::vec3 d = point - v[k];
                    in = in && (e.x * d.y - e.y * d.x) >= 0.0f;
                }
                if (!in) {
                    continue;
                }
                const auto emission = scene.emission_at({0, t}, point);
                const glm::dvec3 want =
                    patch >= 0 ? kPatches[static_cast<std::size_t>(patch)].linear() * kStrength
                               : glm::dvec3(0.0);
                for (int c = 0; c < 3; ++c) {
                    EXPECT_NEAR(emission.radiance[c], want[c], 1e-3 * kStrength)
                        << "at uv " << uv.x << ", " << uv.y << ", channel " << c;
                }
                EXPECT_EQ(emission.density > 0.0, patch >= 0);
                ++checked;
                break;
            }
        }
    }
    EXPECT_GT(checked, 3000);
}

}  // namespace
