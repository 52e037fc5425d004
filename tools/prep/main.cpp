// luxel-prep: splits meshes into surfaces and packs light-map texels.
//   luxel-prep INPUT.gltf|.glb -o OUTPUT.glb [--texel-size METRES] [--crease-deg A]
//              [--padding TEXELS] [--page-size N] [--report FILE.json] [--threads N]
// Writes OUTPUT with TEXCOORD_1 and a surface table per mesh node, prints a summary, and
// writes one PNG per light-map page next to the report (or next to OUTPUT without --report).

#include <exception>
#include <filesystem>
#include <iostream>
#include <new>
#include <span>
#include <string>
#include <system_error>
#include <vector>

#include <CLI/CLI.hpp>

#include "luxel/prep/page_images.hpp"
#include "luxel/prep/prep.hpp"
#include "luxel/prep/sky_map.hpp"
#include "luxel/runtime/cli.hpp"
#include "luxel/runtime/clock.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/runtime/jobs.hpp"
#include "luxel/runtime/pending_file.hpp"
#include "luxel/runtime/tool_main.hpp"
#include "luxel/scene/gltf.hpp"
#include "luxel/scene/load_limits_flag.hpp"

namespace {

/// The files a run writes besides the page pictures: the output, its .bin when it is a .gltf,
/// and the report.
std::vector<std::filesystem::path> outputs_of(const std::filesystem::path& output,
                                              const std::filesystem::path& report) {
    std::vector<std::filesystem::path> outputs{output};
    if (output.extension() == ".gltf") {
        outputs.push_back(std::filesystem::path(output).replace_extension(".bin"));
    }
    if (!report.empty()) {
        outputs.push_back(report);
    }
    return outputs;
}

/// Refuses, before any work, to write over the input or a file it reads (its .bin, its
/// images), and an output whose folder does not exist.
void check_outputs(const std::vector<std::filesystem::path>& outputs,
                   const std::vector<std::filesystem::path>& inputs) {
    for (const auto& output : outputs) {
        std::error_code error;
        for (const auto& input : inputs) {
            if (std::filesystem::equivalent(output, input, error)) {
                throw luxel::UsageError(output.string() + ": is the input " + input.string() +
                                        " (or a file it reads); write the output elsewhere");
            }
        }
        const std::filesystem::path folder =
            output.has_parent_path() ? output.parent_path() : std::filesystem::path(".");
        if (output == outputs.front() && !std::filesystem::is_directory(folder, error)) {
            throw luxel::Error(output.string() + ": the folder " + folder.string() +
                               " does not exist");
        }
    }
}

/// Where the page pictures go: beside the report, named after it, or beside the output.
std::filesystem::path image_stem(const std::filesystem::path& output,
                                 const std::filesystem::path& report) {
    const std::filesystem::path& anchor = report.empty() ? output : report;
    return anchor.parent_path() / anchor.stem();
}

int run(int argc, char** argv) {
    CLI::App app{
        "luxel-prep: splits meshes into surfaces (crease angle and material), gives them a "
        "light-map parameterization at a texel size that fits each object, packs the charts into "
        "light-map "
        "pages and writes the scene back with TEXCOORD_1 and a surface table."};
    luxel::prep::PrepOptions options;
    std::filesystem::path input;
    std::filesystem::path output;
    std::filesystem::path report_file;
    app.add_option("input", input, "the scene to prepare (.gltf or .glb)")->required();
    app.add_option("-o,--output", output, "the prepared scene (.glb or .gltf)")->required();
    app.add_option("--texel-size", options.texel_size, "metres per light-map texel")
        ->capture_default_str();
    app.add_option("--min-texels-across", options.min_texels_across,
                   "texels a prop's width keeps at least (its texels made finer, down to an "
                   "eighth of --texel-size; 0: off)")
        ->capture_default_str();
    app.add_option("--texel-budget", options.texel_budget,
                   "texels the whole level may have; above it every object's texels grow by one "
                   "factor (0: no budget)")
        // CLI11 reads "-5" into an unsigned number by wrapping it: the range refuses that.
        ->check(CLI::Range(std::uint64_t{0}, luxel::prep::kMaxTexelBudget))
        ->capture_default_str();
    app.add_option("--hidden-texel-scale", options.hidden_texel_scale,
                   "texels of surfaces no camera or light can see (the outside of a closed "
                   "level, faces against other geometry) are this many times larger (1: off)")
        ->capture_default_str();
    app.add_option("--crease-deg", options.crease_degrees,
                   "faces whose normals differ by less than this share a surface")
        ->capture_default_str();
    app.add_option("--padding", options.padding, "texels of gutter around every chart")
        ->capture_default_str();
    app.add_option("--page-size", options.page_size,
                   "texels per light-map page edge (0: the size that wastes least)")
        ->capture_default_str();
    app.add_option("--report", report_file,
                   "write the report as JSON here (page PNGs go beside it)");
    luxel::cli::add_threads(app, options.threads);
    luxel::scene::LoadOptions load_limits;
    luxel::cli::add_load_limits(app, load_limits);
    if (!luxel::cli::parse(app, argc, argv)) {
        return 0;
    }

    // What the loaders allow is what luxel-prep may write, and bounds the copies it makes.
    options.max_total_texels = load_limits.max_lightmap_texels;
    options.max_triangles = load_limits.max_prep_triangles;
    options.max_accessors = load_limits.max_array_elements;
    luxel::cli::check_usage([&] { luxel::prep::validate(options); });
    const std::vector<std::filesystem::path> outputs = outputs_of(output, report_file);
    check_outputs(outputs, {input});
    luxel::JobSystem jobs(options.threads);
    luxel::Stopwatch stopwatch;
    const luxel::scene::Scene scene = luxel::scene::load_gltf(input, load_limits);
    check_outputs(outputs, scene.report.external_files);
    const double load_ms = stopwatch.elapsed_ms();
    std::vector<std::filesystem::path> replaced;
    for (const auto& file : outputs) {
        std::error_code ignored;
        if (std::filesystem::exists(file, ignored)) {
            replaced.push_back(file);
        }
    }

    luxel::prep::TerminalProgress progress;
    luxel::prep::PrepResult result;
    try {
        result = luxel::prep::prepare(scene, options, jobs, &progress);
    } catch (const luxel::Error& e) {
        progress.finish();
        throw luxel::Error(input.string() + ": " + e.what());
    }
    luxel::prep::PrepReport& report = result.report;
    report.input = input.string();
    report.output = output.string();
    report.stage_ms.insert(report.stage_ms.begin(), {"load", load_ms});

    std::filesystem::path sky_map;
    if (result.scene.sky.kind == luxel::scene::SkySpec::Kind::Map &&
        result.scene.sky.map.is_absolute()) {
        // The level's map, resolved at load in its folder: named again relative to the output.
        result.scene.sky.map = luxel::prep::place_sky_map(result.scene.sky.map, output);
        sky_map = output.parent_path() / result.scene.sky.map;
    }

    stopwatch.restart();
    luxel::scene::save_gltf(result.scene, output);
    report.add_stage("save", stopwatch.elapsed_ms());

    stopwatch.restart();
    const auto images = luxel::prep::write_page_images(result, image_stem(output, report_file));
    report.add_stage("images", stopwatch.elapsed_ms());

    if (!report_file.empty()) {
        // Like the page pictures beside it, the report may go to a directory yet to be made.
        std::error_code ignored;
        if (report_file.has_parent_path()) {
            std::filesystem::create_directories(report_file.parent_path(), ignored);
        }
        const std::string text = luxel::prep::to_json(report).dump(2) + "\n";
        luxel::write_file_atomically(report_file, std::as_bytes(std::span(text)));
    }
    std::cout << luxel::prep::summary(report);
    for (const auto& file : replaced) {
        std::cout << "  replaced: " << file.string() << "\n";
    }
    for (const auto& image : images) {
        std::cout << "  page picture: " << image.string() << "\n";
    }
    if (!sky_map.empty()) {
        std::cout << "  sky map: " << sky_map.string() << "\n";
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return luxel::run_tool("luxel-prep", run, argc, argv);
}
