// The page packer: padded chart rectangles never overlap, stay on their page, and a surface's
// charts share a page; the automatic page size wastes no more than the sizes it passed over.

#include <random>

#include <gtest/gtest.h>

#include "luxel/prep/packing.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/runtime/jobs.hpp"

namespace {

using namespace luxel;

struct Problem {
    std::vector<prep::PackChart> charts;
    std::vector<std::vector<int>> groups;
};

/// Charts from 1 x 1 to 40 x 40 texels in groups of one to four.
Problem random_problem(unsigned seed, int count) {
    std::mt19937 random(seed);
    std::uniform_int_distribution<int> side(1, 40);
    std::uniform_int_distribution<int> group_size(1, 4);
    Problem problem;
    while (static_cast<int>(problem.charts.size()) < count) {
        std::vector<int> group;
        for (int n = group_size(random); n > 0; --n) {
            group.push_back(static_cast<int>(problem.charts.size()));
            problem.charts.push_back({side(random), side(random)});
        }
        problem.groups.push_back(std::move(group));
    }
    return problem;
}

void expect_valid(const Problem& problem, const prep::PackLayout& layout, int padding) {
    ASSERT_EQ(layout.placements.size(), problem.charts.size());
    const int n = layout.page_size;
    std::vector<std::vector<int>> owner(static_cast<std::size_t>(layout.page_count),
                                        std::vector<int>(static_cast<std::size_t>(n * n), -1));
    for (std::size_t c = 0; c < problem.charts.size(); ++c) {
        const prep::ChartPlacement& p = layout.placements[c];
        ASSERT_GE(p.page, 0);
        ASSERT_LT(p.page, layout.page_count);
        const int w = p.rotated ? problem.charts[c].height : problem.charts[c].width;
        const int h = p.rotated ? problem.charts[c].width : problem.charts[c].height;
        for (int y = p.y - padding; y < p.y + h + padding; ++y) {
            for (int x = p.x - padding; x < p.x + w + padding; ++x) {
                ASSERT_TRUE(x >= 0 && y >= 0 && x < n && y < n)
                    << "chart " << c << " leaves the page";
                int& o =
                    owner[static_cast<std::size_t>(p.page)][static_cast<std::size_t>(y * n + x)];
                ASSERT_EQ(o, -1) << "charts " << o << " and " << c << " overlap";
                o = static_cast<int>(c);
            }
        }
    }
    for (const auto& group : problem.groups) {
        for (const int c : group) {
            EXPECT_EQ(layout.placements[static_cast<std::size_t>(c)].page,
                      layout.placements[static_cast<std::size_t>(group.front())].page);
        }
    }
}

TEST(Packing, FixedPagesHoldEveryChartWithItsPadding) {
    for (unsigned seed = 1; seed <= 5; ++seed) {
        const Problem problem = random_problem(seed, 200);
        for (const int padding : {0, 1, 2}) {
            const auto layout = prep::pack_fixed(problem.charts, problem.groups, padding, 128);
            EXPECT_EQ(layout.page_size, 128);
            EXPECT_GT(layout.page_count, 1);
            expect_valid(problem, layout, padding);
        }
    }
}

TEST(Packing, AutomaticSizeWastesNoMoreThanAnyFixedSizeItTried) {
    const Problem problem = random_problem(7, 120);
    JobSystem jobs(2);
    const auto automatic = prep::pack_automatic(problem.charts, problem.groups, 1, 2048, &jobs);
    expect_valid(problem, automatic, 1);
    std::int64_t used = 0;
    for (const auto& c : problem.charts) {
        used += static_cast<std::int64_t>(c.width) * c.height;
    }
    // The rectangles alone fill most of the pages.
    EXPECT_GT(static_cast<double>(used) / static_cast<double>(automatic.page_texels()), 0.7);
    for (const int size : {128, 160, 256, 400}) {
        const auto fixed = prep::pack_fixed(problem.charts, problem.groups, 1, size);
        EXPECT_LE(static_cast<double>(automatic.page_texels()),
                  1.01 * static_cast<double>(fixed.page_texels()))
            << "page size " << size;
    }
    // The choice does not depend on the threads that tried the sizes.
    const auto serial = prep::pack_automatic(problem.charts, problem.groups, 1, 2048, nullptr);
    EXPECT_EQ(serial.page_size, automatic.page_size);
    EXPECT_EQ(serial.page_count, automatic.page_count);
}

TEST(Packing, TooSmallAPageIsAClearError) {
    const std::vector<prep::PackChart> charts{{50, 10}};
    try {
        (void)prep::pack_fixed(charts, {{0}}, 1, 32);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("--page-size 32"), std::string::npos) << e.what();
    }
}

TEST(Packing, NothingToPackMakesNoPages) {
    JobSystem jobs(1);
    const auto layout = prep::pack_automatic({}, {}, 1, 2048, &jobs);
    EXPECT_EQ(layout.page_count, 0);
    EXPECT_EQ(layout.page_texels(), 0);
}

}  // namespace
