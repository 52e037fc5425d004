#pragma once

// luxel-bench's outputs: CSV, JSON, PNG plots and a Markdown summary of all runs.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "bench_options.hpp"
#include "bench_run.hpp"

namespace luxel::bench {

struct ReportInfo {
    std::string level;
    std::string command;  ///< the command line, for the summary
    std::optional<Change> change;
    const Options* options = nullptr;
    std::string gl;  ///< the GL renderer and version, empty when none was created
};

/// Writes into options.out: runs.csv (one row per configuration), checkpoints.csv,
/// after_change.csv, results.json (everything), indirect_vs_ms.png, caustic_vs_ms.png,
/// image_vs_ms.png (when the image error was measured), after_change.png and summary.md.
/// Returns the files written.
std::vector<std::filesystem::path> write_report(const ReportInfo& info,
                                                const std::vector<RunResult>& runs);

/// What runs.csv and results.json hold in the image columns when --no-image left it out.
inline constexpr const char* kNotMeasured = "not_measured";

/// The columns of runs.csv, in order (tests check every row has them all).
[[nodiscard]] const std::vector<std::string>& run_columns();

}  // namespace luxel::bench
