// luxel-bench: the real-time path's light-map and image error against the reference, next to
// its cost (docs/METHOD.md §10, issue 11).
//   luxel-bench --level NAME|PATH [--budgets 1,2,4,8] [--frames N] [--after N] [--out DIR]
//               [--sweep KNOB=V1,V2 ...] [--change NODE:dx,dy,dz|auto|none] [--ref-* ...]
//               [--image WxH] [--image-spp N] [--camera x,y,z:tx,ty,tz:fov] [--no-image]
//               [--caustic-pixels]
// Writes CSV, JSON, PNG plots, frames and summary.md into DIR; references are cached in
// DIR/cache.

#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <new>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bench_config.hpp"
#include "bench_options.hpp"
#include "bench_run.hpp"
#include "level.hpp"
#include "luxel/runtime/cli.hpp"
#include "luxel/runtime/clock.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/runtime/tool_main.hpp"
#include "luxel/scene/load_limits_flag.hpp"
#include "luxel/scene/sky_flag.hpp"
#include "report.hpp"

namespace {

/// Checks --out before any work (a reference can take minutes): it must be a folder or
/// creatable as one. An earlier run's results there are replaced, as luxel-prep replaces its
/// output, and said so (its cached references in OUT/cache are what a second run is for).
/// Returns the files already in the folder.
std::vector<std::filesystem::path> prepare_out(const std::filesystem::path& out) {
    std::error_code error;
    if (std::filesystem::exists(out, error) && !std::filesystem::is_directory(out, error)) {
        throw luxel::Error(
            "--out " + out.string() +
            ": is a file, not a folder (results and the reference cache go in a folder)");
    }
    std::filesystem::create_directories(out, error);
    if (error) {
        throw luxel::Error("--out " + out.string() +
                           ": cannot create the folder: " + error.message());
    }
    std::vector<std::filesystem::path> present;
    for (const auto& entry : std::filesystem::directory_iterator(out, error)) {
        if (entry.is_regular_file(error)) {
            present.push_back(entry.path());
        }
    }
    if (std::find(present.begin(), present.end(), out / "results.json") != present.end()) {
        std::fprintf(stderr,
                     "luxel-bench: %s holds an earlier run's results: they will be replaced "
                     "(its cached references are reused)\n",
                     out.string().c_str());
    }
    return present;
}

using namespace luxel;

int run(int argc, char** argv) {
    CLI::App app{
        "luxel-bench: runs a level through the real-time lighting path under each "
        "configuration and budget, and measures its light maps (indirect and caustic relRMSE) "
        "and its frame (image relRMSE) against the reference integrator, its lighting ms per "
        "frame, and the frames it takes to recover after a scripted change."};
    bench::Options options;
    std::string budgets;
    std::string image_size;
    std::string camera_text;
    bool no_image = false;
    std::vector<std::string> sweeps;
    app.add_option("--level", options.level,
                   "a prepared level's name (assets/levels/prepared/NAME.glb) or a .glb path")
        ->required();
    app.add_option("--budgets", budgets, "lighting budgets in ms per frame (default 1,2,4,8)");
    app.add_option("--frames", options.frames, "static frames per configuration")
        ->capture_default_str();
    app.add_option("--animate", options.animate,
                   "frames of the level's animation played after the change; at every "
                   "checkpoint the light maps are compared with a reference of that instant "
                   "(one reference each: use a smaller --ref-photons)")
        ->capture_default_str();
    app.add_option("--after", options.after, "frames after the scripted change")
        ->capture_default_str();
    app.add_option("--checkpoint", options.checkpoint, "static frames between error checkpoints")
        ->capture_default_str();
    app.add_option("--out", options.out, "output directory (references cached in OUT/cache)")
        ->capture_default_str();
    app.add_option(
        "--sweep", sweeps,
        "KNOB=V1,V2,... (budget, photons GxM, aim_n, rays, texels_per_unit, filter, "
        "refine, local 0|1, change_blend SECONDS, exact 0|1, contact 0|1, stitch 0|1, "
        "aim_power 0|1, local_order 0|1, probes 0|1, probe_spacing METRES, probe_basis oct|sh2, "
        "unmapped 0|1, "
        "keep SIGMAS, "
        "caustics NxK, caustic_refine PHOTONS, stand_in 0|1, catch_up SHARE, "
        "backend cpu|gpu|gpu-turn|gpu-plane, kernel "
        "larsen|box|cone|world|layer, aa on|off, lightmap bilinear|bicubic, sky_edges "
        "on|off); repeatable, "
        "each varies one knob from the paper's configuration");
    app.add_option("--image", image_size,
                   "WIDTHxHEIGHT of the frames compared for the image error (default 160x120): "
                   "the real-time frame and a reference frame of the level's first camera");
    app.add_option("--camera", camera_text,
                   "x,y,z:tx,ty,tz:fov (position, target, vertical fov in degrees) of both "
                   "frames compared for the image error, as luxel-ref's --camera; default: the "
                   "level's first camera, else the default view");
    app.add_option("--image-spp", options.image.spp,
                   "path samples per pixel of the reference frame")
        ->capture_default_str();
    app.add_flag("--caustic-pixels", options.image.caustic_pixels,
                 "also the frame's caustic term alone against the reference's caustic at pixel "
                 "resolution (luxel-ref --caustic-pixels), over the pixels that see a diffuse "
                 "surface directly: the error a camera close to a caustic shows");
    app.add_flag("--no-image", no_image,
                 "leave the image error out (no frames rendered, no GL context unless "
                 "backend=gpu is swept)");
    app.add_option("--change", options.change,
                   "after the static frames: NODE:dx,dy,dz moves a node, NODE:turn=ax,ay,az,deg "
                   "turns it, NODE:off / NODE:on switch its light; auto: 'moving cube' by 0.3 m "
                   "in x when the level has it; none")
        ->capture_default_str();
    app.add_option("--no-light-map", options.unmapped,
                   "NODE: the node's mesh loses its light map and is lit as a receiver without "
                   "one (the irradiance probes); repeatable. The image error over such pixels is "
                   "reported apart (pixels without a light map)");
    app.add_option("--time", options.time, "animation pose in seconds (frozen)")
        ->capture_default_str();
    app.add_option("--dt", options.dt, "seconds per frame (the IIM fade-in runs on it)")
        ->capture_default_str();
    app.add_option("--ref-photons", options.reference.indirect_photons,
                   "reference: photons for the indirect component")
        ->capture_default_str();
    app.add_option("--ref-caustic-photons", options.reference.caustic_photons,
                   "reference: caustic photons")
        ->capture_default_str();
    app.add_option("--ref-spp", options.reference.spp, "reference: path samples per texel")
        ->capture_default_str();
    app.add_option("--ref-seed", options.reference.seed, "reference: seed")->capture_default_str();
    app.add_flag("--dump-maps", options.dump_maps,
                 "also write every run's per-texel light maps and reference to OUT/maps/");
    cli::add_threads(app, options.threads);
    cli::add_load_limits(app, options.load_limits);
    cli::add_sky(app, options.sky);
    prep::add_auto_prep_flags(app, options.auto_prep);
    if (!cli::parse(app, argc, argv)) {
        return 0;
    }
    cli::check_usage([&] {
        if (!budgets.empty()) {
            options.budgets = bench::parse_budgets(budgets);
        }
        if (!image_size.empty()) {
            if (no_image) {
                throw Error("--image " + image_size + " and --no-image: give one or the other");
            }
            bench::parse_image_size(image_size, options.image);
        }
        options.image.enabled = !no_image;
        if (no_image && options.image.caustic_pixels) {
            throw Error("--caustic-pixels and --no-image: the caustic frame is an image");
        }
        if (!camera_text.empty()) {
            if (no_image) {
                throw Error("--camera and --no-image: the camera is the compared frames'");
            }
            options.image.camera = ref::parse_camera(camera_text);
        }
        for (const std::string& s : sweeps) {
            options.sweeps.push_back(bench::parse_sweep(s));
        }
        if (options.change != "auto" && options.change != "none") {
            options.parsed_change = bench::parse_change(options.change);
        }
        bench::validate(options);
    });

    const std::filesystem::path file = ref::resolve_level(options.level);
    const std::vector<std::filesystem::path> previous = prepare_out(options.out);
    std::string command = "luxel-bench";
    for (int i = 1; i < argc; ++i) {
        command += std::string(" ") + argv[i];
    }
    bench::Bench bench(options, file);
    const std::vector<bench::BenchConfig> configs = bench::make_configs(options);
    std::fprintf(stderr, "luxel-bench: %s, %zu configurations\n", file.string().c_str(),
                 configs.size());
    Stopwatch clock;
    std::vector<bench::RunResult> runs;
    for (const bench::BenchConfig& config : configs) {
        std::fprintf(stderr, "luxel-bench: run %zu/%zu: %s @ %g ms (%s)\n", runs.size() + 1,
                     configs.size(), config.method.c_str(), config.budget_ms,
                     config.knobs().c_str());
        runs.push_back(bench.run(config));
    }
    bench::ReportInfo info;
    info.level = file.stem().string();
    info.command = command;
    info.change = bench.change();
    info.options = &options;
    info.gl = bench.gl_description();
    const auto files = bench::write_report(info, runs);
    std::fprintf(stderr, "luxel-bench: wrote %zu files to %s in %.1f s\n", files.size(),
                 options.out.string().c_str(), clock.elapsed_ms() / 1000.0);
    for (const std::filesystem::path& written : files) {
        if (std::find(previous.begin(), previous.end(), written) != previous.end()) {
            std::fprintf(stderr, "luxel-bench:   replaced: %s\n", written.string().c_str());
        }
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    return luxel::run_tool("luxel-bench", run, argc, argv);
}
