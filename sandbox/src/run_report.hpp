#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace luxel::sandbox {

/// What a sandbox run measured, frame by frame, and its summary: the JSON report of --report
/// and the text printed at the end of a headless run.
class RunReport {
  public:
    /// Facts about the run (level, GL renderer, backend, size...), copied into the report.
    void set_info(const std::string& key, const nlohmann::json& value);

    struct Frame {
        double frame_ms = 0.0;     ///< the whole frame (CPU, GPU finished)
        double lighting_ms = 0.0;  ///< LightingSystem::update
        double budget_ms = 0.0;
        std::map<std::string, double> pass_ms;   ///< GPU time per render pass
        std::map<std::string, double> counters;  ///< photons traced, texels gathered, ...
    };
    void add_frame(Frame frame);

    [[nodiscard]] std::size_t frame_count() const { return frames_.size(); }
    /// Every field: info, frames, frame time (median, p95, max), lighting time (median, p95,
    /// max, and over budget: frames and worst ratio), per-pass times (median, p95) and counters
    /// (total, per frame mean, last).
    [[nodiscard]] nlohmann::json to_json() const;
    /// A few lines for stdout.
    [[nodiscard]] std::string summary() const;
    /// Writes to_json() to `file`; throws luxel::Error naming the file when it cannot.
    void write(const std::filesystem::path& file) const;

  private:
    nlohmann::json info_ = nlohmann::json::object();
    std::vector<Frame> frames_;
};

/// The q-quantile (0..1) of `values` by the nearest rank; 0 for none.
[[nodiscard]] double quantile(std::vector<double> values, double q);

}  // namespace luxel::sandbox
