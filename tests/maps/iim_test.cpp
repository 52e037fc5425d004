// The IIM's double buffer: an update fades in over its texel's fade time, a texel updated mid-fade
// continues from what it showed, and only the touched rectangle is marked for upload.

#include <limits>

#include <gtest/gtest.h>

#include "luxel/lighting/core/iim_page.hpp"

namespace {

using namespace luxel::lighting;

TEST(IimPage, UpdatesFadeInOverTheirOwnFadeTime) {
    IimPage page(16);
    page.commit(3, 4, glm::vec3(2.0f), 10.0, 0.5);
    EXPECT_EQ(page.shown(3, 4, 10.0), glm::vec3(0.0f));
    EXPECT_NEAR(page.shown(3, 4, 10.25).x, 1.0f, 1e-5f);
    EXPECT_EQ(page.shown(3, 4, 10.5), glm::vec3(2.0f));
    EXPECT_EQ(page.shown(3, 4, 99.0), glm::vec3(2.0f));
    // Mid-fade update with a shorter fade (a texel re-gathered after a change): starts from
    // the 1.0 it showed and reaches 4 in 0.1 s, not 0.5 s.
    page.commit(3, 4, glm::vec3(4.0f), 10.25, 0.1);
    EXPECT_NEAR(page.shown(3, 4, 10.25).x, 1.0f, 1e-5f);
    EXPECT_NEAR(page.shown(3, 4, 10.30).x, 2.5f, 1e-4f);
    EXPECT_EQ(page.shown(3, 4, 10.35), glm::vec3(4.0f));
    // Committed again mid-way through that short fade with the long one (a photon-driven pass
    // a frame after a local pass): it still arrives when the short fade would have ended.
    page.commit(3, 4, glm::vec3(6.0f), 10.30, 0.5);
    EXPECT_NEAR(page.shown(3, 4, 10.30).x, 2.5f, 1e-4f);
    EXPECT_NEAR(page.shown(3, 4, 10.325).x, 4.25f, 1e-3f);
    // (Times are kept as float seconds, as the GPU reads them: equal to about 1e-6 s.)
    EXPECT_NEAR(page.shown(3, 4, 10.35).x, 6.0f, 1e-3f);
    // Once it has ended, the long fade is the long fade again.
    page.commit(3, 4, glm::vec3(8.0f), 11.0, 0.5);
    EXPECT_NEAR(page.shown(3, 4, 11.25).x, 7.0f, 1e-4f);
    // A neighbour keeps its own fade.
    page.commit(4, 4, glm::vec3(2.0f), 10.25, 0.5);
    EXPECT_NEAR(page.shown(4, 4, 10.35).x, 0.4f, 1e-4f);
    // Fade time 0, negative or not finite: at once.
    page.commit(5, 5, glm::vec3(7.0f), 11.0, 0.0);
    EXPECT_EQ(page.shown(5, 5, 11.0), glm::vec3(7.0f));
    page.commit(6, 5, glm::vec3(7.0f), 11.0, -1.0);
    EXPECT_EQ(page.shown(6, 5, 11.0), glm::vec3(7.0f));
    page.commit(7, 5, glm::vec3(7.0f), 11.0, std::numeric_limits<double>::quiet_NaN());
    EXPECT_EQ(page.shown(7, 5, 11.0), glm::vec3(7.0f));
}

TEST(RadiancePage, ChangedRectanglesGrowAndEachReaderSeesThemOnce) {
    RadiancePage page(32);
    EXPECT_FALSE(page.changes_since(page.version).any());
    const auto v0 = page.version;
    page.mark_changed({2, 3, 4, 5});
    const auto v1 = page.version;
    page.mark_changed({10, 1, 2, 2});
    EXPECT_GT(page.version, v0);
    const PageChanges changes = page.changes_since(v0);
    EXPECT_FALSE(changes.everything);
    EXPECT_EQ(changes.rect, (luxel::scene::TexelRect{2, 1, 10, 7}));
    // A reader that has read up to now sees nothing; one that read after the first change sees
    // only the second: readers keep their own positions and nothing is cleared.
    EXPECT_FALSE(page.changes_since(page.version).any());
    EXPECT_EQ(page.changes_since(v1).rect, (luxel::scene::TexelRect{10, 1, 2, 2}));
    EXPECT_EQ(page.changes_since(v0).rect, changes.rect);
    const auto v2 = page.version;
    page.mark_changed({0, 0, 0, 5});  // empty: nothing
    EXPECT_EQ(page.version, v2);
    EXPECT_FALSE(page.changes_since(v2).any());
}

TEST(RadiancePage, AReaderOlderThanTheLogReadsEverything) {
    RadiancePage page(16);
    const auto v0 = page.version;
    for (std::size_t i = 0; i <= RadiancePage::kLogLength; ++i) {
        page.mark_changed({1, 1, 1, 1});
    }
    EXPECT_LE(page.log.size(), RadiancePage::kLogLength);
    EXPECT_TRUE(page.changes_since(v0).everything);
    EXPECT_FALSE(page.changes_since(v0 + 1).everything);
    EXPECT_EQ(page.changes_since(v0 + 1).rect, (luxel::scene::TexelRect{1, 1, 1, 1}));
    // A version set by hand, with no log entry for it, also reads as everything.
    RadiancePage set_by_hand(4);
    set_by_hand.version = 1;
    EXPECT_TRUE(set_by_hand.changes_since(0).everything);
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
