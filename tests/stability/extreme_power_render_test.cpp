// Frames at extreme light powers (issue 12): the prepared Cornell box rendered by the
// FrameRenderer with its light scaled by 1e6 and 1e-6, against x 1, same camera, after the
// lighting has converged. Every pixel of every term must be finite and non-negative, and the
// terms must scale linearly: photon paths, shadow maps and G-buffer do not depend on power,
// only the float rounding of the powers and radiances differs. Linearity is asserted off the
// glass sphere's pixels; on them, a disabled test documents what 16-bit probes do today.
//
// Headless GL 4.5 on EGL (llvmpipe without a GPU), as tests/render.

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "luxel/ecs/transform.hpp"
#include "luxel/renderer/frame_renderer.hpp"
#include "luxel/scene/gltf.hpp"
#include "render_scenes.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;

constexpr int kWidth = 96;
constexpr int kHeight = 72;

/// The four linear terms of a converged frame of a prepared level with its lights' power
/// (punctual lights' intensity, emissive materials' strength) multiplied by `scale`, seen from
/// the level's camera, and the albedo image (alpha 1 marks specular pixels).
struct Frames {
    Image frame;
    Image direct;
    Image indirect;
    Image specular;
    Image albedo;
};

Frames render_level(const std::string& level, float scale) {
    test::RenderWorld world;
    auto source = std::make_shared<scene::Scene>(scene::load_gltf(test::prepared_level(level)));
    for (auto& light : source->lights) {
        light.intensity *= scale;
    }
    for (auto& material : source->materials) {
        material.emissive_strength *= scale;
    }
    world::instantiate(world.registry, source);
    world.start();
    // Unlimited budget until converged: every map is complete, whatever the power.
    for (int i = 0; i < 50 && !world.lighting->plan().census().converged; ++i) {
        world.update(1e9);
    }
    EXPECT_TRUE(world.lighting->plan().census().converged) << level << " x " << scale;
    renderer::FrameSettings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    settings.cube_shadow_size = 128;
    settings.map_shadow_size = 256;
    settings.specular_cube_size = 32;
    // Linearity is the terms' and the composite's: the edge anti-aliasing decides per pixel by
    // comparisons that float rounding of a scaled frame can flip (METHOD 8.4), so it is off.
    settings.anti_aliasing = false;
    settings.specular_faces_per_frame = 6;
    renderer::FrameRenderer renderer(world.registry, *world.lighting, settings);
    const float aspect = static_cast<float>(kWidth) / static_cast<float>(kHeight);
    renderer::FrameCamera camera = renderer::FrameCamera::look_at(
        {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, {0.0f, 1.0f, 0.0f}, 0.9f, aspect);
    for (auto [entity, c] : world.registry.view<scene::CameraComponent>()) {
        const auto* placed = world.registry.try_get<ecs::WorldTransform>(entity);
        camera = renderer::FrameCamera::from_scene(
            c.camera, placed ? placed->matrix : glm::mat4(1.0f), aspect);
    }
    // Three frames, the last long after every IIM fade (0.5 s) and with every probe face drawn.
    for (int f = 1; f <= 3; ++f) {
        renderer.render(camera, world.time + 10.0 * f);
    }
    return {renderer.read(renderer::FrameImage::Frame), renderer.read(renderer::FrameImage::Direct),
            renderer.read(renderer::FrameImage::Indirect),
            renderer.read(renderer::FrameImage::Specular),
            renderer.read(renderer::FrameImage::Albedo)};
}

/// Counts values that are NaN, infinite or negative (rgb and alpha).
int bad_values(const Image& image) {
    int bad = 0;
    for (const float v : image.rgba) {
        bad += std::isfinite(v) && v >= 0.0f ? 0 : 1;
    }
    return bad;
}

struct Deviation {
    double worst = 0.0;     ///< largest |v / scale / base - 1| over rgb where base > 0
    int zero_mismatch = 0;  ///< base 0 where the scaled value is not, or a non-finite one
    int compared = 0;
};

/// How far `scaled` / scale is from `base`, pixel by pixel; `skip_specular` leaves out the
/// pixels the albedo image marks specular.
Deviation deviation(const Image& scaled, const Image& base, double scale, const Image& albedo,
                    bool skip_specular) {
    Deviation d;
    for (std::size_t i = 0; i < base.rgba.size() && i < scaled.rgba.size(); ++i) {
        if (i % 4 == 3 || (skip_specular && albedo.rgba[i - i % 4 + 3] > 0.5f)) {
            continue;
        }
        const double b = base.rgba[i];
        const double s = static_cast<double>(scaled.rgba[i]) / scale;
        if (b > 0.0 && std::isfinite(s)) {
            d.worst = std::max(d.worst, std::abs(s / b - 1.0));
            ++d.compared;
        } else if ((b > 0.0) != (s > 0.0) || !std::isfinite(s)) {
            ++d.zero_mismatch;
        }
    }
    return d;
}

class ExtremePowerFrames : public ::testing::Test {
  protected:
    void SetUp() override { context_ = test::make_render_context(); }
    void TearDown() override { context_.reset(); }
    std::unique_ptr<GlContext> context_;
};

// The tolerance, 1e-5 relative: every term is computed in 32-bit floats and stored in RGBA32F
// targets; the power enters each pixel through a handful of products (light power, falloff,
// albedo, IIM texel), each rounding by at most 2^-24 = 6e-8 relative, so the scaled frames
// differ from linear by a few 1e-7 (measured 3e-7). The G-buffer's RGBA16F attributes (albedo,
// normal, F0) do not depend on power and round the same way in both frames.
//
// Off specular pixels here, with each term on its own; SpecularAndEmissionScaleLinearly below
// holds the whole frame including the sphere. Finiteness is asserted for every pixel of every
// term.
TEST_F(ExtremePowerFrames, CornellTermsAreFiniteAndScaleLinearlyOffSpecularPixels) {
    const Frames base = render_level("cornell", 1.0f);
    ASSERT_EQ(bad_values(base.frame), 0);
    for (const float scale : {1e6f, 1e-6f}) {
        const Frames scaled = render_level("cornell", scale);
        ASSERT_EQ(scaled.frame.rgba.size(), base.frame.rgba.size());
        const struct {
            const char* name;
            const Image& scaled;
            const Image& base;
        } terms[] = {{"frame", scaled.frame, base.frame},
                     {"direct", scaled.direct, base.direct},
                     {"indirect", scaled.indirect, base.indirect},
                     {"specular", scaled.specular, base.specular}};
        for (const auto& term : terms) {
            const int bad = bad_values(term.scaled);
            const Deviation all =
                deviation(term.scaled, term.base, static_cast<double>(scale), base.albedo, false);
            const Deviation diffuse =
                deviation(term.scaled, term.base, static_cast<double>(scale), base.albedo, true);
            std::printf(
                "[ figures  ] cornell x %g %s: %d non-finite or negative values; worst deviation "
                "from linear %.2e off specular pixels (%d values), %.2e on all (%d values)\n",
                static_cast<double>(scale), term.name, bad, diffuse.worst, diffuse.compared,
                all.worst, all.compared);
            EXPECT_EQ(bad, 0) << term.name << " x " << scale;
            EXPECT_LE(diffuse.worst, 1e-5) << term.name << " x " << scale;
            EXPECT_EQ(diffuse.zero_mismatch, 0) << term.name << " x " << scale;
            if (std::string(term.name) != "specular") {
                EXPECT_GT(diffuse.compared, kWidth * kHeight) << term.name << ": nothing lit";
            }
        }
    }
}

// The same requirement where half-float targets used to sit in the path: the specular term
// of the Cornell box's glass sphere (specular cube maps, renderer/src/specular_cube_maps.cpp) and
// the furnace's emission seen directly (the G-buffer's emission target,
// renderer/src/frame_targets.cpp). Both were RGBA16F, and this test found the sphere 0.91
// darker than linear at x 1e6 (radiance saturated at 65,504) and black at x 1e-6 (below
// half-float's smallest subnormal); both are RGBA32F now.
TEST_F(ExtremePowerFrames, SpecularAndEmissionScaleLinearly) {
    for (const std::string level : {"cornell", "furnace"}) {
        const Frames base = render_level(level, 1.0f);
        for (const float scale : {1e6f, 1e-6f}) {
            const Frames scaled = render_level(level, scale);
            const Deviation all =
                deviation(scaled.frame, base.frame, static_cast<double>(scale), base.albedo, false);
            std::printf(
                "[ figures  ] %s x %g frame: worst deviation from linear %.2e over %d values, %d "
                "non-finite or negative\n",
                level.c_str(), static_cast<double>(scale), all.worst, all.compared,
                bad_values(scaled.frame));
            EXPECT_EQ(bad_values(scaled.frame), 0) << level << " x " << scale;
            EXPECT_LE(all.worst, 1e-5) << level << " x " << scale;
            EXPECT_EQ(all.zero_mismatch, 0) << level << " x " << scale;
        }
    }
}

}  // namespace
