// The luxel-bench executable: errors that name the flag or level at fault, a tiny run that
// writes every output with consistent columns, and the references (light maps and frames)
// reused from the cache by a second run. The image and backend columns: bench_image_test.cpp.

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench_outputs.hpp"
#include "luxel/runtime/image.hpp"
#include "temp_dir.hpp"

namespace {

using luxel::testing::CommandResult;
using luxel::testing::count;
using luxel::testing::luxel_bench;
using luxel::testing::quoted;
using luxel::testing::read_csv;

TEST(BenchCli, ABadFlagIsRejectedByName) {
    const CommandResult run = luxel_bench("--level cornell --bogus 3");
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.output.find("--bogus"), std::string::npos) << run.output;
}

TEST(BenchCli, AMissingLevelIsNamed) {
    luxel::testing::TempDir dir("luxel-bench-cli");
    CommandResult run = luxel_bench("--level no-such-level --out " + quoted(dir / "out"));
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.output.find("no-such-level"), std::string::npos) << run.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "out" / "runs.csv"));
    run = luxel_bench("--frames 3");
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.output.find("--level"), std::string::npos) << run.output;
}

TEST(BenchCli, BadValuesAreExplained) {
    CommandResult run = luxel_bench("--level cornell --sweep photons=77y40");
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.output.find("--sweep photons"), std::string::npos) << run.output;
    run = luxel_bench("--level cornell --sweep colour=1,2");
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.output.find("unknown knob"), std::string::npos) << run.output;
    run = luxel_bench("--level cornell --budgets 4,-1");
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.output.find("--budgets"), std::string::npos) << run.output;
    run = luxel_bench("--level cornell --change 'no such node:1,0,0' --frames 1");
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.output.find("no such node"), std::string::npos) << run.output;
    run = luxel_bench("--level cornell --change cube:1,0");
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.output.find("--change"), std::string::npos) << run.output;
    run = luxel_bench("--level cornell --change 'door hinge:turn=0,1,0'");
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.output.find("the axis and the angle"), std::string::npos) << run.output;
    run = luxel_bench("--level cornell --change 'moving cube:turn=0,0,0,90'");
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.output.find("axis is zero"), std::string::npos) << run.output;
}

TEST(BenchCli, TheAnimatedPhaseJudgesEachCheckpointByItsOwnReference) {
    luxel::testing::TempDir dir("luxel-bench-animate");
    const std::filesystem::path out = dir / "out";
    const CommandResult run = luxel_bench(
        "--level cornell --budgets 8 --frames 2 --change none --animate 4 --checkpoint 2 "
        "--ref-photons 100000 --ref-caustic-photons 50000 --ref-spp 1 --no-image --threads 2 "
        "--out " +
        quoted(out));
    ASSERT_EQ(run.exit_code, 0) << run.output;
    // The static pose's reference and one per animated checkpoint (frames 2 and 4).
    EXPECT_EQ(count(run.output, "computing reference"), 3u) << run.output;
    const auto rows = read_csv(out / "checkpoints.csv");
    ASSERT_GT(rows.size(), 1u);
    const auto column = [&](const std::string& name) {
        return static_cast<std::size_t>(std::find(rows[0].begin(), rows[0].end(), name) -
                                        rows[0].begin());
    };
    ASSERT_LT(column("animated_time_s"), rows[0].size());
    std::vector<double> times;
    for (std::size_t r = 1; r < rows.size(); ++r) {
        if (rows[r][column("phase")] != "animated") {
            continue;
        }
        const double error = std::stod(rows[r][column("indirect_relrmse")]);
        EXPECT_TRUE(std::isfinite(error) && error >= 0.0) << rows[r][column("indirect_relrmse")];
        times.push_back(std::stod(rows[r][column("animated_time_s")]));
    }
    ASSERT_EQ(times.size(), 2u);
    EXPECT_NEAR(times[0], 2.0 / 30.0, 1e-3);
    EXPECT_NEAR(times[1], 4.0 / 30.0, 1e-3);
    const auto runs = read_csv(out / "runs.csv");
    ASSERT_EQ(runs.size(), 2u);
    const auto median = std::find(runs[0].begin(), runs[0].end(), "animated_indirect_median");
    ASSERT_NE(median, runs[0].end());
    EXPECT_NE(runs[1][static_cast<std::size_t>(median - runs[0].begin())], "not_measured");
}

