// What the camera sees gathers first (issue 19, docs/METHOD.md §6.10): after a change that
// reaches every surface (the Cornell box's light dims to half), the gather requests put every
// surface in the player's view before every surface out of it, each group in the order of its
// photons' change; without a view the order is the photons' change alone.

#include <algorithm>
#include <cstdint>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "luxel/lighting/components.hpp"
#include "stability_support.hpp"

namespace {

using namespace luxel;

lighting::AxisBox box(glm::vec3 min, glm::vec3 max) {
    lighting::AxisBox b;
    b.add(min);
    b.add(max);
    return b;
}

TEST(ViewFirst, TheFrustumTestKeepsWhatCanBeSeenAndDropsWhatCannot) {
    // At the origin looking down -z, 90 degrees, near 0.1, far 10.
    const glm::mat4 vp = glm::perspective(glm::radians(90.0f), 1.0f, 0.1f, 10.0f);
    EXPECT_TRUE(lighting::in_view(box({-0.5f, -0.5f, -3.0f}, {0.5f, 0.5f, -2.0f}), vp));
    EXPECT_FALSE(lighting::in_view(box({-0.5f, -0.5f, 2.0f}, {0.5f, 0.5f, 3.0f}), vp));   // behind
    EXPECT_FALSE(lighting::in_view(box({4.0f, -0.5f, -3.0f}, {5.0f, 0.5f, -2.0f}), vp));  // right
    EXPECT_FALSE(lighting::in_view(box({-0.5f, -0.5f, -30.0f}, {0.5f, 0.5f, -20.0f}), vp));
    // Around the eye (a room the player stands in): in view.
    EXPECT_TRUE(lighting::in_view(box({-5.0f, -5.0f, -5.0f}, {5.0f, 5.0f, 5.0f}), vp));
    // Crossing the eye's plane sideways, partly in front: in view.
    EXPECT_TRUE(lighting::in_view(box({-1.0f, -0.2f, -1.0f}, {1.0f, 0.2f, 1.0f}), vp));
    EXPECT_FALSE(lighting::in_view(lighting::AxisBox{}, vp));  // empty
}

TEST(ViewFirst, AChangeGathersTheSurfacesInViewFirst) {
    const ManualClock clock;
    luxel::testing::LitLevel level(luxel::testing::load_prepared("cornell"),
                                   luxel::testing::stability_config(77, 40), false, clock);
    ASSERT_LE(level.converge(600), 600) << level.pending();

    // The light dims; its photons are retraced (what the next update would do first), so every
    // surface's delta_i passes the threshold and asks for a full pass.
    level.registry.view<lighting::PointLight>().each(
        [&](ecs::Entity entity, const lighting::PointLight&) {
            level.registry.patch<lighting::PointLight>(
                entity, [](lighting::PointLight& light) { light.power *= 0.5f; });
        });
    level.lighting->photons().sync();
    level.lighting->photons().retrace_pending(level.jobs);
    const std::vector<lighting::MapRequest> anywhere = level.lighting->maps().gather_requests();
    ASSERT_GT(anywhere.size(), 4u);

    // A camera 0.4 m above the floor's middle looking straight down with a narrow lens: the
    // floor (and what stands on it there) is in view, the walls and the ceiling are not.
    const glm::mat4 view = glm::lookAt(glm::vec3(0.0f, 0.4f, 0.0f), glm::vec3(0.0f, 0.0f, 0.0f),
                                       glm::vec3(0.0f, 0.0f, -1.0f));
    const glm::mat4 projection = glm::perspective(0.6f, 1.0f, 0.05f, 10.0f);
    level.lighting->set_view(lighting::ViewHint{projection * view});
    const auto& maps = level.lighting->maps();
    const std::vector<lighting::MapRequest> looking = maps.gather_requests();
    ASSERT_EQ(looking.size(), anywhere.size());

    std::size_t seen = 0;
    std::size_t unseen_before_seen = 0;
    std::size_t unseen = 0;
    for (const lighting::MapRequest& request : looking) {
        const auto* name =
            level.registry.try_get<scene::Name>(maps.surfaces()[request.surface].entity);
        const bool in_view = lighting::in_view(
            lighting::transformed(
                [&] {
                    lighting::AxisBox box;
                    for (const auto& texel : maps.surfaces()[request.surface].texels.texels) {
                        box.add(texel.position);
                    }
                    return box;
                }(),
                maps.surfaces()[request.surface].to_world),
            projection * view);
        if (in_view) {
            ++seen;
            unseen_before_seen += unseen;
            unseen = 0;
            EXPECT_TRUE(name != nullptr && (name->value == "floor" || name->value == "moving cube"))
                << (name != nullptr ? name->value : "?") << " should not be in view";
        } else {
            ++unseen;
        }
    }
    EXPECT_GT(seen, 0u);
    EXPECT_GT(unseen, 0u);
    EXPECT_EQ(unseen_before_seen, 0u) << "a surface out of view went before one in view";

    // Without the view the order is the photons' change alone, which here does not put the
    // floor first.
    std::vector<std::uint32_t> order_anywhere;
    std::vector<std::uint32_t> order_looking;
    for (const auto& r : anywhere) {
        order_anywhere.push_back(r.surface);
    }
    for (const auto& r : looking) {
        order_looking.push_back(r.surface);
    }
    EXPECT_NE(order_anywhere, order_looking);
    level.lighting->set_view(std::nullopt);
    std::vector<std::uint32_t> order_again;
    for (const auto& r : maps.gather_requests()) {
        order_again.push_back(r.surface);
    }
    EXPECT_EQ(order_again, order_anywhere);
}

}  // namespace
