// Light maps in the frame: a surface whose IIM holds a known constant renders that radiance
// (or albedo * E / pi where the IIM holds irradiance), the front/back blend mixes previous and
// current as the clock says, and a changed rectangle uploads only its texels.

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>

#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>

#include "luxel/renderer/frame_renderer.hpp"
#include "render_scenes.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;

constexpr int kSize = 128;
constexpr int kPage = 8;
constexpr float kCommitted = 10.0f;
constexpr float kFadeSeconds = 0.5f;
const glm::vec3 kAlbedoA(0.5f, 0.6f, 0.7f);  // untextured: the IIM holds radiance
const glm::vec3 kAlbedoB(0.8f, 0.4f, 0.2f);  // textured: the IIM holds irradiance
const glm::vec3 kCentreA(-1.1f, 0.0f, 0.0f);
const glm::vec3 kCentreB(1.1f, 0.0f, 0.0f);
const glm::vec3 kCurrentA(0.2f, 0.4f, 0.8f);
const glm::vec3 kCurrentB(3.0f, 2.0f, 1.0f);
const glm::vec3 kPrevious(1.0f, 0.5f, 0.25f);

class Lightmaps : public ::testing::Test {
  protected:
    void SetUp() override {
        context_ = test::make_render_context();
        for (const bool textured : {false, true}) {
            const glm::vec3 centre = textured ? kCentreB : kCentreA;
            const ecs::Entity entity = world_.add_mesh(
                test::single_mesh_scene(test::horizontal_square(glm::vec3(0.0f), 1.0f),
                                        textured ? kAlbedoB : kAlbedoA, textured),
                centre);
            world_.registry.emplace<LightmappedSurface>(entity,
                                                        test::whole_page_layout(kPage, 4.0));
            (textured ? b_ : a_) = entity;
        }
        world_.start();
        world_.update();
    }
    void TearDown() override {
        renderer_.reset();
        context_.reset();
    }

    /// The IIM page of an entity's surface. The test plays the gatherer, so it writes the
    /// pages the LightingSystem owns (through a const_cast: it hands them out read-only).
    IimPage& page_of(ecs::Entity entity) {
        auto& maps = const_cast<IlluminationMaps&>(world_.lighting->maps());
        for (std::size_t s = 0; s < maps.surfaces().size(); ++s) {
            if (maps.surfaces()[s].entity == entity) {
                const std::int32_t page = maps.aim().surface_page[s];
                EXPECT_GE(page, 0);
                return maps.iim_pages()[static_cast<std::size_t>(page)];
            }
        }
        ADD_FAILURE() << "no surface for the entity";
        return maps.iim_pages()[0];
    }

    void fill(IimPage& page, const glm::vec3& current, float fade_seconds = kFadeSeconds) {
        std::fill(page.current.texels.begin(), page.current.texels.end(), current);
        std::fill(page.previous.texels.begin(), page.previous.texels.end(), kPrevious);
        std::fill(page.fades.begin(), page.fades.end(), IimFade{kCommitted, fade_seconds});
        page.current.mark_changed({0, 0, kPage, kPage});
    }

    renderer::FrameRenderer& renderer() {
        if (!renderer_) {
            renderer::FrameSettings settings;
            settings.width = kSize;
            settings.height = kSize;
            // Pixel values against the IIM, edges of the plane included: no edge filter.
            settings.anti_aliasing = false;
            renderer_ = std::make_unique<renderer::FrameRenderer>(world_.registry, *world_.lighting,
                                                                  settings);
        }
        return *renderer_;
    }

    /// Renders at `now` and calls check(pixel value, light-map uv, which plane) for each
    /// pixel of the two planes; returns how many pixels were checked.
    int render_and_check(
        double now, const std::function<void(const glm::vec3&, const glm::vec2&, bool)>& check) {
        const renderer::FrameCamera camera = renderer::FrameCamera::look_at(
            {0.0f, 4.0f, 0.0f}, glm::vec3(0.0f), {0.0f, 0.0f, -1.0f}, 1.0f, 1.0f);
        renderer().render(camera, now);
        const Image indirect = renderer().read(renderer::FrameImage::Indirect);
        const auto positions = test::read_texture(renderer().position_texture(), kSize, kSize);
        int checked = 0;
        for (int y = 0; y < kSize; ++y) {
            for (int x = 0; x < kSize; ++x) {
                const glm::vec4 p =
                    positions[static_cast<std::size_t>((kSize - 1 - y) * kSize + x)];
                if (p.w == 0.0f) {
                    continue;
                }
                const bool is_b = p.x > 0.0f;
                const glm::vec3 local = glm::vec3(p) - (is_b ? kCentreB : kCentreA);
                // horizontal_square's UVs: (0, 0) at (-1, -1), (1, 1) at (1, 1) in (x, z).
                const glm::vec2 uv((local.x + 1.0f) / 2.0f, (local.z + 1.0f) / 2.0f);
                check(glm::vec3(indirect.pixel(x, y)), uv, is_b);
                ++checked;
            }
        }
        return checked;
    }

