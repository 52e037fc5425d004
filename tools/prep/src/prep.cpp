#include "luxel/prep/prep.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <string>

#include "luxel/prep/hidden_faces.hpp"
#include "luxel/prep/output.hpp"
#include "luxel/prep/packing.hpp"
#include "luxel/prep/surfaces.hpp"
#include "luxel/prep/texel_density.hpp"
#include "luxel/runtime/clock.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/scene/portal.hpp"

namespace luxel::prep {
namespace {

/// The per-node state while the stages run.
struct NodeWork {
    int node = -1;
    double texel_size = 0.0;  ///< this node's (texel_density.hpp)
    /// Per crease surface, its texel size over the node's: hidden_texel_scale where no
    /// viewpoint sees it (hidden_faces.hpp), else 1.
    std::vector<double> crease_scale;
    NodeGeometry geometry;
    std::vector<CreaseSurface> crease_surfaces;
    std::vector<std::vector<Chart>> charts_per_crease;  ///< per crease surface
    std::vector<ChartingCounts> counts_per_crease;
};

/// Counts finished items of a stage for the progress bar.
class StageProgress {
  public:
    StageProgress(Progress* sink, const char* stage, std::size_t total)
        : sink_(sink), stage_(stage), total_(total) {
        if (sink_ != nullptr) {
            sink_->update(stage_, 0, total_);
        }
    }
    void step() {
        const std::size_t done = ++done_;
        if (sink_ != nullptr) {
            sink_->update(stage_, done, total_);
        }
    }

