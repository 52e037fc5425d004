// Light-map seams (docs/METHOD.md §6.13): which edges find_seams calls seams, and the
// SeamStitcher making both sides' lookups agree without drifting or touching other texels;
// then cornell as luxel-prep prepared it, gathered for real, with and without stitching.

#include <cmath>
#include <filesystem>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "luxel/lighting/core/cpu_gather.hpp"
#include "luxel/lighting/core/light_map_seams.hpp"
#include "luxel/lighting/core/seam_stitcher.hpp"
#include "luxel/runtime/jobs.hpp"
#include "luxel/scene/gltf.hpp"
#include "luxel/world/scene_instance.hpp"
#include "map_test_scenes.hpp"

namespace {

using namespace luxel;
using lighting::IimContent;
using lighting::IimPage;
using lighting::SeamSurface;

constexpr int kPage = 64;

/// A 1 m square at y = 0 from x = x0 to x0 + 1 (z from 0 to 1) as two triangles, its chart
/// 20 x 20 texels at page texel (left, 2): x0 maps to `left`, x0 + 1 to left + 20.
scene::Primitive square(float x0, float left, glm::vec3 normal = {0.0f, 1.0f, 0.0f}) {
    scene::Primitive p;
    const auto corner = [&](float u, float v) {
        p.positions.emplace_back(x0 + u, 0.0f, v);
        p.normals.push_back(normal);
        p.texcoords1.emplace_back((left + 20.0f * u) / kPage, (2.0f + 20.0f * v) / kPage);
    };
    corner(0, 0);
    corner(1, 0);
    corner(1, 1);
    corner(0, 1);
    p.indices = {0, 3, 1, 1, 3, 2};
    return p;
}

/// Every texel left of column 26 holds `left`, the rest `right`: two gathers that disagree.
IimPage step_page(glm::vec3 left, glm::vec3 right) {
    IimPage page(kPage);
    for (int y = 0; y < kPage; ++y) {
        for (int x = 0; x < kPage; ++x) {
            page.current.at(x, y) = x < 26 ? left : right;
            page.previous.at(x, y) = page.current.at(x, y);
        }
    }
    return page;
}

std::vector<SeamSurface> two_sides(const scene::Primitive& a, const scene::Primitive& b) {
    return {{0, &a, 0, kPage, IimContent::Radiance, glm::vec3(0.5f)},
            {1, &b, 0, kPage, IimContent::Radiance, glm::vec3(0.5f)}};
}

TEST(LightMapSeams, TwoChartsOfAFlatFloorMeetAtASeam) {
    const scene::Primitive left = square(-1.0f, 2.0f);
    const scene::Primitive right = square(0.0f, 30.0f);
    const auto samples = lighting::find_seams(two_sides(left, right));
    // The shared edge x = 0 is 20 texels long on both sides: two samples per texel.
    ASSERT_EQ(samples.size(), 40u);
    for (const auto& s : samples) {
        // Side a or b is the left chart's right edge (x = 22), the other the right chart's left.
        const float xa = s.page_a == 0 ? s.point_a.x : -1.0f;
        const float xb = s.page_b == 0 ? s.point_b.x : -1.0f;
        EXPECT_TRUE((std::abs(xa - 22.0f) < 1e-4f && std::abs(xb - 30.0f) < 1e-4f) ||
                    (std::abs(xa - 30.0f) < 1e-4f && std::abs(xb - 22.0f) < 1e-4f));
        EXPECT_NEAR(s.point_a.y, s.point_b.y, 1e-4f);
    }
}

TEST(LightMapSeams, HardEdgesOtherQuantitiesAndBrokenInputAreNotSeams) {
    const scene::Primitive left = square(-1.0f, 2.0f);
    // The right square folded up 90 degrees about the shared edge: a box's corner.
    scene::Primitive folded = square(0.0f, 30.0f, {-1.0f, 0.0f, 0.0f});
    for (glm::vec3& p : folded.positions) {
        p = glm::vec3(0.0f, p.x, p.z);
    }
    EXPECT_TRUE(lighting::find_seams(two_sides(left, folded)).empty());

    // Radiance of two albedos differs across the edge however smooth it is; irradiance does
    // not.
    const scene::Primitive right = square(0.0f, 30.0f);
    auto sides = two_sides(left, right);
    sides[1].albedo = glm::vec3(0.8f);
    EXPECT_TRUE(lighting::find_seams(sides).empty());
    sides[0].content = IimContent::Irradiance;
    sides[1].content = IimContent::Irradiance;
    EXPECT_EQ(lighting::find_seams(sides).size(), 40u);

    // One chart over both squares (the same UVs at the shared corners) has no seam.
    scene::Primitive joined = square(0.0f, 22.0f);
    EXPECT_TRUE(lighting::find_seams(two_sides(left, joined)).size() == 40u)
        << "two surfaces still meet";
    auto same_surface = two_sides(left, joined);
    same_surface[1].surface = 0;
    EXPECT_TRUE(lighting::find_seams(same_surface).empty());

    // Hostile data: NaN UVs, indices past the vertices, no page: no seam, no crash.
    scene::Primitive broken = right;
    broken.texcoords1[0] = glm::vec2(std::numeric_limits<float>::quiet_NaN());
    EXPECT_LT(lighting::find_seams(two_sides(left, broken)).size(), 40u);
    broken = right;
    broken.indices = {0, 3, 99, 1, 3, 2};
    EXPECT_NO_THROW((void)lighting::find_seams(two_sides(left, broken)));
    auto no_page = two_sides(left, right);
    no_page[1].page = -1;
    EXPECT_TRUE(lighting::find_seams(no_page).empty());
}

TEST(SeamStitcher, BothSidesAgreeAndOnlyTheSeamsTexelsMove) {
    const scene::Primitive left = square(-1.0f, 2.0f);
    const scene::Primitive right = square(0.0f, 30.0f);
    auto samples = lighting::find_seams(two_sides(left, right));
    std::vector<IimPage> pages{step_page(glm::vec3(1.0f), glm::vec3(1.2f, 1.3f, 0.9f))};
    const double before = lighting::seam_mismatch(samples, pages);
    EXPECT_GT(before, 0.1);

    lighting::SeamStitcher stitcher;
    stitcher.add_object(samples, pages);
    EXPECT_GT(stitcher.texels(), 0u);
    stitcher.stitch(0, pages, 1.0, 0.0);
    EXPECT_EQ(stitcher.stitches(), 0u) << "the right side has no pass in yet";
    EXPECT_EQ(pages[0].current.at(21, 10), glm::vec3(1.0f));
    stitcher.stitch(1, pages, 1.0, 0.0);
    EXPECT_EQ(stitcher.stitches(), 1u);

    const double after = lighting::seam_mismatch(samples, pages);
    EXPECT_LT(after, 0.05 * before) << "before " << before;
    // The lookups meet between the two gathers, and texels two away from the seam's lookups
    // keep what was gathered.
    const glm::vec3 middle = pages[0].current.sample(glm::vec2(22.0f, 12.0f) / float(kPage));
    EXPECT_GT(middle.x, 1.05f);
    EXPECT_LT(middle.x, 1.15f);
    for (int y = 0; y < kPage; ++y) {
        EXPECT_EQ(pages[0].current.at(19, y), glm::vec3(1.0f));
        EXPECT_EQ(pages[0].current.at(33, y), glm::vec3(1.2f, 1.3f, 0.9f));
    }
    EXPECT_GT(pages[0].current.version, 0u) << "the renderer must see the stitched texels";
}

TEST(SeamStitcher, StitchingAgainStartsFromTheGathersNotFromItself) {
    const scene::Primitive left = square(-1.0f, 2.0f);
    const scene::Primitive right = square(0.0f, 30.0f);
    auto samples = lighting::find_seams(two_sides(left, right));
    std::vector<IimPage> pages{step_page(glm::vec3(1.0f), glm::vec3(2.0f))};
    lighting::SeamStitcher stitcher;
    stitcher.add_object(samples, pages);
    stitcher.stitch(0, pages, 0.0, 0.0);
    stitcher.stitch(1, pages, 0.0, 0.0);
    const std::vector<glm::vec3> once = pages[0].current.texels;
    for (int i = 0; i < 20; ++i) {
        stitcher.stitch(i % 2 == 0 ? 0u : 1u, pages, 0.0, 0.0);
    }
    EXPECT_EQ(pages[0].current.texels, once) << "repeated stitches drifted";

    // The left side gathered again (its texels committed anew, the right side's stitched
    // values left as they are): the result is what stitching both gathers gives.
    for (int y = 0; y < kPage; ++y) {
        for (int x = 0; x < 26; ++x) {
            pages[0].commit(x, y, glm::vec3(1.5f), 1.0, 0.0);
        }
    }
    stitcher.stitch(0, pages, 1.0, 0.0);
    std::vector<IimPage> fresh{step_page(glm::vec3(1.5f), glm::vec3(2.0f))};
    lighting::SeamStitcher reference;
    reference.add_object(samples, fresh);
    reference.stitch(0, fresh, 0.0, 0.0);
    reference.stitch(1, fresh, 0.0, 0.0);
    for (std::size_t i = 0; i < fresh[0].current.texels.size(); ++i) {
        ASSERT_NEAR(pages[0].current.texels[i].x, fresh[0].current.texels[i].x, 1e-5f) << i;
    }
}

TEST(SeamStitcher, NonFiniteTexelsNeverSpread) {
    const scene::Primitive left = square(-1.0f, 2.0f);
    const scene::Primitive right = square(0.0f, 30.0f);
    std::vector<IimPage> pages{step_page(glm::vec3(1.0f), glm::vec3(1.2f))};
    pages[0].current.at(21, 10) = glm::vec3(std::numeric_limits<float>::infinity());
    pages[0].current.at(30, 11) = glm::vec3(std::numeric_limits<float>::quiet_NaN());
    lighting::SeamStitcher stitcher;
    stitcher.add_object(lighting::find_seams(two_sides(left, right)), pages);
    stitcher.stitch(0, pages, 0.0, 0.0);
    stitcher.stitch(1, pages, 0.0, 0.0);
    for (const glm::vec3& v : pages[0].current.texels) {
        if (v == glm::vec3(std::numeric_limits<float>::infinity()) || std::isnan(v.x)) {
            continue;  // a texel the stitcher does not read keeps what it held
        }
        ASSERT_TRUE(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z));
        ASSERT_GE(v.x, 0.0f);
    }
    EXPECT_TRUE(std::isfinite(pages[0].current.at(21, 10).x)) << "a stitched texel is finite";
}

