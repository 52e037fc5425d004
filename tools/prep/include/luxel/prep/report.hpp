#pragma once

#include <cstdint>
#include <mutex>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "luxel/prep/geometry.hpp"
#include "luxel/prep/options.hpp"

namespace luxel::prep {

/// One mesh node's share of the result.
struct NodeSummary {
    std::string name;
    int node = -1;
    std::size_t triangles = 0;
    std::size_t surfaces = 0;
    std::size_t charts = 0;
    std::int64_t texels = 0;
    double area = 0.0;
    double texel_size = 0.0;  ///< metres, chosen per node (texel_density.hpp)
};

/// What luxel-prep did and how well: written as JSON (--report) and as a human summary.
struct PrepReport {
    std::string input;
    std::string output;
    PrepOptions options;
    std::size_t mesh_nodes = 0;      ///< nodes with a mesh
    std::size_t prepared_nodes = 0;  ///< of those, nodes that got a light map
    /// Of mesh_nodes, nodes whose mesh a skin deforms: they get no light map (a texel would not
    /// stay on one spot of the level) and are kept as they came, joints and weights included.
    std::size_t skinned_nodes = 0;
    std::size_t triangles = 0;       ///< light-mapped triangles kept
    std::size_t crease_surfaces = 0;
    /// Crease surfaces no viewpoint sees (hidden_faces.hpp), given coarser texels, and their
    /// area; why the test did not run, if it did not.
    std::size_t hidden_surfaces = 0;
    double hidden_area = 0.0;
    std::string visibility_skipped;
    double visibility_cell = 0.0;  ///< metres: the cells the test judged with (0: not judged)
    std::size_t surfaces = 0;
    std::size_t charts = 0;
    std::size_t planar_charts = 0;
    std::size_t conformal_charts = 0;
    std::int64_t texels = 0;  ///< texels covered by charts (padding excluded)
    int pages = 0;
    int page_size = 0;
    /// texels / (pages * page_size^2); 0 without pages.
    double efficiency = 0.0;
    /// Area stretch over all triangles (world area per texel / texel_size^2); the mean is
    /// area-weighted.
    double stretch_min = 0.0;
    double stretch_mean = 0.0;
    double stretch_max = 0.0;
    GeometryCounts repairs;
    std::vector<std::string> warnings;
    std::vector<std::pair<std::string, double>> stage_ms;  ///< in the order they ran
    std::vector<NodeSummary> nodes;

    void add_stage(std::string name, double milliseconds) {
        stage_ms.emplace_back(std::move(name), milliseconds);
    }
};

[[nodiscard]] nlohmann::json to_json(const PrepReport& report);
/// A few lines for a person: counts, pages, efficiency, stretch, warnings and stage times.
[[nodiscard]] std::string summary(const PrepReport& report);

/// Receives progress from any thread.
class Progress {
  public:
    virtual ~Progress() = default;
    virtual void update(std::string_view stage, std::size_t done, std::size_t total) = 0;
    virtual void finish() = 0;
};

/// A one-line progress bar on stderr, redrawn at most ten times a second; silent unless stderr
/// is a terminal (logs and pipes get no carriage returns).
class TerminalProgress final : public Progress {
  public:
    TerminalProgress();
    void update(std::string_view stage, std::size_t done, std::size_t total) override;
    void finish() override;
    [[nodiscard]] bool enabled() const { return enabled_; }

  private:
    bool enabled_;
    bool drawn_ = false;
    std::mutex mutex_;
    std::int64_t last_draw_ns_ = 0;
};

}  // namespace luxel::prep
