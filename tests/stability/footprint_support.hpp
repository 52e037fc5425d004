#pragma once

// Shared by the footprint tests (issue 19): a level converged with a box-shaped object resting
// on a light-mapped floor, and the floor texels it leaves or comes to cover when it moves.

#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "luxel/ecs/transform.hpp"
#include "luxel/scene/components.hpp"
#include "stability_support.hpp"

namespace luxel::testing {

/// How the lighting answers a move: luxel's defaults, or with parts off (the paper: neither
/// local passes nor exact invalidation).
struct Response {
    bool local_passes = true;
    bool exact_invalidation = true;
    double change_blend_seconds = lighting::IlluminationSettings{}.change_blend_seconds;
    double change_test_sigmas = lighting::IlluminationSettings{}.change_test_sigmas;
    double aim_threshold = lighting::IlluminationSettings{}.aim_threshold;
};
inline constexpr Response kLuxel{};
inline constexpr Response kPaper{false, false};

inline constexpr std::uint32_t kFootprintRefinePasses = 4;

inline lighting::LightingConfig footprint_config(const Response& response) {
    lighting::LightingConfig config = stability_config(77, 40);
    config.maps.refine_passes = kFootprintRefinePasses;
    config.maps.local_passes = response.local_passes;
    config.photons.selective.exact_invalidation = response.exact_invalidation;
    config.maps.change_blend_seconds = response.change_blend_seconds;
    config.maps.change_test_sigmas = response.change_test_sigmas;
    config.maps.aim_threshold = response.aim_threshold;
    return config;
}

/// Which level, which object rests on which floor.
struct FootprintSetup {
    std::string level;   ///< a prepared level's name (assets/levels/prepared/)
    std::string object;  ///< the node that moves: an axis-aligned box in its own space
    std::string floor;   ///< the light-mapped floor node it rests on
    float half = 0.25f;  ///< the object's half size, metres
    /// Floor texels this far inside a footprint's edge count (the texels right at an edge see
    /// the object's side and are neither lit nor dark).
    float inset = 0.06f;
};

/// A level on a clock that never advances (every unit free: each frame does all the work
/// queued), converged with the object where it rests, its animations stopped.
struct FootprintLevel {
    const ManualClock clock;
    FootprintSetup setup;
    LitLevel level;
    ecs::Entity object;
    std::vector<std::uint32_t> floor;  ///< the floor's light-mapped surfaces (luxel-prep's charts)
    glm::mat4 rest{1.0f};

    /// `before_converging` may move the object first (to converge the truth where it goes).
    template <typename Move>
    FootprintLevel(FootprintSetup setup_in, const Response& response, Move before_converging)
        : setup(std::move(setup_in)),
          level(load_prepared(setup.level), footprint_config(response), false, clock),
          object(level.instance.find(setup.object)) {
        rest = world_matrix();
        before_converging(*this);
        EXPECT_LE(level.converge(600), 600) << level.pending();
        const auto& maps = level.lighting->maps();
        for (std::uint32_t s = 0; s < maps.surfaces().size(); ++s) {
            const auto* name = level.registry.try_get<scene::Name>(maps.surfaces()[s].entity);
            if (name != nullptr && name->value == setup.floor &&
                !maps.surfaces()[s].texels.texels.empty()) {
                floor.push_back(s);
            }
        }
        EXPECT_FALSE(floor.empty())
            << setup.level << " has no light-mapped '" << setup.floor << "'";
    }
    FootprintLevel(FootprintSetup setup_in, const Response& response)
        : FootprintLevel(std::move(setup_in), response, [](FootprintLevel&) {}) {}

    [[nodiscard]] glm::mat4 world_matrix() const {
        return level.registry.get<ecs::WorldTransform>(object).matrix;
    }

    /// Whether a world point lies under the object placed by `world` (its footprint, inset).
    [[nodiscard]] bool under(const glm::mat4& world, const glm::vec3& point) const {
        const glm::vec3 local = glm::vec3(glm::inverse(world) * glm::vec4(point, 1.0f));
        const float edge = setup.half - setup.inset;
        return std::abs(local.x) < edge && std::abs(local.z) < edge && local.y < -0.6f * setup.half;
    }

    /// The floor texels (surface, index) under the object placed by `in` and not by `out`.
    [[nodiscard]] std::vector<std::pair<std::uint32_t, std::size_t>> floor_between(
        const glm::mat4& in, const glm::mat4& out) const {
        std::vector<std::pair<std::uint32_t, std::size_t>> found;
        for (const std::uint32_t s : floor) {
            const auto world = level.lighting->maps().world_texels(s);
            for (std::size_t i = 0; i < world.size(); ++i) {
                if (under(in, world[i].position) && !under(out, world[i].position)) {
                    found.emplace_back(s, i);
                }
            }
        }
        return found;
    }

    /// The mean committed IIM over floor texels.
    [[nodiscard]] double mean_iim(
        const std::vector<std::pair<std::uint32_t, std::size_t>>& texels) const {
        return mean_over(texels, [](const lighting::IimPage& page, int x, int y) {
            return page.current.at(x, y);
        });
    }

    /// The mean IIM a player sees now (the fade-in included) over floor texels.
    [[nodiscard]] double mean_shown(
        const std::vector<std::pair<std::uint32_t, std::size_t>>& texels) const {
        return mean_over(texels, [this](const lighting::IimPage& page, int x, int y) {
            return page.shown(x, y, level.time);
        });
    }

    /// The mean AIM (the radiance the gathers read off the floor) over floor texels.
    [[nodiscard]] double mean_aim(
        const std::vector<std::pair<std::uint32_t, std::size_t>>& texels) const {
        const auto& maps = level.lighting->maps();
        double sum = 0.0;
        for (const auto& [s, i] : texels) {
            const auto page = static_cast<std::size_t>(maps.aim().surface_page[s]);
            const auto& texel = maps.surfaces()[s].texels.texels[i];
            const glm::vec3 v = maps.aim().pages[page].at(texel.x, texel.y);
            sum += static_cast<double>(v.x + v.y + v.z) / 3.0;
        }
        return texels.empty() ? 0.0 : sum / static_cast<double>(texels.size());
    }

    template <typename Read>
    [[nodiscard]] double mean_over(const std::vector<std::pair<std::uint32_t, std::size_t>>& texels,
                                   Read read) const {
        const auto& maps = level.lighting->maps();
        double sum = 0.0;
        for (const auto& [s, i] : texels) {
            const auto page = static_cast<std::size_t>(maps.aim().surface_page[s]);
            const auto& texel = maps.surfaces()[s].texels.texels[i];
            const glm::vec3 v = read(maps.iim_pages()[page], texel.x, texel.y);
            sum += static_cast<double>(v.x + v.y + v.z) / 3.0;
        }
        return texels.empty() ? 0.0 : sum / static_cast<double>(texels.size());
    }
};

}  // namespace luxel::testing
