// Light maps in the frame: a surface whose IIM holds a known constant renders that radiance
// (or albedo * E / pi where the IIM holds irradiance), the front/back blend mixes previous and
// current as the clock says, a changed rectangle uploads only its texels, and the bicubic
// option keeps gradients and smooths the texel grid.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

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
            settings.bicubic_light_maps = bicubic_;
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

    /// Plane A's pixels in the screen row whose texel row (v * page) is nearest `texel_row`, in
    /// screen order, as (texel x, radiance). The camera looks straight down, so a screen row
    /// keeps one v and runs along u.
    std::vector<std::pair<float, glm::vec3>> row_of_a(double now, float texel_row) {
        renderer().render(renderer::FrameCamera::look_at({0.0f, 4.0f, 0.0f}, glm::vec3(0.0f),
                                                         {0.0f, 0.0f, -1.0f}, 1.0f, 1.0f),
                          now);
        const Image indirect = renderer().read(renderer::FrameImage::Indirect);
        const auto positions = test::read_texture(renderer().position_texture(), kSize, kSize);
        int best_row = -1;
        float best = 1e9f;
        std::vector<std::vector<std::pair<float, glm::vec3>>> rows(kSize);
        for (int y = 0; y < kSize; ++y) {
            for (int x = 0; x < kSize; ++x) {
                const glm::vec4 p =
                    positions[static_cast<std::size_t>((kSize - 1 - y) * kSize + x)];
                if (p.w == 0.0f || p.x > 0.0f) {
                    continue;
                }
                const glm::vec3 local = glm::vec3(p) - kCentreA;
                const glm::vec2 t = glm::vec2(local.x + 1.0f, local.z + 1.0f) * (kPage / 2.0f);
                rows[static_cast<std::size_t>(y)].emplace_back(t.x,
                                                               glm::vec3(indirect.pixel(x, y)));
                if (std::abs(t.y - texel_row) < best) {
                    best = std::abs(t.y - texel_row);
                    best_row = y;
                }
            }
        }
        return best_row < 0 ? std::vector<std::pair<float, glm::vec3>>{}
                            : rows[static_cast<std::size_t>(best_row)];
    }

    bool bicubic_ = false;
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

TEST_F(Lightmaps, BicubicKeepsGradientsExactAndSmoothsTheTexelGridsCreases) {
    // FrameSettings::bicubic_light_maps against bilinear on plane A's radiance page, long
    // after the commit (no blend): first a gradient along u, which both filters reproduce
    // exactly away from the page's border, then one bright texel (4, 4) on a floor of 1, whose
    // bilinear image is a tent with a crease at every texel centre and whose B-spline image is
    // smooth, lower and never negative.
    const double late = kCommitted + 100.0;
    IimPage& page = page_of(a_);
    fill(page_of(b_), kCurrentB);
    auto ramp = [](float f) { return kCurrentA * (0.5f + 0.25f * f); };
    struct Profile {
        float peak = 0.0f;
        float lowest = 1e9f;
        float crease = 0.0f;  ///< largest second difference between neighbouring pixels
    };
    std::array<Profile, 2> profiles;
    for (const bool bicubic : {false, true}) {
        bicubic_ = bicubic;
        renderer_.reset();
        fill(page, kCurrentA);
        for (int y = 0; y < kPage; ++y) {
            for (int x = 0; x < kPage; ++x) {
                page.current.at(x, y) = ramp(static_cast<float>(x));
            }
        }
        int checked = 0;
        for (const auto& [t, l] : row_of_a(late, 3.5f)) {
            // f = t - 0.5: the B-spline's taps f - 1 .. f + 2 stay on the page for f in [1, 5].
            if (t > 1.6f && t < 5.4f) {
                expect_close(l, ramp(t - 0.5f), 0.01f, bicubic ? "bicubic ramp" : "bilinear ramp");
                ++checked;
            }
        }
        EXPECT_GT(checked, 15);

        fill(page, glm::vec3(1.0f));
        page.current.at(4, 4) = glm::vec3(20.0f);
        const std::vector<std::pair<float, glm::vec3>> row = row_of_a(late, 4.5f);
        ASSERT_GT(row.size(), 30u);
        Profile& profile = profiles[bicubic ? 1 : 0];
        for (std::size_t i = 0; i < row.size(); ++i) {
            profile.peak = std::max(profile.peak, row[i].second.g);
            profile.lowest = std::min(profile.lowest, row[i].second.g);
            if (i > 0 && i + 1 < row.size()) {
                const float second =
                    row[i - 1].second.g - 2.0f * row[i].second.g + row[i + 1].second.g;
                profile.crease = std::max(profile.crease, std::abs(second));
            }
        }
        std::printf("[ figures  ] %s: peak %.3f, lowest %.3f, largest second difference %.3f\n",
                    bicubic ? "bicubic" : "bilinear", profile.peak, profile.lowest, profile.crease);
    }
    const Profile& bilinear = profiles[0];
    const Profile& bicubic = profiles[1];
    EXPECT_GT(bilinear.peak, 15.0f);
    // The B-spline at a texel centre: 2/3 of it and 1/6 of each neighbour, 1 + 19 * 4/9 in
    // two dimensions.
    EXPECT_NEAR(bicubic.peak, 1.0f + 19.0f * 4.0f / 9.0f, 0.1f * 19.0f * 4.0f / 9.0f);
    EXPECT_GE(bicubic.lowest, 1.0f - 1e-3f);
    EXPECT_LT(bicubic.crease, 0.4f * bilinear.crease);
}

}  // namespace
