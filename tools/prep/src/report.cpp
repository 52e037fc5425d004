#include "luxel/prep/report.hpp"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <iomanip>
#include <sstream>

namespace luxel::prep {

nlohmann::json to_json(const PrepReport& report) {
    nlohmann::json stages = nlohmann::json::object();
    double total = 0.0;
    for (const auto& [name, ms] : report.stage_ms) {
        stages[name] = ms;
        total += ms;
    }
    nlohmann::json nodes = nlohmann::json::array();
    for (const NodeSummary& node : report.nodes) {
        nodes.push_back({{"node", node.node},
                         {"name", node.name},
                         {"triangles", node.triangles},
                         {"surfaces", node.surfaces},
                         {"charts", node.charts},
                         {"texels", node.texels},
                         {"area", node.area},
                         {"texel_size", node.texel_size}});
    }
    const PrepOptions& o = report.options;
    return {
        {"input", report.input},
        {"output", report.output},
        {"options",
         {{"texel_size", o.texel_size},
          {"min_texels_across", o.min_texels_across},
          {"texel_budget", o.texel_budget},
          {"hidden_texel_scale", o.hidden_texel_scale},
          {"crease_deg", o.crease_degrees},
          {"padding", o.padding},
          {"page_size", o.page_size == 0 ? nlohmann::json("auto") : nlohmann::json(o.page_size)},
          {"surface_texel_budget", o.surface_texel_budget},
          {"max_stretch", o.max_stretch},
          {"threads", o.threads}}},
        {"mesh_nodes", report.mesh_nodes},
        {"prepared_nodes", report.prepared_nodes},
        {"skinned_nodes", report.skinned_nodes},
        {"triangles", report.triangles},
        {"crease_surfaces", report.crease_surfaces},
        {"hidden_surfaces",
         {{"count", report.hidden_surfaces},
          {"area", report.hidden_area},
          {"cell", report.visibility_cell},
          {"not_judged", report.visibility_skipped}}},
        {"surfaces", report.surfaces},
        {"charts",
         {{"total", report.charts},
          {"planar", report.planar_charts},
          {"conformal", report.conformal_charts}}},
        {"texels", report.texels},
        {"pages", report.pages},
        {"page_size", report.page_size},
        {"packing_efficiency", report.efficiency},
        {"stretch",
         {{"min", report.stretch_min}, {"mean", report.stretch_mean}, {"max", report.stretch_max}}},
        {"repairs",
         {{"degenerate_faces_dropped", report.repairs.degenerate_faces},
          {"non_manifold_faces_split", report.repairs.non_manifold_faces},
          {"isolated_vertices_dropped", report.repairs.isolated_vertices},
          {"faces_with_computed_normals", report.repairs.faces_without_normals}}},
        {"warnings", report.warnings},
        {"stage_ms", stages},
        {"total_ms", total},
        {"nodes", nodes},
    };
}

std::string summary(const PrepReport& report) {
    std::ostringstream out;
    out << std::fixed;
    out << report.input << " -> " << report.output << "\n";
    out << "  " << report.prepared_nodes << " of " << report.mesh_nodes
        << " mesh nodes light-mapped, " << report.triangles << " triangles\n";
    if (report.skinned_nodes > 0) {
        out << "  " << report.skinned_nodes << " skinned mesh node"
            << (report.skinned_nodes == 1 ? "" : "s")
            << " kept without a light map (a skin deforms them)\n";
    }
    out << "  " << report.surfaces << " surfaces (" << report.crease_surfaces
        << " before the texel budget), " << report.charts << " charts (" << report.planar_charts
        << " planar, " << report.conformal_charts << " conformal)\n";
    out << "  " << report.texels << " texels of " << std::setprecision(3)
        << report.options.texel_size << " m on " << report.pages << " page"
        << (report.pages == 1 ? "" : "s") << " of " << report.page_size << "^2, packing efficiency "
        << std::setprecision(1) << 100.0 * report.efficiency << "%\n";
    if (!report.visibility_skipped.empty()) {
        out << "  hidden surfaces not judged: " << report.visibility_skipped << "\n";
    } else if (report.hidden_surfaces > 0) {
        out << "  " << report.hidden_surfaces << " surfaces no camera or light sees ("
            << std::setprecision(2) << report.hidden_area << " m^2) got texels "
            << std::setprecision(0) << report.options.hidden_texel_scale << "x larger\n";
    }
    out << "  stretch min " << std::setprecision(3) << report.stretch_min << ", mean "
        << report.stretch_mean << ", max " << report.stretch_max << " (bound "
        << report.options.max_stretch << ")\n";
    const GeometryCounts& r = report.repairs;
    if (r.degenerate_faces + r.non_manifold_faces + r.isolated_vertices + r.faces_without_normals >
        0) {
        out << "  repaired: " << r.degenerate_faces << " degenerate faces dropped, "
            << r.non_manifold_faces << " non-manifold faces split off, " << r.isolated_vertices
            << " isolated vertices dropped, " << r.faces_without_normals
            << " faces given computed normals\n";
    }
    for (const auto& warning : report.warnings) {
        out << "  warning: " << warning << "\n";
    }
    out << "  time:";
    double total = 0.0;
    for (const auto& [name, ms] : report.stage_ms) {
        out << " " << name << " " << std::setprecision(1) << ms << " ms,";
        total += ms;
    }
    out << " total " << std::setprecision(1) << total << " ms\n";
    return out.str();
}

TerminalProgress::TerminalProgress() : enabled_(isatty(STDERR_FILENO) == 1) {}

void TerminalProgress::update(std::string_view stage, std::size_t done, std::size_t total) {
    if (!enabled_) {
        return;
    }
    const std::int64_t now = std::chrono::duration_cast<std::chrono::nanoseconds>(
                                 std::chrono::steady_clock::now().time_since_epoch())
                                 .count();
    std::lock_guard lock(mutex_);
    if (done < total && now - last_draw_ns_ < 100'000'000) {
        return;
    }
    last_draw_ns_ = now;
    constexpr int kWidth = 30;
    const double fraction =
        total == 0 ? 1.0 : static_cast<double>(done) / static_cast<double>(total);
    const int filled = static_cast<int>(fraction * kWidth);
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(kWidth, '.');
    std::fprintf(stderr, "\r\033[Kluxel-prep [%s] %-9.*s %zu/%zu", bar.c_str(),
                 static_cast<int>(stage.size()), stage.data(), done, total);
    std::fflush(stderr);
    drawn_ = true;
}

void TerminalProgress::finish() {
    std::lock_guard lock(mutex_);
    if (enabled_ && drawn_) {
        std::fprintf(stderr, "\r\033[K");
        std::fflush(stderr);
        drawn_ = false;
    }
}

}  // namespace luxel::prep