    std::unique_ptr<GlContext> context_;
    test::RenderWorld world_;
    ecs::Entity a_;
    ecs::Entity b_;
    std::unique_ptr<renderer::FrameRenderer> renderer_;
};

void expect_close(const glm::vec3& got, const glm::vec3& expected, float tolerance,
                  const char* what) {
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(got[c], expected[c], tolerance * expected[c]) << what << " channel " << c;
    }
}

TEST_F(Lightmaps, ConstantIimRendersItsRadiance) {
    fill(page_of(a_), kCurrentA);
    fill(page_of(b_), kCurrentB);
    const double blend = kFadeSeconds;
    const glm::vec3 expected_b = kAlbedoB * kCurrentB / glm::pi<float>();
    int on_a = 0;
    int on_b = 0;
    const int checked = render_and_check(
        kCommitted + 2.0 * blend, [&](const glm::vec3& l, const glm::vec2&, bool is_b) {
            expect_close(l, is_b ? expected_b : kCurrentA, 0.01f,
                         is_b ? "irradiance page" : "radiance page");
            (is_b ? on_b : on_a) += 1;
        });
    EXPECT_GT(on_a, 1000);
    EXPECT_GT(on_b, 1000);
    EXPECT_EQ(checked, on_a + on_b);
    // The frame adds nothing else: no lights, no emission.
    const Image frame = renderer().read(renderer::FrameImage::Frame);
    const Image indirect = renderer().read(renderer::FrameImage::Indirect);
    for (std::size_t i = 0; i < frame.rgba.size(); i += 4) {
        EXPECT_FLOAT_EQ(frame.rgba[i], indirect.rgba[i]);
    }
}

TEST_F(Lightmaps, BlendMixesPreviousAndCurrentByTheClockOverEachTexelsOwnFade) {
    // Page B's texels fade four times faster than page A's (a local pass's texels after a
    // change against a refinement's): each follows its own fade.
    const float fade_a = kFadeSeconds;
    const float fade_b = 0.25f * kFadeSeconds;
    fill(page_of(a_), kCurrentA, fade_a);
    fill(page_of(b_), kCurrentB, fade_b);
    for (const float fraction : {0.0f, 0.1f, 0.25f, 0.5f, 0.9f, 1.0f}) {
        const double now = kCommitted + fraction * fade_a;
        const float fraction_b = std::min(fraction * fade_a / fade_b, 1.0f);
        const glm::vec3 a = glm::mix(kPrevious, kCurrentA, fraction);
        const glm::vec3 b =
            kAlbedoB * glm::mix(kPrevious, kCurrentB, fraction_b) / glm::pi<float>();
        render_and_check(now, [&](const glm::vec3& l, const glm::vec2&, bool is_b) {
            expect_close(l, is_b ? b : a, 0.01f, "blend");
        });
    }
    // Before the commit (a clock that went backwards): the previous value.
    render_and_check(kCommitted - 1.0, [&](const glm::vec3& l, const glm::vec2&, bool is_b) {
        expect_close(l, is_b ? kAlbedoB * kPrevious / glm::pi<float>() : kPrevious, 0.01f,
                     "before");
    });
}

TEST_F(Lightmaps, OnlyTheDirtyRectangleIsUploaded) {
    IimPage& page = page_of(a_);
    fill(page, kCurrentA);
    fill(page_of(b_), kCurrentB);
    const double late = kCommitted + 100.0;
    render_and_check(late, [](const glm::vec3&, const glm::vec2&, bool) {});
    const std::uint64_t uploads = renderer().counters().page_uploads;
    const std::uint64_t texels = renderer().counters().texels_uploaded;
    EXPECT_EQ(uploads, 2u);
    EXPECT_EQ(texels, 2u * kPage * kPage);

    // Unchanged pages upload nothing.
    render_and_check(late, [](const glm::vec3&, const glm::vec2&, bool) {});
    EXPECT_EQ(renderer().counters().page_uploads, uploads);

    // Texels 2..4 x 2..4 of page A change, as a gather would mark them.
    const glm::vec3 changed(5.0f, 6.0f, 7.0f);
    for (int y = 2; y <= 4; ++y) {
        for (int x = 2; x <= 4; ++x) {
            page.current.at(x, y) = changed;
        }
    }
    page.current.mark_changed({2, 2, 3, 3});
    int inside = 0;
    render_and_check(late, [&](const glm::vec3& l, const glm::vec2& uv, bool is_b) {
        const glm::vec2 t = uv * static_cast<float>(kPage);
        // Bilinear lookups between texel centres 2.5 .. 4.5 read only changed texels.
        if (!is_b && t.x > 2.6f && t.x < 4.4f && t.y > 2.6f && t.y < 4.4f) {
            expect_close(l, changed, 0.01f, "changed rectangle");
            ++inside;
        }
    });
    EXPECT_GT(inside, 20);
    EXPECT_EQ(renderer().counters().page_uploads, uploads + 1);
    EXPECT_EQ(renderer().counters().texels_uploaded, texels + 9u);
}

}  // namespace
