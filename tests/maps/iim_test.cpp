// The IIM's double buffer: an update fades in over the blend time, a texel updated mid-fade
// continues from what it showed, and only the touched rectangle is marked for upload.

#include <gtest/gtest.h>

#include "luxel/lighting/core/iim_page.hpp"

namespace {

using namespace luxel::lighting;

TEST(IimPage, UpdatesFadeInOverTheBlendTime) {
    IimPage page(16);
    page.commit(3, 4, glm::vec3(2.0f), 10.0, 0.5);
    EXPECT_EQ(page.shown(3, 4, 10.0, 0.5), glm::vec3(0.0f));
    EXPECT_NEAR(page.shown(3, 4, 10.25, 0.5).x, 1.0f, 1e-5f);
    EXPECT_EQ(page.shown(3, 4, 10.5, 0.5), glm::vec3(2.0f));
    EXPECT_EQ(page.shown(3, 4, 99.0, 0.5), glm::vec3(2.0f));
    // Mid-fade update: starts from the 1.0 it showed, heads for 4.
    page.commit(3, 4, glm::vec3(4.0f), 10.25, 0.5);
    EXPECT_NEAR(page.shown(3, 4, 10.25, 0.5).x, 1.0f, 1e-5f);
    EXPECT_NEAR(page.shown(3, 4, 10.5, 0.5).x, 2.5f, 1e-5f);
    // Blend time 0: at once.
    page.commit(5, 5, glm::vec3(7.0f), 11.0, 0.0);
    EXPECT_EQ(page.shown(5, 5, 11.0, 0.0), glm::vec3(7.0f));
}

TEST(RadiancePage, DirtyRectanglesGrowAndAreTakenOnce) {
    RadiancePage page(32);
    EXPECT_EQ(page.take_dirty().width, 0);
    const auto v0 = page.version;
    page.mark_dirty({2, 3, 4, 5});
    page.mark_dirty({10, 1, 2, 2});
    EXPECT_GT(page.version, v0);
    const auto dirty = page.take_dirty();
    EXPECT_EQ(dirty, (luxel::scene::TexelRect{2, 1, 10, 7}));
    EXPECT_EQ(page.take_dirty().width, 0);
    page.mark_dirty({0, 0, 0, 5});  // empty: nothing
    EXPECT_EQ(page.take_dirty().width, 0);
}

TEST(RadiancePage, BilinearLookupBetweenTexelCentres) {
    RadiancePage page(4);
    page.at(1, 1) = glm::vec3(1.0f);
    page.at(2, 1) = glm::vec3(3.0f);
    // Halfway between the centres of (1, 1) and (2, 1): u = 2 / 4, v = 1.5 / 4.
    EXPECT_NEAR(page.sample({2.0f / 4.0f, 1.5f / 4.0f}).x, 2.0f, 1e-6f);
    EXPECT_NEAR(page.sample({1.5f / 4.0f, 1.5f / 4.0f}).x, 1.0f, 1e-6f);
    EXPECT_EQ(page.sample({NAN, 0.5f}), glm::vec3(0.0f));
    EXPECT_EQ(page.sample({-5.0f, 9.0f}), page.at(0, 3));  // clamped to the page
}

}  // namespace
