// The photon map's storage (docs/METHOD.md §4.3): half-float powers that keep each channel,
// path fingerprints that see every move past the tolerance, groups replaced together or one by
// one alike, and running energy sums that do not drift.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/packing.hpp>

#include "luxel/lighting/core/halton.hpp"
#include "luxel/lighting/core/photon_map.hpp"
#include "luxel/lighting/core/surface_deltas.hpp"
#include "luxel/runtime/error.hpp"

namespace {

using namespace luxel;
using namespace luxel::lighting;

/// A group of `photons` photons of `hops_each` hops, quasi-random positions in a 4 m box, every
/// third hop unstored (surface -1, object 7), powers from `power(i)`.
template <class Power>
TracedGroup make_group(std::uint32_t photons, std::uint32_t hops_each, std::uint32_t surfaces,
                       std::uint64_t first, Power power) {
    TracedGroup traced;
    traced.starts.push_back(0);
    std::uint64_t i = first;
    for (std::uint32_t p = 0; p < photons; ++p) {
        for (std::uint32_t h = 0; h < hops_each; ++h, ++i) {
            const glm::vec3 position(4.0 * radical_inverse(2, i), 4.0 * radical_inverse(3, i),
                                     4.0 * radical_inverse(5, i));
            const bool stored = i % 3 != 0;
            traced.hops.push_back({position, power(i),
                                   stored ? static_cast<std::int32_t>(i % surfaces) : -1,
                                   stored ? kNoObject : ObjectId{7}, h});
        }
        traced.starts.push_back(static_cast<std::uint32_t>(traced.hops.size()));
    }
    return traced;
}

std::span<const TracedHop> photon_hops(const TracedGroup& traced, std::uint32_t photon) {
    return {traced.hops.data() + traced.starts[photon],
            traced.starts[photon + 1] - traced.starts[photon]};
}

TEST(PhotonMapStorage, HalfFloatPowersKeepEveryChannelToItsOwnValue) {
    // Three groups of very different brightness (a 10 mW bulb's photons, a lamp's, the sun's),
    // channels spread over four orders of magnitude within each.
    for (const double watts : {1e-6, 0.05, 3e4}) {
        PhotonMap map(3, 1);
        const TracedGroup traced = make_group(40, 4, 3, 11, [&](std::uint64_t i) {
            return glm::vec3(glm::dvec3(1.0, std::pow(10.0, -4.0 * radical_inverse(7, i)),
                                        0.5 * radical_inverse(11, i)) *
                             watts);
        });
        map.replace_group(0, traced);
        double worst = 0.0;
        double traced_energy = 0.0;
        double stored_energy = 0.0;
        std::size_t compared = 0;
        for (std::uint32_t s = 0; s < 3; ++s) {
            stored_energy += map.surface(s).stored_energy.value();
            for (std::size_t i = 0; i < map.surface(s).hit_count(); ++i) {
                const StoredHit hit = map.hit(s, i);
                // Find the hop this hit came from by its position (all distinct).
                const auto hop =
                    std::find_if(traced.hops.begin(), traced.hops.end(),
                                 [&](const TracedHop& h) { return h.position == hit.position; });
                ASSERT_NE(hop, traced.hops.end());
                const glm::vec3 decoded = hit.power;
                for (int c = 0; c < 3; ++c) {
                    if (hop->power[c] >= 1e-4f * static_cast<float>(watts)) {
                        worst = std::max(worst, std::abs(static_cast<double>(decoded[c]) /
                                                             static_cast<double>(hop->power[c]) -
                                                         1.0));
                        ++compared;
                    }
                }
            }
        }
        for (const TracedHop& hop : traced.hops) {
            if (hop.surface >= 0) {
                traced_energy += static_cast<double>(hop.power.r) + hop.power.g + hop.power.b;
            }
        }
        std::printf(
            "[ figures  ] %.0e W photons: worst channel %.2e of its value over %zu "
            "channels, energy %.2e off\n",
            watts, worst, compared, stored_energy / traced_energy - 1.0);
        EXPECT_GT(compared, 200u);
        EXPECT_LE(worst, 1.0 / 2048.0);  // half a unit in the last place of 10 bits
        EXPECT_NEAR(stored_energy, traced_energy, 1e-4 * traced_energy);
        EXPECT_NEAR(stored_energy,
                    map.recount_energy(0) + map.recount_energy(1) + map.recount_energy(2),
                    1e-12 * traced_energy);
    }
}

TEST(PhotonMapStorage, HalfFloatsRoundToNearestEvenForEveryHalfUpToOne) {
    // Every half h in [0, 1) stored as itself (red), a quarter of the way to the next one
    // (blue: glm's conversion is the answer) and at the midpoint (green: a tie goes to the even
    // half, where glm rounds away from zero, which would bias a sum of such powers upwards),
    // with a first hop of power 1 setting the scale.
    PhotonMap map(1, 1);
    TracedGroup traced;
    traced.starts.push_back(0);
    traced.hops.push_back({glm::vec3(-1.0f), glm::vec3(1.0f), 0, kNoObject, 0});
    for (std::uint16_t h = 0; h < 0x3C00; ++h) {
        const float value = glm::unpackHalf1x16(h);
        const float next = glm::unpackHalf1x16(static_cast<std::uint16_t>(h + 1));
        traced.hops.push_back(
            {glm::vec3(float(h)),
             glm::vec3(value, 0.5f * (value + next), value + 0.25f * (next - value)), 0, kNoObject,
             0});
    }
    traced.starts.push_back(static_cast<std::uint32_t>(traced.hops.size()));
    map.replace_group(0, traced);
    ASSERT_EQ(map.surface(0).hit_count(), traced.hops.size());
    std::size_t mismatched = 0;
    for (std::size_t i = 0; i < map.surface(0).hit_count(); ++i) {
        const StoredHit hit = map.hit(0, i);
        if (hit.position.x < 0.0f) {
            EXPECT_EQ(hit.power, glm::vec3(1.0f));
            continue;
        }
        const auto h = static_cast<std::uint16_t>(hit.position.x);
        const float even = glm::unpackHalf1x16(static_cast<std::uint16_t>(h + (h & 1u)));
        const float quarter = traced.hops[h + 1u].power.b;
        mismatched += hit.power.r == glm::unpackHalf1x16(h) ? 0 : 1;
        mismatched += hit.power.g == even ? 0 : 1;
        mismatched += hit.power.b == glm::unpackHalf1x16(glm::packHalf1x16(quarter)) ? 0 : 1;
    }
    EXPECT_EQ(mismatched, 0u) << "of " << 3 * 0x3C00 << " channels";
}

TEST(PhotonMapStorage, AHopMovedFartherThanTheToleranceAlwaysDiverges) {
    const DivergenceTolerance tolerance{1e-3f};
    PhotonMap map(4, 1, tolerance);
    const TracedGroup traced =
        make_group(64, 5, 4, 3, [](std::uint64_t) { return glm::vec3(1.0f); });
    map.replace_group(0, traced);
    std::uint32_t small_moves_seen = 0;
    std::uint32_t trials = 0;
    for (std::uint32_t p = 0; p < 64; ++p) {
        const auto hops = photon_hops(traced, p);
        EXPECT_FALSE(map.diverges(0, p, hops)) << "photon " << p << " as stored";
        for (std::size_t h = 0; h < hops.size(); ++h) {
            if (hops[h].surface < 0) {
                std::vector<TracedHop> other(hops.begin(), hops.end());
                other[h].object = 8;
                EXPECT_TRUE(map.diverges(0, p, other)) << "another object at an unstored hop";
                continue;
            }
            for (std::uint64_t k = 0; k < 8; ++k, ++trials) {
                // A direction spread over the sphere.
                const double z = 2.0 * radical_inverse(2, trials + 1) - 1.0;
                const double phi = 6.283185307179586 * radical_inverse(3, trials + 1);
                const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
                const glm::vec3 direction(r * std::cos(phi), r * std::sin(phi), z);
                std::vector<TracedHop> moved(hops.begin(), hops.end());
                moved[h].position += direction * (1.001f * tolerance.distance);
                EXPECT_TRUE(map.diverges(0, p, moved)) << "photon " << p << " hop " << h;
                moved[h].position = hops[h].position + direction * (0.1f * tolerance.distance);
                small_moves_seen += map.diverges(0, p, moved) ? 1 : 0;
            }
            std::vector<TracedHop> elsewhere(hops.begin(), hops.end());
            elsewhere[h].surface = (elsewhere[h].surface + 1) % 4;
            EXPECT_TRUE(map.diverges(0, p, elsewhere)) << "another surface";
        }
        std::vector<TracedHop> longer(hops.begin(), hops.end());
        longer.push_back(longer.back());
        EXPECT_TRUE(map.diverges(0, p, longer)) << "one more hop";
        EXPECT_TRUE(map.diverges(0, p, hops.first(hops.size() - 1))) << "one hop fewer";
    }
    // A move of a tenth of the tolerance crosses a cell's face along some axis with
    // probability about sqrt(3) / 10 times the direction's summed |components| (~1.5): a
    // retrace that was not needed, about a quarter of the time.
    const double seen = static_cast<double>(small_moves_seen) / static_cast<double>(trials);
    std::printf("[ figures  ] %u moves of 1.001 tolerance: all diverge; of 0.1 tolerance: %.1f%%\n",
                trials, 100.0 * seen);
    EXPECT_GT(trials, 1000u);
    EXPECT_LT(seen, 0.4);
    EXPECT_TRUE(map.diverges(0, 64, photon_hops(traced, 0))) << "a photon never traced";
}

TEST(PhotonMapStorage, GroupsReplacedTogetherHoldWhatReplacingThemOneByOneHolds) {
    auto group = [](std::uint32_t g, std::uint32_t round) {
        return make_group(20 + g, 3, 5, 1000 * round + 97 * g,
                          [&](std::uint64_t i) { return glm::vec3(0.01f * float(1 + i % 13)); });
    };
    PhotonMap together(5, 6);
    PhotonMap one_by_one(5, 6);
    std::vector<std::uint32_t> groups(6);
    std::vector<TracedGroup> traced(6);
    for (std::uint32_t round = 0; round < 3; ++round) {
        // Round 0 stores all six; later rounds replace groups 1, 3 and 4.
        groups.clear();
        traced.clear();
        for (std::uint32_t g = 0; g < 6; ++g) {
            if (round == 0 || g == 1 || g == 3 || g == 4) {
                groups.push_back(g);
                traced.push_back(group(g, round));
            }
        }
        together.replace_groups(groups, traced);
        for (std::size_t i = 0; i < groups.size(); ++i) {
            one_by_one.replace_group(groups[i], traced[i]);
        }
    }
    auto contents = [](const PhotonMap& map, std::uint32_t s) {
        std::vector<std::tuple<std::uint32_t, float, float, float, float>> hits;
        for (std::size_t i = 0; i < map.surface(s).hit_count(); ++i) {
            const StoredHit hit = map.hit(s, i);
            hits.emplace_back(hit.group, hit.position.x, hit.position.y, hit.position.z,
                              hit.power.r);
        }
        std::sort(hits.begin(), hits.end());
        return hits;
    };
    ASSERT_EQ(together.stored_hit_count(), one_by_one.stored_hit_count());
    for (std::uint32_t s = 0; s < 5; ++s) {
        EXPECT_EQ(contents(together, s), contents(one_by_one, s)) << "surface " << s;
        EXPECT_NEAR(together.surface(s).changed_full.value(),
                    one_by_one.surface(s).changed_full.value(),
                    1e-12 * one_by_one.surface(s).changed_full.value());
    }
    const std::uint32_t twice[] = {2, 2};
    const TracedGroup pair[] = {group(2, 5), group(2, 6)};
    EXPECT_THROW(together.replace_groups(twice, pair), Error);
    const std::uint32_t missing[] = {6};
    EXPECT_THROW(together.clear_groups(missing), Error);
    // A path that claims more hops than were traced is refused before anything changes.
    TracedGroup broken = group(1, 7);
    broken.starts.back() += 1;
    const std::size_t held = together.stored_hit_count();
    EXPECT_THROW(together.replace_group(1, broken), Error);
    EXPECT_EQ(together.stored_hit_count(), held);
    EXPECT_THROW(PhotonMap(1, 1, DivergenceTolerance{0.0f}), Error);
}

TEST(PhotonMapStorage, AMillionAddRemoveCyclesDoNotDrift) {
    // Powers spanning twelve orders of magnitude, stored and removed group by group.
    PhotonMap map(4, 64);
    std::uint64_t cycles = 0;
    for (int round = 0; round < 400; ++round) {
        for (std::uint32_t g = 0; g < 64; ++g) {
            TracedGroup traced;
            traced.starts.push_back(0);
            for (int k = 0; k < 40; ++k) {
                const double scale = std::pow(10.0, -6.0 + 12.0 * radical_inverse(3, cycles + 1));
                const auto power = static_cast<float>(scale * (1.0 + radical_inverse(5, cycles)));
                traced.hops.push_back({glm::vec3(float(k)), glm::vec3(power, 0.5f * power, 0.0f),
                                       static_cast<std::int32_t>((g + k) % 4), kNoObject,
                                       static_cast<std::uint32_t>(k % 3)});
                traced.starts.push_back(static_cast<std::uint32_t>(traced.hops.size()));
                ++cycles;
            }
            map.replace_group(g, traced);
        }
    }
    EXPECT_GE(cycles, 1'000'000u);
    for (std::uint32_t s = 0; s < 4; ++s) {
        const double running = map.surface(s).stored_energy.value();
        const double recount = map.recount_energy(s);
        EXPECT_NEAR(running, recount, 1e-9 * std::abs(recount)) << "surface " << s;
        for (std::size_t i = 0; i < map.surface(s).hit_count(); ++i) {
            ASSERT_LT(map.hit(s, i).group, 64u);
        }
    }
    for (std::uint32_t g = 0; g < 64; ++g) {
        map.clear_group(g);
    }
    EXPECT_EQ(map.stored_hit_count(), 0u);
    for (std::uint32_t s = 0; s < 4; ++s) {
        EXPECT_NEAR(map.surface(s).stored_energy.value(), 0.0, 1e-9);
    }
}

TEST(PhotonMapStorage, DeltasCountStoredAndRemovedEnergyAndReset) {
    PhotonMap map(1, 1);
    TracedGroup traced;
    traced.starts = {0, 2};
    traced.hops = {{glm::vec3(0.0f), glm::vec3(1.0f), 0, kNoObject, 0},
                   {glm::vec3(1.0f), glm::vec3(0.5f), 0, kNoObject, 1}};
    map.replace_group(0, traced);
    SurfaceDeltas deltas;
    EXPECT_DOUBLE_EQ(deltas.full(map, 0), 4.5);
    EXPECT_DOUBLE_EQ(deltas.indirect(map, 0), 1.5);
    deltas.consume_full(map, 0);
    EXPECT_DOUBLE_EQ(deltas.full(map, 0), 0.0);
    EXPECT_DOUBLE_EQ(deltas.indirect(map, 0), 1.5);
    map.replace_group(0, traced);  // removes 4.5 and stores 4.5
    EXPECT_DOUBLE_EQ(deltas.full(map, 0), 9.0);
    EXPECT_DOUBLE_EQ(deltas.indirect(map, 0), 4.5);
    // A second reader keeps its own position: what the first consumed is still new to it.
    SurfaceDeltas other;
    EXPECT_DOUBLE_EQ(other.full(map, 0), 13.5);
    other.consume_indirect(map, 0);
    EXPECT_DOUBLE_EQ(other.indirect(map, 0), 0.0);
    EXPECT_DOUBLE_EQ(deltas.indirect(map, 0), 4.5);
    // A hit's share of its surface's arrays (position, half-float power, owner).
    EXPECT_EQ(sizeof(glm::vec3) + sizeof(HalfPower) + sizeof(std::uint32_t), 22u);
}

}  // namespace