/// cornell as luxel-prep prepared it (its walls and floor cut in two surfaces each), photons,
/// AIM and one CPU gather over every surface; the seams' mismatch afterwards.
double cornell_seam_mismatch(bool stitch, std::size_t* sample_count) {
    luxel::testing::TracedLevel level("cornell");
    lighting::PhotonWorld& photons = *level.photons;
    lighting::IlluminationSettings settings;
    settings.stitch_seams = stitch;
    lighting::IlluminationMaps maps(level.registry, photons, settings);
    maps.sync();
    for (const auto& request : maps.aim_requests()) {
        maps.rebuild_aim(request.surface);
    }
    lighting::CpuGatherer gatherer(photons.ray_scene(), maps.aim(), {64, 1e6f}, &level.jobs);
    for (const auto& request : maps.gather_requests()) {
        maps.gather(request.surface, 1u << 20, gatherer, 0.0);
    }
    const auto samples = maps.seam_samples();
    *sample_count = samples.size();
    EXPECT_EQ(maps.counters().seam_stitches > 0, stitch);
    for (const IimPage& page : maps.iim_pages()) {
        for (const glm::vec3& v : page.current.texels) {
            EXPECT_TRUE(std::isfinite(v.x) && v.x >= 0.0f && std::isfinite(v.y) &&
                        std::isfinite(v.z));
        }
    }
    return lighting::seam_mismatch(samples, maps.iim_pages());
}

TEST(SeamStitcher, CornellsSplitWallsShowNoStep) {
    std::size_t samples = 0;
    const double apart = cornell_seam_mismatch(false, &samples);
    EXPECT_GT(samples, 100u) << "cornell's walls, floor and ceiling are two surfaces each";
    std::size_t stitched_samples = 0;
    const double stitched = cornell_seam_mismatch(true, &stitched_samples);
    EXPECT_EQ(stitched_samples, samples);
    // The goal: the two sides agree within 2% (relRMSE of one against the other).
    EXPECT_LT(stitched, 0.02) << "without stitching " << apart;
    EXPECT_LT(stitched, 0.25 * apart) << "without stitching " << apart;
    RecordProperty("mismatch_without", std::to_string(apart));
    RecordProperty("mismatch_with", std::to_string(stitched));
    std::printf("cornell seams: %zu samples, mismatch %.4f without stitching, %.4f with\n", samples,
                apart, stitched);
}

}  // namespace