TEST(BenchCli, ALightSwitchAndATurnAreScriptedChanges) {
    luxel::testing::TempDir dir("luxel-bench-switch");
    const std::string tiny =
        " --budgets 8 --frames 4 --after 3 --checkpoint 2 --ref-photons 100000 "
        "--ref-caustic-photons 50000 --ref-spp 1 --no-image --threads 2 --out ";
    // The box light of the caustics level goes off after the static frames: a new reference
    // for the light that is left, and the recovery measured against it.
    CommandResult run =
        luxel_bench("--level caustics --change 'box light:off'" + tiny + quoted(dir / "switch"));
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_NE(run.output.find("after the change"), std::string::npos) << run.output;
    EXPECT_EQ(read_csv(dir / "switch" / "after_change.csv").size(), 1u + 3u);
    // Cornell's cube turned 45 degrees about its vertical axis.
    run = luxel_bench("--level cornell --change 'moving cube:turn=0,1,0,45'" + tiny +
                      quoted(dir / "turn"));
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_EQ(read_csv(dir / "turn" / "after_change.csv").size(), 1u + 3u);
    // A node without a light cannot be switched.
    run = luxel_bench("--level cornell --change 'moving cube:off'" + tiny + quoted(dir / "bad"));
    EXPECT_NE(run.exit_code, 0);
    EXPECT_NE(run.output.find("carries no light"), std::string::npos) << run.output;
}

TEST(BenchCli, ATinyRunWritesEveryOutputAndASecondReusesTheReference) {
    luxel::testing::TempDir dir("luxel-bench-run");
    const std::filesystem::path out = dir / "out";
    const std::string arguments =
        "--level cornell --budgets 8 --frames 4 --after 3 --checkpoint 2 --ref-photons 100000 "
        "--ref-caustic-photons 50000 --ref-spp 1 --image 32x24 --image-spp 4 --sweep rays=16 "
        "--threads 2 --out " +
        quoted(out);
    const CommandResult first = luxel_bench(arguments);
    ASSERT_EQ(first.exit_code, 0) << first.output;
    // Light maps and a frame, before and after the change.
    EXPECT_EQ(count(first.output, "computing reference frame"), 2u) << first.output;
    EXPECT_EQ(count(first.output, "computing reference"), 4u) << first.output;

    const auto runs = read_csv(out / "runs.csv");
    ASSERT_EQ(runs.size(), 3u);  // header, paper @ 8 ms, rays=16 @ 8 ms
    const std::vector<std::string> must{"method",
                                        "budget_ms",
                                        "ms_median",
                                        "ms_p95",
                                        "indirect_relrmse",
                                        "indirect_worst_region",
                                        "indirect_p99_texel",
                                        "caustic_relrmse",
                                        "recovery_frames",
                                        "worst_region_after",
                                        "p99_texel_after",
                                        "recovery_frames_local",
                                        "ref_se_indirect"};
    for (const std::string& column : must) {
        EXPECT_NE(std::find(runs[0].begin(), runs[0].end(), column), runs[0].end()) << column;
    }
    for (std::size_t r = 1; r < runs.size(); ++r) {
        EXPECT_EQ(runs[r].size(), runs[0].size()) << "row " << r;
        for (const std::string& cell : runs[r]) {
            EXPECT_FALSE(cell.empty()) << "row " << r;
        }
    }
    EXPECT_EQ(runs[1][1], "paper");
    EXPECT_EQ(runs[2][1], "rays=16");
    for (const char* name : {"checkpoints.csv", "after_change.csv"}) {
        const auto rows = read_csv(out / name);
        ASSERT_GT(rows.size(), 1u) << name;
        for (const auto& row : rows) {
            EXPECT_EQ(row.size(), rows[0].size()) << name;
        }
    }
    EXPECT_EQ(read_csv(out / "after_change.csv").size(), 1u + 2u * 3u);
    // The local error: finite, non-negative numbers in every run and after every frame.
    const auto cell = [&](const std::vector<std::vector<std::string>>& rows, std::size_t row,
                          const std::string& name) {
        const auto at = std::find(rows[0].begin(), rows[0].end(), name);
        EXPECT_NE(at, rows[0].end()) << name;
        return std::stod(rows[row].at(static_cast<std::size_t>(at - rows[0].begin())));
    };
    for (std::size_t r = 1; r < runs.size(); ++r) {
        for (const char* name : {"indirect_worst_region", "indirect_p99_texel",
                                 "worst_region_after", "p99_texel_after"}) {
            const double value = cell(runs, r, name);
            EXPECT_TRUE(std::isfinite(value) && value >= 0.0) << name << " row " << r;
        }
        // Local recovery needs the global error back too: never before the global one.
        const double global = cell(runs, r, "recovery_frames");
        const double local = cell(runs, r, "recovery_frames_local");
        if (global < 0.0) {
            EXPECT_EQ(local, -1.0) << "row " << r;
        } else if (local >= 0.0) {
            EXPECT_GE(local, global) << "row " << r;
        }
    }
    const auto after_rows = read_csv(out / "after_change.csv");
    for (std::size_t r = 1; r < after_rows.size(); ++r) {
        EXPECT_GT(cell(after_rows, r, "indirect_worst_region"), 0.0) << "row " << r;
        EXPECT_GT(cell(after_rows, r, "indirect_p99_texel"), 0.0) << "row " << r;
    }

    std::ifstream json_file(out / "results.json");
    const nlohmann::json json = nlohmann::json::parse(json_file);
    ASSERT_EQ(json["runs"].size(), 2u);
    EXPECT_EQ(json["runs"][0]["frame_ms"].size(), 4u + 3u);
    EXPECT_EQ(json["level"], "cornell");

    for (const char* png : {"indirect_vs_ms.png", "caustic_vs_ms.png", "image_vs_ms.png",
                            "after_change.png", "after_change_region.png"}) {
        const luxel::Image8 image = luxel::read_png(out / png);
        EXPECT_EQ(image.width, 900) << png;
        EXPECT_EQ(image.height, 560) << png;
    }
    std::ifstream summary(out / "summary.md");
    const std::string text((std::istreambuf_iterator<char>(summary)),
                           std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("| paper | 8.0 |"), std::string::npos) << text;
    EXPECT_NE(text.find("Goals"), std::string::npos) << text;

    // The same references again: read from OUT/cache, not computed.
    const CommandResult second = luxel_bench(arguments);
    ASSERT_EQ(second.exit_code, 0) << second.output;
    EXPECT_EQ(count(second.output, "computing reference"), 0u) << second.output;
    // Each of the two runs reads both poses' light maps and frames.
    EXPECT_EQ(count(second.output, "from cache"), 8u) << second.output;
    // The first run's results are replaced, and the run says so before and after.
    EXPECT_NE(second.output.find("holds an earlier run's results: they will be replaced"),
              std::string::npos)
        << second.output;
    EXPECT_NE(second.output.find("replaced: " + (out / "results.json").string()), std::string::npos)
        << second.output;
    EXPECT_EQ(count(first.output, "replaced"), 0u) << first.output;
}

