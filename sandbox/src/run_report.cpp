#include "run_report.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <set>

#include "luxel/runtime/error.hpp"

namespace luxel::sandbox {

double quantile(std::vector<double> values, double q) {
    if (values.empty()) {
        return 0.0;
    }
    const auto index = static_cast<std::size_t>(
        std::clamp(q, 0.0, 1.0) * static_cast<double>(values.size() - 1) + 0.5);
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(index),
                     values.end());
    return values[index];
}

namespace {

nlohmann::json distribution(const std::vector<double>& values) {
    return {{"median", quantile(values, 0.5)},
            {"p95", quantile(values, 0.95)},
            {"max", values.empty() ? 0.0 : *std::max_element(values.begin(), values.end())}};
}

}  // namespace

void RunReport::set_info(const std::string& key, const nlohmann::json& value) {
    info_[key] = value;
}

void RunReport::add_frame(Frame frame) {
    frames_.push_back(std::move(frame));
}

nlohmann::json RunReport::to_json() const {
    std::vector<double> frame_ms;
    std::vector<double> lighting_ms;
    std::size_t over_budget = 0;
    double worst_ratio = 0.0;
    std::set<std::string> passes;
    std::set<std::string> counters;
    for (const Frame& frame : frames_) {
        frame_ms.push_back(frame.frame_ms);
        lighting_ms.push_back(frame.lighting_ms);
        if (frame.budget_ms > 0.0) {
            const double ratio = frame.lighting_ms / frame.budget_ms;
            worst_ratio = std::max(worst_ratio, ratio);
            over_budget += ratio > 1.0 ? 1 : 0;
        }
        for (const auto& [name, ms] : frame.pass_ms) {
            passes.insert(name);
        }
        for (const auto& [name, value] : frame.counters) {
            counters.insert(name);
        }
    }
    nlohmann::json report;
    report["info"] = info_;
    report["frames"] = frames_.size();
    report["frame_ms"] = distribution(frame_ms);
    nlohmann::json lighting = distribution(lighting_ms);
    lighting["budget_ms"] = frames_.empty() ? 0.0 : frames_.back().budget_ms;
    lighting["frames_over_budget"] = over_budget;
    lighting["worst_ratio_to_budget"] = worst_ratio;
    report["lighting_ms"] = lighting;
    nlohmann::json pass_report = nlohmann::json::object();
    for (const std::string& name : passes) {
        std::vector<double> values;
        for (const Frame& frame : frames_) {
            if (const auto found = frame.pass_ms.find(name); found != frame.pass_ms.end()) {
                values.push_back(found->second);
            }
        }
        pass_report[name] = distribution(values);
    }
    report["pass_ms"] = pass_report;
    nlohmann::json counter_report = nlohmann::json::object();
    for (const std::string& name : counters) {
        double total = 0.0;
        double last = 0.0;
        for (const Frame& frame : frames_) {
            if (const auto found = frame.counters.find(name); found != frame.counters.end()) {
                total += found->second;
                last = found->second;
            }
        }
        counter_report[name] = {
            {"total", total},
            {"per_frame", frames_.empty() ? 0.0 : total / static_cast<double>(frames_.size())},
            {"last", last}};
    }
    report["counters"] = counter_report;
    return report;
}

std::string RunReport::summary() const {
    const nlohmann::json report = to_json();
    char line[512];
    std::string text;
    std::snprintf(line, sizeof(line),
                  "%zu frames: frame %.2f ms median, %.2f ms p95; lighting %.2f ms median, "
                  "%.2f ms p95 against a %.2f ms budget (%zu frames over)\n",
                  frames_.size(), report["frame_ms"]["median"].get<double>(),
                  report["frame_ms"]["p95"].get<double>(),
                  report["lighting_ms"]["median"].get<double>(),
                  report["lighting_ms"]["p95"].get<double>(),
                  report["lighting_ms"]["budget_ms"].get<double>(),
                  report["lighting_ms"]["frames_over_budget"].get<std::size_t>());
    text += line;
    for (const auto& [name, values] : report["pass_ms"].items()) {
        std::snprintf(line, sizeof(line), "  pass %-14s %7.3f ms median, %7.3f ms p95\n",
                      name.c_str(), values["median"].get<double>(), values["p95"].get<double>());
        text += line;
    }
    for (const auto& [name, values] : report["counters"].items()) {
        std::snprintf(line, sizeof(line), "  %-24s %12.0f total, %10.1f per frame\n", name.c_str(),
                      values["total"].get<double>(), values["per_frame"].get<double>());
        text += line;
    }
    return text;
}

void RunReport::write(const std::filesystem::path& file) const {
    if (file.has_parent_path()) {
        std::error_code ignored;
        std::filesystem::create_directories(file.parent_path(), ignored);
    }
    std::ofstream out(file);
    if (!out) {
        throw Error("cannot write the report to " + file.string());
    }
    out << to_json().dump(2) << "\n";
    if (!out) {
        throw Error("writing the report to " + file.string() + " failed");
    }
}

}  // namespace luxel::sandbox