  private:
    Progress* sink_;
    const char* stage_;
    std::size_t total_;
    std::atomic<std::size_t> done_{0};
};

std::string node_label(const scene::Scene& scene, int node) {
    const std::string& name = scene.nodes[static_cast<std::size_t>(node)].name;
    return "node " + std::to_string(node) + (name.empty() ? "" : " '" + name + "'");
}

[[noreturn]] void too_many_texels(const std::string& what, double texels,
                                  const PrepOptions& options) {
    throw Error(what + " need about " + std::to_string(static_cast<long long>(texels)) +
                " light-map texels at --texel-size " + std::to_string(options.texel_size) +
                " m, more than the lightmap-texels limit of " +
                std::to_string(options.max_total_texels) +
                "; use a larger --texel-size (or --limit lightmap-texels=N)");
}

/// The triangles stage 1 copies (each mesh node's, once per node), checked before any copy is
/// made: a few thousand nodes sharing one large mesh would otherwise take gigabytes of
/// half-edge meshes before the texel limit could be checked on their area.
void check_triangles(const scene::Scene& input, const std::vector<NodeWork>& work,
                     const PrepOptions& options) {
    std::uint64_t triangles = 0;
    for (const NodeWork& w : work) {
        const int mesh = input.nodes[static_cast<std::size_t>(w.node)].mesh;
        for (const scene::Primitive& primitive :
             input.meshes[static_cast<std::size_t>(mesh)].primitives) {
            triangles += primitive.triangle_count();
        }
    }
    if (triangles > options.max_triangles) {
        throw Error(std::to_string(work.size()) + " mesh nodes draw " + std::to_string(triangles) +
                    " triangles, each node's copied by luxel-prep, more than the prep-triangles "
                    "limit of " +
                    std::to_string(options.max_triangles) + " (--limit prep-triangles=N)");
    }
}

/// Every surface becomes a primitive of at least kAccessorsPerSurface accessors: a file of
/// more than the loaders' `elements` limit would be refused by every tool that reads it, and
/// on the way would cost luxel-prep kilobytes of JSON a surface. Checked before packing.
void check_accessors(std::uint64_t surfaces, const PrepOptions& options) {
    if (surfaces * kAccessorsPerSurface > options.max_accessors) {
        throw Error(std::to_string(surfaces) + " light-mapped surfaces, each a primitive of " +
                    std::to_string(kAccessorsPerSurface) +
                    " or more accessors, are more than the elements limit of " +
                    std::to_string(options.max_accessors) +
                    " accessors a level may hold (--limit elements=N); every separate piece of "
                    "a mesh is a surface of its own");
    }
}

/// What the packer gets: every chart's rectangle, grouped by surface, and where each node's
/// charts are in that list.
struct PackInput {
    std::vector<PackChart> charts;
    std::vector<std::vector<int>> groups;
    std::vector<std::vector<int>> index_of_chart;  ///< per prepared node, per chart
};

/// Stage 1: a welded half-edge mesh per mesh node, in world space.
void build_all_geometry(const scene::Scene& input, const PrepOptions& options,
                        std::vector<NodeWork>& work, JobSystem& jobs, Progress* progress) {
    const std::vector<glm::mat4> world = input.world_matrices();
    StageProgress step(progress, "geometry", work.size());
    jobs.parallel_for(0, work.size(), [&](std::size_t i) {
        NodeWork& w = work[i];
        const scene::Node& node = input.nodes[static_cast<std::size_t>(w.node)];
        try {
            w.geometry = build_geometry(
                input.meshes[static_cast<std::size_t>(node.mesh)], input.materials,
                glm::dmat4(world[static_cast<std::size_t>(w.node)]), options.lightmap_specular);
        } catch (const Error& e) {
            throw Error(node_label(input, w.node) + ": " + e.what());
        }
        step.step();
    });
}

/// Stage 2: crease surfaces.
void find_all_crease_surfaces(const PrepOptions& options, std::vector<NodeWork>& work,
                              JobSystem& jobs, Progress* progress) {
    StageProgress step(progress, "surfaces", work.size());
    jobs.parallel_for(0, work.size(), [&](std::size_t i) {
        work[i].crease_surfaces = find_crease_surfaces(work[i].geometry, options.crease_degrees);
        work[i].charts_per_crease.resize(work[i].crease_surfaces.size());
        work[i].counts_per_crease.resize(work[i].crease_surfaces.size());
        step.step();
    });
}

/// Stage 2b: each node's texel size; then the texel limit, checked before any charting so
/// that a typo like --texel-size 0.00005 ends in a message, not in hours of work.
void choose_texel_sizes(const scene::Scene& input, const PrepOptions& options,
                        std::vector<NodeWork>& work) {
    std::vector<NodeExtent> extents;
    extents.reserve(work.size());
    for (const NodeWork& w : work) {
        NodeExtent& extent = extents.emplace_back();
        for (const CreaseSurface& surface : w.crease_surfaces) {
            extent.area += surface.area;
        }
        glm::dvec3 lo(std::numeric_limits<double>::max());
        glm::dvec3 hi(std::numeric_limits<double>::lowest());
        for (const Face& face : w.geometry.faces) {
            for (const int v : face.vertices) {
                lo = glm::min(lo, w.geometry.position(v));
                hi = glm::max(hi, w.geometry.position(v));
            }
        }
        extent.size = w.geometry.faces.empty() ? glm::dvec3(0.0) : hi - lo;
        extent.texel_scale = texel_scale_of(input.nodes[static_cast<std::size_t>(w.node)],
                                            node_label(input, w.node));
    }
    const std::vector<double> sizes = node_texel_sizes(extents, options);
    double texels = 0.0;
    double area = 0.0;
    for (std::size_t i = 0; i < work.size(); ++i) {
        work[i].texel_size = sizes[i];
        texels += extents[i].area / (sizes[i] * sizes[i]);
        area += extents[i].area;
    }
    if (texels > static_cast<double>(options.max_total_texels)) {
        too_many_texels("the scene's " + std::to_string(area) + " m^2", texels, options);
    }
}

/// Stage 2c: which crease surfaces no viewpoint sees; they get hidden_texel_scale times the
/// node's texel size.
void coarsen_hidden_surfaces(const scene::Scene& input, const PrepOptions& options,
                             std::vector<NodeWork>& work, PrepReport& report) {
    for (NodeWork& w : work) {
        w.crease_scale.assign(w.crease_surfaces.size(), 1.0);
    }
    if (options.hidden_texel_scale <= 1.0) {
        return;
    }
    std::vector<VisibilityTriangle> triangles;
    std::vector<std::pair<std::size_t, std::size_t>> surfaces;  // (work, crease surface)
    for (std::size_t i = 0; i < work.size(); ++i) {
        const NodeWork& w = work[i];
        const bool dynamic = input.is_dynamic(w.node);
        for (std::size_t s = 0; s < w.crease_surfaces.size(); ++s) {
            const auto id = static_cast<std::uint32_t>(surfaces.size());
            surfaces.emplace_back(i, s);
            for (const int f : w.crease_surfaces[s].faces) {
                const Face& face = w.geometry.faces[static_cast<std::size_t>(f)];
                triangles.push_back({w.geometry.position(face.vertices[0]),
                                     w.geometry.position(face.vertices[1]),
                                     w.geometry.position(face.vertices[2]), id, dynamic});
            }
        }
    }
    // Cells up to four texels: a doorway or a corridor stays open at that size.
    const Visibility visibility = find_seen_surfaces(triangles, surfaces.size(), viewpoints(input),
                                                     options.texel_size, 4.0 * options.texel_size);
    report.visibility_skipped = visibility.skipped;
    report.visibility_cell = visibility.cell_size;
    for (std::size_t k = 0; k < surfaces.size(); ++k) {
        if (!visibility.seen[k]) {
            NodeWork& w = work[surfaces[k].first];
            w.crease_scale[surfaces[k].second] = options.hidden_texel_scale;
            ++report.hidden_surfaces;
            report.hidden_area += w.crease_surfaces[surfaces[k].second].area;
        }
    }
}

/// The chart limits of one node: the level's, at the node's texel size.
ChartLimits node_limits(const ChartLimits& level, const PrepOptions& options, double texel_size) {
    ChartLimits limits = level;
    limits.texel_size = texel_size;
    limits.area_budget = options.surface_texel_budget * texel_size * texel_size;
    return limits;
}

/// Stage 3: charts, one task per crease surface (so one big mesh is still many tasks).
void build_all_charts(const scene::Scene& input, const PrepOptions& options,
                      const ChartLimits& limits, std::vector<NodeWork>& work, JobSystem& jobs,
                      Progress* progress) {
    std::vector<std::pair<std::size_t, std::size_t>> tasks;
    for (std::size_t i = 0; i < work.size(); ++i) {
        for (std::size_t s = 0; s < work[i].crease_surfaces.size(); ++s) {
            tasks.emplace_back(i, s);
        }
    }
    StageProgress step(progress, "charts", tasks.size());
    jobs.parallel_for(0, tasks.size(), [&](std::size_t t) {
        const auto [i, s] = tasks[t];
        NodeWork& w = work[i];
        try {
            w.charts_per_crease[s] =
                build_charts(w.geometry, w.crease_surfaces[s],
                             node_limits(limits, options, w.texel_size * w.crease_scale[s]),
                             &w.counts_per_crease[s]);
        } catch (const Error& e) {
            throw Error(node_label(input, w.node) + ": " + e.what());
        }
        step.step();
    });
}

/// Stage 4a: surfaces within the texel budget (and, on small pages, within what one page
/// holds), numbered in node order, and the packer's input.
PackInput assemble_surfaces(const PrepOptions& options, const ChartLimits& limits,
                            std::vector<NodeWork>& work, PrepResult& result) {
    PrepReport& report = result.report;
    PackInput pack;
    int next_id = 0;
    double padded_texels = 0.0;
    for (NodeWork& w : work) {
        report.repairs.faces += w.geometry.counts.faces;
        report.repairs.degenerate_faces += w.geometry.counts.degenerate_faces;
        report.repairs.non_manifold_faces += w.geometry.counts.non_manifold_faces;
        report.repairs.isolated_vertices += w.geometry.counts.isolated_vertices;
        report.repairs.faces_without_normals += w.geometry.counts.faces_without_normals;
        report.crease_surfaces += w.crease_surfaces.size();
        if (w.crease_surfaces.empty()) {
            continue;
        }
        PreparedNode prepared;
        prepared.node = w.node;
        prepared.texel_size = w.texel_size;
        for (std::size_t s = 0; s < w.crease_surfaces.size(); ++s) {
            const double area_budget =
                node_limits(limits, options, w.texel_size * w.crease_scale[s]).area_budget;
            std::vector<Chart>& charts = w.charts_per_crease[s];
            report.planar_charts += w.counts_per_crease[s].planar;
            report.conformal_charts += w.counts_per_crease[s].conformal;
            std::vector<std::vector<int>> chart_faces;
            std::vector<double> chart_area;
            std::vector<PackChart> chart_sizes;
            for (const Chart& chart : charts) {
                chart_faces.push_back(chart.faces);
                chart_area.push_back(chart.area);
                chart_sizes.push_back({chart.width, chart.height});
            }
            const auto first_chart = static_cast<int>(prepared.charts.size());
            for (const auto& group :
                 group_charts(w.geometry, chart_faces, chart_area, area_budget)) {
                for (const auto& run :
                     split_to_fit(chart_sizes, group, options.padding, limits.max_extent)) {
                    PreparedSurface surface;
                    surface.id = next_id++;
                    surface.material = w.crease_surfaces[s].material;
                    if (w.crease_scale[s] != 1.0) {
                        surface.texel_size = w.texel_size * w.crease_scale[s];
                    }
                    for (const int c : run) {
                        surface.charts.push_back(first_chart + c);
                        surface.area += charts[static_cast<std::size_t>(c)].area;
                    }
                    prepared.surfaces.push_back(std::move(surface));
                }
            }
            for (Chart& chart : charts) {
                prepared.charts.push_back(std::move(chart));
            }
        }
        std::vector<int>& index_of_chart = pack.index_of_chart.emplace_back(prepared.charts.size());
        for (const PreparedSurface& surface : prepared.surfaces) {
            std::vector<int> group;
            for (const int c : surface.charts) {
                const Chart& chart = prepared.charts[static_cast<std::size_t>(c)];
                index_of_chart[static_cast<std::size_t>(c)] = static_cast<int>(pack.charts.size());
                group.push_back(static_cast<int>(pack.charts.size()));
                pack.charts.push_back({chart.width, chart.height});
                padded_texels += static_cast<double>(chart.width + 2 * options.padding) *
                                 (chart.height + 2 * options.padding);
            }
            pack.groups.push_back(std::move(group));
        }
        prepared.geometry = std::move(w.geometry);
        result.nodes.push_back(std::move(prepared));
    }
    if (padded_texels > static_cast<double>(options.max_total_texels)) {
        too_many_texels("the charts with their padding", padded_texels, options);
    }
    check_accessors(pack.groups.size(), options);
    return pack;
}

/// Stage 5a: every chart moved to its page, with TEXCOORD_1 and coverage; then each surface's
/// page, rectangle and texels.
void place_all_charts(const PackInput& pack, const PackLayout& layout, PrepResult& result,
                      JobSystem& jobs, Progress* progress) {
    std::vector<std::pair<std::size_t, std::size_t>> slots;  // (node, chart)
    for (std::size_t n = 0; n < result.nodes.size(); ++n) {
        result.nodes[n].placed.resize(result.nodes[n].charts.size());
        for (std::size_t c = 0; c < result.nodes[n].charts.size(); ++c) {
            slots.emplace_back(n, c);
        }
    }
    StageProgress step(progress, "output", slots.size());
    jobs.parallel_for(0, slots.size(), [&](std::size_t i) {
        const auto [n, c] = slots[i];
        PreparedNode& node = result.nodes[n];
        const auto placement =
            layout.placements[static_cast<std::size_t>(pack.index_of_chart[n][c])];
        node.placed[c] = place_chart(node.charts[c], placement, layout.page_size);
        step.step();
    });
    for (PreparedNode& node : result.nodes) {
        for (PreparedSurface& surface : node.surfaces) {
            int x0 = std::numeric_limits<int>::max();
            int y0 = x0;
            int x1 = std::numeric_limits<int>::lowest();
            int y1 = x1;
            for (const int c : surface.charts) {
                const PlacedChart& placed = node.placed[static_cast<std::size_t>(c)];
                surface.page = placed.page;
                surface.texels += placed.texels;
                x0 = std::min(x0, placed.rect.x);
                y0 = std::min(y0, placed.rect.y);
                x1 = std::max(x1, placed.rect.x + placed.rect.width);
                y1 = std::max(y1, placed.rect.y + placed.rect.height);
            }
            surface.rect = {x0, y0, x1 - x0, y1 - y0};
        }
    }
}

/// The report's totals, per-node lines and warnings.
void summarize(const scene::Scene& input, const PackLayout& layout, PrepResult& result) {
    PrepReport& report = result.report;
    double stretch_sum = 0.0;
    double area_sum = 0.0;
    report.stretch_min = std::numeric_limits<double>::max();
    for (const PreparedNode& node : result.nodes) {
        NodeSummary summary;
        summary.node = node.node;
        summary.name = input.nodes[static_cast<std::size_t>(node.node)].name;
        summary.texel_size = node.texel_size;
        summary.triangles = node.geometry.faces.size();
        summary.surfaces = node.surfaces.size();
        summary.charts = node.charts.size();
        for (const PreparedSurface& surface : node.surfaces) {
            summary.texels += surface.texels;
            summary.area += surface.area;
        }
        for (const Chart& chart : node.charts) {
            report.stretch_min = std::min(report.stretch_min, chart.stretch_min);
            report.stretch_max = std::max(report.stretch_max, chart.stretch_max);
            stretch_sum += chart.stretch_area_sum;
            area_sum += chart.area;
        }
        report.triangles += summary.triangles;
        report.surfaces += summary.surfaces;
        report.charts += summary.charts;
        report.texels += summary.texels;
        report.nodes.push_back(std::move(summary));
    }
    report.stretch_mean = area_sum > 0.0 ? stretch_sum / area_sum : 0.0;
    if (area_sum == 0.0) {
        report.stretch_min = 0.0;
    }
    report.prepared_nodes = result.nodes.size();
    report.pages = result.page_count;
    report.page_size = result.page_size;
    report.efficiency = layout.page_texels() > 0 ? static_cast<double>(report.texels) /
                                                       static_cast<double>(layout.page_texels())
                                                 : 0.0;
    if (report.repairs.non_manifold_faces > 0) {
        report.warnings.push_back(std::to_string(report.repairs.non_manifold_faces) +
                                  " faces on non-manifold edges or vertices were split off "
                                  "through copies of their vertices");
    }
    if (report.repairs.degenerate_faces > 0) {
        report.warnings.push_back(std::to_string(report.repairs.degenerate_faces) +
                                  " zero-area faces were dropped");
    }
    if (report.mesh_nodes == 0) {
        report.warnings.emplace_back("the scene has no mesh nodes: nothing to prepare");
    }
}

}  // namespace

PrepResult prepare(const scene::Scene& input, const PrepOptions& options, JobSystem& jobs,
                   Progress* progress) {
    validate(options);
    silence_openmesh();
    PrepResult result;
    result.report.options = options;
    result.padding = options.padding;
    std::vector<NodeWork> work;
    for (std::size_t n = 0; n < input.nodes.size(); ++n) {
        const scene::Node& node = input.nodes[n];
        // A portal is an opening, not a surface: it gets no light map. Nor does a skinned
        // mesh: its surface moves over itself as it deforms, so no texel stays on one spot.
        if (node.mesh < 0 || scene::is_portal(node)) {
            continue;
        }
        if (node.skin >= 0) {
            ++result.report.skinned_nodes;
        } else {
            work.emplace_back().node = static_cast<int>(n);
        }
    }
    result.report.mesh_nodes = work.size() + result.report.skinned_nodes;

    check_triangles(input, work, options);
    Stopwatch stage;
    build_all_geometry(input, options, work, jobs, progress);
    result.report.add_stage("geometry", stage.elapsed_ms());

    stage.restart();
    find_all_crease_surfaces(options, work, jobs, progress);
    choose_texel_sizes(input, options, work);
    coarsen_hidden_surfaces(input, options, work, result.report);
    result.report.add_stage("surfaces", stage.elapsed_ms());

    stage.restart();
    ChartLimits limits;
    limits.texel_size = options.texel_size;
    limits.max_stretch = options.max_stretch;
    limits.area_budget = options.surface_texel_budget * options.texel_size * options.texel_size;
    limits.max_extent = options.page_size > 0 ? options.page_size : options.auto_page_limit;
    limits.padding = options.padding;
    build_all_charts(input, options, limits, work, jobs, progress);
    result.report.add_stage("charts", stage.elapsed_ms());

    stage.restart();
    const PackInput pack = assemble_surfaces(options, limits, work, result);
    if (progress != nullptr) {
        progress->update("packing", 0, 1);
    }
    const PackLayout layout =
        options.page_size > 0
            ? pack_fixed(pack.charts, pack.groups, options.padding, options.page_size)
            : pack_automatic(pack.charts, pack.groups, options.padding, options.auto_page_limit,
                             &jobs);
    // The pages are what the loaders count (and what the page pictures allocate): charts
    // within the limit can still need more pages than it allows once packed.
    const auto page_texels = static_cast<double>(layout.page_texels());
    if (page_texels > static_cast<double>(options.max_total_texels)) {
        too_many_texels("the packed pages (" + std::to_string(layout.page_count) + " of " +
                            std::to_string(layout.page_size) + "^2)",
                        page_texels, options);
    }
    result.page_size = layout.page_size;
    result.page_count = layout.page_count;
    result.report.add_stage("packing", stage.elapsed_ms());

    stage.restart();
    place_all_charts(pack, layout, result, jobs, progress);
    summarize(input, layout, result);
    result.scene =
        build_output_scene(input, result.nodes, result.page_size, result.report.warnings);
    result.report.add_stage("output", stage.elapsed_ms());
    if (progress != nullptr) {
        progress->finish();
    }
    return result;
}

}  // namespace luxel::prep
