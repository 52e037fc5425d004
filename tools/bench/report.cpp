#include "report.hpp"

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "luxel/runtime/error.hpp"
#include "plot.hpp"

namespace luxel::bench {
namespace {

/// The goals for cornell (converged light maps).
constexpr double kIndirectGoal = 0.05;
constexpr double kCausticGoal = 0.15;
constexpr double kImageGoal = 0.05;
constexpr double kRecoveryBudgetMs = 4.0;
constexpr int kRecoveryGoalFrames = 30;

std::string number(double v, int decimals = 4) {
    if (!std::isfinite(v)) {
        return v > 0 ? "inf" : "nan";
    }
    std::ostringstream out;
    out.setf(std::ios::fixed);
    out.precision(decimals);
    out << v;
    return out.str();
}

std::string change_text(const std::optional<Change>& change) {
    if (!change) {
        return "none";
    }
    std::ostringstream out;
    out << change->node << ":" << change->offset.x << "," << change->offset.y << ","
        << change->offset.z;
    return out.str();
}

/// An image figure, or kNotMeasured.
std::string image_number(const RunResult& r, double v, int decimals = 4) {
    return r.image_measured ? number(v, decimals) : kNotMeasured;
}

std::vector<std::string> row(const ReportInfo& info, const RunResult& r) {
    const BenchConfig& c = r.config;
    return {
        info.level,
        c.method,
        number(c.budget_ms, 2),
        std::to_string(c.groups),
        std::to_string(c.per_group),
        std::to_string(c.aim_n),
        std::to_string(c.rays),
        std::to_string(c.texels_per_unit),
        std::to_string(c.filter),
        std::to_string(c.refine),
        std::to_string(c.caustic_photons),
        std::to_string(c.caustic_slices),
        c.backend,
        c.kernel,
        c.aa,
        std::to_string(r.frame_ms.size()),
        std::to_string(r.active_frames),
        std::to_string(r.static_work_frames),
        number(r.ms_median, 3),
        number(r.ms_p95, 3),
        number(r.indirect),
        number(r.indirect_region),
        number(r.indirect_p99),
        number(r.caustic),
        image_number(r, r.image),
        image_number(r, r.image_net),
        image_number(r, r.reference_se_image, 5),
        r.changed ? change_text(info.change) : "none",
        number(r.indirect_at_change),
        number(r.indirect_after),
        r.changed ? image_number(r, r.image_after) : kNotMeasured,
        std::to_string(r.recovery_frames),
        r.changed ? number(r.region_after) : kNotMeasured,
        r.changed ? number(r.p99_after) : kNotMeasured,
        std::to_string(r.recovery_frames_local),
        number(r.reference_se[0], 5),
        number(r.reference_se[1], 5),
        number(r.reference_se[2], 5),
        number(r.reference_se_after[1], 5),
        std::to_string(r.caustic_photons),
        std::to_string(r.caustic_unbinned),
        image_number(r, r.frame_gpu_ms, 3),
        image_number(r, r.caustic_gpu_ms, 3),
        r.animated_indirect.empty() ? kNotMeasured : number(r.animated_indirect_median),
        r.animated_indirect.empty() ? kNotMeasured : number(r.animated_indirect_max),
        r.unmapped_pixels > 0 ? image_number(r, r.image_unmapped) : kNotMeasured,
        std::to_string(r.unmapped_pixels),
        r.unmapped_interior_pixels > 0 ? image_number(r, r.image_unmapped_interior) : kNotMeasured,
        std::to_string(r.unmapped_interior_pixels)};
}

void write_csv(const std::filesystem::path& path, const std::vector<std::string>& header,
               const std::vector<std::vector<std::string>>& rows) {
    std::ofstream out(path);
    const auto line = [&](const std::vector<std::string>& cells) {
        for (std::size_t i = 0; i < cells.size(); ++i) {
            out << (i ? "," : "");
            // RFC 4180: a cell holding a comma or a quote is quoted, its quotes doubled (the
            // change "moving cube:0.3,0,0" has commas).
            if (cells[i].find_first_of(",\"") == std::string::npos) {
                out << cells[i];
                continue;
            }
            out << '"';
            for (const char c : cells[i]) {
                out << (c == '"' ? "\"\"" : std::string(1, c));
            }
            out << '"';
        }
        out << "\n";
    };
    line(header);
    for (const auto& r : rows) {
        line(r);
    }
    if (!out) {
        throw Error("cannot write " + path.string());
    }
}

std::string run_name(const RunResult& r) {
    return r.config.method + " @ " + number(r.config.budget_ms, 1) + " ms";
}

enum class Measure { Indirect, Caustic, Image };

double measured(const RunResult& r, Measure what) {
    switch (what) {
        case Measure::Indirect:
            return r.indirect;
        case Measure::Caustic:
            return r.caustic;
        case Measure::Image:
            return r.image;
    }
    return 0.0;
}

/// Error against median ms, one curve per method, with the Pareto front over all runs.
PlotSpec error_plot(const std::vector<RunResult>& runs, Measure what, const ReportInfo& info) {
    PlotSpec spec;
    static constexpr const char* kTitles[] = {": indirect light-map error against ms per frame",
                                              ": caustic light-map error against ms per frame",
                                              ": image error against lighting ms per frame"};
    static constexpr const char* kLabels[] = {"indirect relRMSE %", "caustic relRMSE %",
                                              "image relRMSE %"};
    spec.title = info.level + kTitles[static_cast<int>(what)];
    spec.x_label = "lighting ms per frame (median, real clock)";
    spec.y_label = kLabels[static_cast<int>(what)];
    std::map<std::string, std::size_t> index;
    std::vector<glm::dvec2> all;
    for (const RunResult& r : runs) {
        auto [it, added] = index.try_emplace(r.config.method, spec.series.size());
        if (added) {
            spec.series.push_back({r.config.method, {}, false});
        }
        const glm::dvec2 p(r.ms_median, 100.0 * measured(r, what));
        spec.series[it->second].points.push_back(p);
        all.push_back(p);
    }
    for (Series& s : spec.series) {
        std::sort(s.points.begin(), s.points.end(),
                  [](const glm::dvec2& a, const glm::dvec2& b) { return a.x < b.x; });
    }
    spec.front = pareto_front(all);
    if (info.level == "cornell") {
        static constexpr double kGoals[] = {kIndirectGoal, kCausticGoal, kImageGoal};
        spec.lines.push_back({100.0 * kGoals[static_cast<int>(what)], "goal"});
    }
    return spec;
}

/// What an after-change plot shows: the global relRMSE, or the worst 8x8-texel region's error.
enum class AfterMeasure { Global, WorstRegion };

PlotSpec after_plot(const std::vector<RunResult>& runs, const ReportInfo& info, AfterMeasure what) {
    const bool region = what == AfterMeasure::WorstRegion;
    PlotSpec spec;
    spec.title =
        info.level +
        (region ? ": worst 8x8-texel region after moving " : ": indirect error after moving ") +
        (info.change ? info.change->node : std::string("nothing"));
    spec.x_label = "frames after the change";
    spec.y_label = region ? "worst region error, % of the level's RMS" : "indirect relRMSE %";
    // The paper's configuration at every budget, then other methods at the budget nearest
    // 4 ms: at most ten curves stay readable.
    for (const RunResult& r : runs) {
        if (!r.changed || spec.series.size() >= 10) {
            continue;
        }
        const bool paper = r.config.method == "paper";
        if (!paper && std::abs(r.config.budget_ms - kRecoveryBudgetMs) > 1e-9) {
            continue;
        }
        const std::vector<double>& curve = region ? r.after_region : r.after_indirect;
        Series s{run_name(r),
                 {{0.0, 100.0 * (region ? r.region_at_change : r.indirect_at_change)}},
                 !paper};
        for (std::size_t f = 0; f < curve.size(); ++f) {
            s.points.push_back({static_cast<double>(f + 1), 100.0 * curve[f]});
        }
        spec.series.push_back(std::move(s));
        if (paper && std::abs(r.config.budget_ms - kRecoveryBudgetMs) < 1e-9) {
            spec.lines.push_back(
                {200.0 * (region ? r.indirect_region : r.indirect), "2x converged, paper @ 4 ms"});
        }
    }
    return spec;
}

std::string recovery_text(const RunResult& r, int frames) {
    if (!r.changed) {
        return "-";
    }
    return frames >= 0 ? std::to_string(frames) : std::string("not within");
}

std::string goal_line(const std::string& what, double value, double goal, bool lower_is_met) {
    const bool met = lower_is_met ? value <= goal : value >= goal;
    return "- " + what + ": " + number(100.0 * value, 2) + "% (goal <= " + number(100.0 * goal, 0) +
           "%): **" + (met ? "met" : "missed") + "**\n";
}

}  // namespace

const std::vector<std::string>& run_columns() {
    static const std::vector<std::string> columns{"level",
                                                  "method",
                                                  "budget_ms",
                                                  "groups",
                                                  "per_group",
                                                  "aim_n",
                                                  "rays",
                                                  "texels_per_unit",
                                                  "filter",
                                                  "refine",
                                                  "caustic_photons",
                                                  "caustic_slices",
                                                  "backend",
                                                  "kernel",
                                                  "aa",
                                                  "frames",
                                                  "active_frames",
                                                  "static_work_frames",
                                                  "ms_median",
                                                  "ms_p95",
                                                  "indirect_relrmse",
                                                  "indirect_worst_region",
                                                  "indirect_p99_texel",
                                                  "caustic_relrmse",
                                                  "image_relrmse",
                                                  "image_relrmse_net",
                                                  "ref_se_image",
                                                  "change",
                                                  "indirect_at_change",
                                                  "indirect_after",
                                                  "image_after",
                                                  "recovery_frames",
                                                  "worst_region_after",
                                                  "p99_texel_after",
                                                  "recovery_frames_local",
                                                  "ref_se_direct",
                                                  "ref_se_indirect",
                                                  "ref_se_caustic",
                                                  "ref_se_indirect_after",
                                                  "caustic_photons_stored",
                                                  "caustic_unbinned",
                                                  "frame_gpu_ms",
                                                  "caustic_gpu_ms",
                                                  "animated_indirect_median",
                                                  "animated_indirect_max",
                                                  "image_unmapped_relrmse",
                                                  "unmapped_pixels",
                                                  "image_unmapped_interior_relrmse",
                                                  "unmapped_interior_pixels"};
    return columns;
}

std::vector<std::filesystem::path> write_report(const ReportInfo& info,
                                                const std::vector<RunResult>& runs) {
    const std::filesystem::path& out = info.options->out;
    std::filesystem::create_directories(out);
    std::vector<std::filesystem::path> files;

    std::vector<std::vector<std::string>> rows;
    std::vector<std::vector<std::string>> checkpoints;
    std::vector<std::vector<std::string>> after;
    nlohmann::json json;
    json["level"] = info.level;
    json["command"] = info.command;
    json["change"] = change_text(info.change);
    const ReferenceSpec& ref = info.options->reference;
    json["reference"] = {{"indirect_photons", ref.indirect_photons},
                         {"caustic_photons", ref.caustic_photons},
                         {"spp", ref.spp},
                         {"seed", ref.seed}};
    const ImageSpec& image = info.options->image;
    json["image"] = {{"measured", image.enabled}};
    if (image.enabled) {
        json["image"]["width"] = image.width;
        json["image"]["height"] = image.height;
        json["image"]["reference_spp"] = image.spp;
    }
    json["gl"] = info.gl;
    for (const RunResult& r : runs) {
        rows.push_back(row(info, r));
        nlohmann::json run;
        const auto cells = rows.back();
        for (std::size_t i = 0; i < cells.size(); ++i) {
            run[run_columns()[i]] = cells[i];
        }
        run["frame_ms"] = r.frame_ms;
        run["after_indirect"] = r.after_indirect;
        run["after_caustic"] = r.after_caustic;
        run["after_worst_region"] = r.after_region;
        run["after_p99_texel"] = r.after_p99;
        if (r.caustic_pixels >= 0.0) {
            run["caustic_pixels_relrmse"] = r.caustic_pixels;
            run["ref_se_caustic_pixels"] = r.reference_se_caustic_pixels;
        }
        for (const Checkpoint& c : r.checkpoints) {
            const char* phase = c.animated ? "animated" : c.after_change ? "after" : "static";
            checkpoints.push_back({r.config.method, number(r.config.budget_ms, 2), phase,
                                   std::to_string(c.frame), number(c.indirect),
                                   number(c.indirect_region), number(c.indirect_p99),
                                   number(c.caustic), c.image ? number(*c.image) : kNotMeasured,
                                   c.animated ? number(c.time, 3) : "0"});
            run["checkpoints"].push_back(
                {{"frame", c.frame},
                 {"phase", phase},
                 {"time", c.time},
                 {"after_change", c.after_change},
                 {"indirect", c.indirect},
                 {"indirect_worst_region", c.indirect_region},
                 {"indirect_p99_texel", c.indirect_p99},
                 {"caustic", c.caustic},
                 {"image", c.image ? nlohmann::json(*c.image) : nlohmann::json(kNotMeasured)}});
        }
        for (std::size_t f = 0; f < r.after_indirect.size(); ++f) {
            after.push_back({r.config.method, number(r.config.budget_ms, 2), std::to_string(f + 1),
                             number(r.after_indirect[f]), number(r.after_region[f]),
                             number(r.after_p99[f]), number(r.after_caustic[f])});
        }
        json["runs"].push_back(run);
    }
    write_csv(out / "runs.csv", run_columns(), rows);
    write_csv(out / "checkpoints.csv",
              {"method", "budget_ms", "phase", "frame", "indirect_relrmse", "indirect_worst_region",
               "indirect_p99_texel", "caustic_relrmse", "image_relrmse", "animated_time_s"},
              checkpoints);
    write_csv(out / "after_change.csv",
              {"method", "budget_ms", "frame", "indirect_relrmse", "indirect_worst_region",
               "indirect_p99_texel", "caustic_relrmse"},
              after);
    {
        std::ofstream file(out / "results.json");
        file << json.dump(2) << "\n";
    }
    files.insert(files.end(), {out / "runs.csv", out / "checkpoints.csv", out / "after_change.csv",
                               out / "results.json"});
    write_plot(out / "indirect_vs_ms.png", error_plot(runs, Measure::Indirect, info));
    write_plot(out / "caustic_vs_ms.png", error_plot(runs, Measure::Caustic, info));
    files.push_back(out / "indirect_vs_ms.png");
    files.push_back(out / "caustic_vs_ms.png");
    if (image.enabled) {
        write_plot(out / "image_vs_ms.png", error_plot(runs, Measure::Image, info));
        files.push_back(out / "image_vs_ms.png");
    }
    if (info.change) {
        write_plot(out / "after_change.png", after_plot(runs, info, AfterMeasure::Global));
        files.push_back(out / "after_change.png");
        write_plot(out / "after_change_region.png",
                   after_plot(runs, info, AfterMeasure::WorstRegion));
        files.push_back(out / "after_change_region.png");
    }

    std::ostringstream md;
    md << "# luxel-bench: " << info.level << "\n\n```\n" << info.command << "\n```\n\n";
    md << "Reference: " << ref.indirect_photons << " indirect photons, " << ref.caustic_photons
       << " caustic photons, " << ref.spp << " spp (direct), seed " << ref.seed
       << ". Change: " << change_text(info.change) << ".\n\n";
    if (image.enabled) {
        md << "Image error: the real-time frame (FrameRenderer + CausticPass on " << info.gl
           << ") against a reference frame of "
           << (image.camera ? "the --camera view" : "the level's first camera") << ", "
           << image.width << "x" << image.height << ", " << image.spp
           << " spp; \"image\" is its relRMSE at the last static frame, (net) the same with the "
              "reference frame's own noise taken out. Frames side by side (real time | "
              "reference) in frames/, each real-time frame also as linear EXR.\n\n";
    } else {
        md << "Image error: **not measured** (--no-image).\n\n";
    }
    md << "Local error: the indirect light's worst 8x8-texel region and 99th-percentile texel, "
          "in % of the level's RMS reference indirect irradiance (the relRMSE's denominator). "
          "Recovery frames: until the global error is under twice its converged value "
          "(global), and until the global, worst-region and p99 errors all are (local).\n\n";
    md << "| method | budget ms | ms median | ms p95 | indirect | worst region / p99 | caustic "
          "| image (net) | after change | worst region after | recovery frames global / local "
          "| ref. SE ind. / caus. / image |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const RunResult& r : runs) {
        md << "| " << r.config.method << " | " << number(r.config.budget_ms, 1) << " | "
           << number(r.ms_median, 2) << " | " << number(r.ms_p95, 2) << " | "
           << number(100.0 * r.indirect, 2) << "% | " << number(100.0 * r.indirect_region, 1)
           << "% / " << number(100.0 * r.indirect_p99, 1) << "% | " << number(100.0 * r.caustic, 2)
           << "% | "
           << (r.image_measured
                   ? number(100.0 * r.image, 2) + "% (" + number(100.0 * r.image_net, 2) + "%)"
                   : std::string("not measured"))
           << " | "
           << (r.changed ? number(100.0 * r.indirect_at_change, 1) + "% -> " +
                               number(100.0 * r.indirect_after, 1) + "%"
                         : "-")
           << " | "
           << (r.changed ? number(100.0 * r.region_at_change, 1) + "% -> " +
                               number(100.0 * r.region_after, 1) + "%"
                         : "-")
           << " | " << recovery_text(r, r.recovery_frames) << " / "
           << recovery_text(r, r.recovery_frames_local) << " | "
           << number(100.0 * r.reference_se[1], 2) << "% / " << number(100.0 * r.reference_se[2], 2)
           << "% / " << (r.image_measured ? number(100.0 * r.reference_se_image, 2) + "%" : "-")
           << " |\n";
    }
    if (info.options->animate > 0) {
        md << "\nAnimated phase (" << info.options->animate
           << " frames of the level's animation after the change; indirect relRMSE against a "
              "reference of each checkpoint's instant):\n\n";
        for (const RunResult& r : runs) {
            md << "- " << r.config.method << " @ " << number(r.config.budget_ms, 1)
               << " ms: median " << number(100.0 * r.animated_indirect_median, 2) << "%, largest "
               << number(100.0 * r.animated_indirect_max, 2) << "% over "
               << r.animated_indirect.size() << " checkpoints\n";
        }
    }
    md << "\nReference adequacy (its relative standard error at most 1/10 of the error it "
          "judges):\n";
    for (const RunResult& r : runs) {
        const bool ok_i = r.reference_se[1] <= 0.1 * r.indirect;
        const bool ok_c = r.reference_se[2] <= 0.1 * r.caustic;
        const bool ok_f = !r.image_measured || r.reference_se_image <= 0.1 * r.image;
        if (!ok_i || !ok_c || !ok_f) {
            md << "- " << run_name(r) << ": " << (ok_i ? "" : "indirect ")
               << (ok_c ? "" : "caustic ") << (ok_f ? "" : "image ")
               << "reference not converged enough\n";
        }
    }
    md << "- (rows not listed: adequate)\n";
    if (info.level == "cornell") {
        md << "\nGoals (issue 11), paper's configuration:\n";
        for (const RunResult& r : runs) {
            if (r.config.method != "paper") {
                continue;
            }
            md << "\n" << run_name(r) << ":\n";
            md << goal_line("indirect, converged", r.indirect, kIndirectGoal, true);
            md << goal_line("caustic, converged", r.caustic, kCausticGoal, true);
            if (r.image_measured) {
                md << goal_line("image, converged", r.image, kImageGoal, true);
                md << goal_line("image, converged, net of the reference's noise", r.image_net,
                                kImageGoal, true);
            } else {
                md << "- image: **not measured** (--no-image)\n";
            }
            if (r.changed) {
                const bool met = r.recovery_frames >= 0 && r.recovery_frames <= kRecoveryGoalFrames;
                md << "- recovery after the change: "
                   << (r.recovery_frames >= 0 ? std::to_string(r.recovery_frames) + " frames"
                                              : "not within the frames run")
                   << " (goal <= 30 at 4 ms): **" << (met ? "met" : "missed") << "**\n";
            }
        }
    }
    md << "\n![indirect](indirect_vs_ms.png)\n![caustic](caustic_vs_ms.png)\n";
    if (image.enabled) {
        md << "![image](image_vs_ms.png)\n";
    }
    if (info.change) {
        md << "![after change](after_change.png)\n"
              "![after change, worst region](after_change_region.png)\n";
    }
    {
        std::ofstream file(out / "summary.md");
        file << md.str();
    }
    files.push_back(out / "summary.md");
    return files;
}

}  // namespace luxel::bench