// luxel-ref's reference-bytes check holds for luxel-bench's reference too: refused, naming
// the level and the limit, before the reference allocates its per-texel state.
TEST(BenchCli, LightMapsBeyondTheReferenceMemoryLimitAreRefused) {
    luxel::testing::TempDir dir("luxel-bench-cli");
    const CommandResult run = luxel_bench(
        "--level cornell --budgets 8 --frames 2 --ref-photons 100000 --ref-caustic-photons 50000 "
        "--ref-spp 1 --no-image --threads 2 --limit reference-bytes=1k --out " +
        quoted(dir / "out"));
    EXPECT_EQ(run.exit_code, 1) << run.output;
    EXPECT_NE(run.output.find("cornell.glb: "), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("reference-bytes"), std::string::npos) << run.output;
    EXPECT_EQ(count(run.output, "computing reference"), 0u) << run.output;
}

TEST(BenchCli, AnOutThatIsAFileIsRefusedBeforeAnyWork) {
    luxel::testing::TempDir dir("luxel-bench-out");
    const std::filesystem::path file = dir / "results";
    std::ofstream(file) << "not a folder\n";
    const CommandResult run = luxel_bench(
        "--level cornell --budgets 8 --frames 2 --ref-photons 100000 --ref-caustic-photons 50000 "
        "--ref-spp 1 --no-image --threads 2 --out " +
        quoted(file));
    EXPECT_EQ(run.exit_code, 1) << run.output;
    EXPECT_NE(run.output.find("--out " + file.string() + ": is a file, not a folder"),
              std::string::npos)
        << run.output;
    // Refused before the reference: nothing computed, the file as it was.
    EXPECT_EQ(count(run.output, "computing reference"), 0u) << run.output;
    std::ifstream kept(file);
    std::string line;
    std::getline(kept, line);
    EXPECT_EQ(line, "not a folder");
}

}  // namespace
