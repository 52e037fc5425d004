// luxel-sandbox: the main job. Runs a level (the sandbox game level by default) the way a game
// would: ECS game systems, LightingSystem::update within a budget, FrameRenderer. Headless by
// default when there is no display (a scripted camera, PNG frames and a JSON report), or in a
// GLFW window with a free camera and a Dear ImGui panel.

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "luxel/runtime/cli.hpp"
#include "luxel/runtime/clock.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/runtime/gl_context.hpp"
#include "luxel/runtime/image.hpp"
#include "luxel/runtime/jobs.hpp"
#include "luxel/runtime/log.hpp"
#include "luxel/runtime/render_target.hpp"
#include "luxel/runtime/shader_library.hpp"
#include "luxel/runtime/tool_main.hpp"
#include "luxel/scene/load_limits_flag.hpp"
#include "luxel/scene/sky_flag.hpp"
#include "runs.hpp"
#include "sandbox_level.hpp"

namespace {

struct Size {
    int width = 640;
    int height = 360;
};

constexpr int kMaxFramebufferSize = 16384;

/// Parses "WxH"; returns an error message for CLI11, empty when valid.
std::string parse_size(const std::string& text, Size& size) {
    const auto x = text.find('x');
    auto parse_int = [](std::string_view digits, int& value) {
        const auto* end = digits.data() + digits.size();
        const auto result = std::from_chars(digits.data(), end, value);
        return result.ec == std::errc() && result.ptr == end;
    };
    Size parsed;
    if (x == std::string::npos || !parse_int(std::string_view(text).substr(0, x), parsed.width) ||
        !parse_int(std::string_view(text).substr(x + 1), parsed.height)) {
        return "expected WxH such as 640x360, got '" + text + "'";
    }
    if (parsed.width < 1 || parsed.height < 1 || parsed.width > kMaxFramebufferSize ||
        parsed.height > kMaxFramebufferSize) {
        return "each side must be within 1.." + std::to_string(kMaxFramebufferSize) + ", got '" +
               text + "'";
    }
    size = parsed;
    return {};
}

/// "direct,indirect,caustics,specular,emission" (any subset, or "all").
std::string parse_terms(const std::string& text, luxel::renderer::FrameTerms& terms) {
    luxel::renderer::FrameTerms parsed{false, false, false, false, false};
    std::size_t start = 0;
    while (start <= text.size()) {
        const std::size_t comma = std::min(text.find(',', start), text.size());
        const std::string term = text.substr(start, comma - start);
        if (term == "all") {
            parsed = {};
        } else if (term == "direct") {
            parsed.direct = true;
        } else if (term == "indirect") {
            parsed.indirect = true;
        } else if (term == "caustics") {
            parsed.caustics = true;
        } else if (term == "specular") {
            parsed.specular = true;
        } else if (term == "emission") {
            parsed.emission = true;
        } else {
            return "unknown lighting term '" + term +
                   "' (expected all, direct, indirect, caustics, specular, emission)";
        }
        start = comma + 1;
    }
    terms = parsed;
    return {};
}

int run(int argc, char** argv) {
    CLI::App app{
        "luxel sandbox: runs a level with moving objects through the lighting system, headless "
        "(the default when there is no display) or in a window."};
    luxel::sandbox::RunOptions options;
    std::string level_names;
    for (const auto& name : luxel::sandbox::level_names()) {
        level_names += (level_names.empty() ? "" : ", ") + name;
    }
    app.add_option(
           "--level", options.app.level,
           "a built-in level (" + level_names +
               ") or a .glb/.gltf file (prepared at load if luxel-prep never was run on it)")
        ->capture_default_str();
    app.add_option("--gl", options.gl, "OpenGL backend")
        ->check(CLI::IsMember({"auto", "egl", "osmesa", "window"}))
        ->capture_default_str();
    app.add_option("--frames", options.frames,
                   "frames to run (default 150 headless, until closed in a window)")
        ->check(CLI::Range(1, 10'000'000));
    app.add_option("--budget-ms", options.app.budget_ms,
                   "lighting budget per frame in milliseconds (0 pauses lighting)")
        ->check(CLI::Range(0.0, 10'000.0))
        ->capture_default_str();
    app.add_option("--warm-up-ms", options.app.warm_up_ms,
                   "lighting warm-up at load, like a loading screen (0: start unlit)")
        ->check(CLI::Range(0.0, 1e7))
        ->capture_default_str();
    app.add_option("--out", options.out, "output directory for frames, screenshots and the report")
        ->capture_default_str();
    app.add_option("--report", options.report, "JSON report file (default <out>/report.json)");
    app.add_option("--camera", options.camera,
                   "headless camera: the level's scripted path, or fixed at its start")
        ->check(CLI::IsMember({"path", "fixed"}))
        ->capture_default_str();
    app.add_option("--camera-at", options.camera_at,
                   "with --camera fixed: the time (s) along the path the camera stays at")
        ->check(CLI::Range(0.0, 1e6))
        ->capture_default_str();
    app.add_option("--exposure", options.exposure,
                   "display exposure for PNG and the window (0: automatic)")
        ->check(CLI::Range(0.0, 1e9))
        ->capture_default_str();
    app.add_flag("--exr", options.exr, "also write every frame as linear EXR");
    app.add_option("--png-every", options.png_every,
                   "write every n-th frame as PNG (0: only the last)")
        ->check(CLI::Range(0, 1'000'000))
        ->capture_default_str();
    app.add_option_function<std::string>(
        "--terms",
        [&](const std::string& text) {
            if (auto error = parse_terms(text, options.terms); !error.empty()) {
                throw CLI::ValidationError("--terms", error);
            }
        },
        "lighting terms to draw, comma-separated: direct, indirect, caustics, specular, "
        "emission, or all (default all)");
    app.add_option_function<std::string>(
           "--aa", [&](const std::string& text) { options.app.anti_aliasing = text == "on"; },
           "anti-aliasing of the frame's geometric edges (docs/METHOD.md 8.4)")
        ->check(CLI::IsMember({"on", "off"}))
        ->default_str("on");
    app.add_option_function<std::string>(
           "--soft-shadows",
           [&](const std::string& text) { options.app.soft_shadows = text == "on"; },
           "soft shadows of lights with a radius (extras.luxel.light_radius; docs/METHOD.md "
           "8.8); off: every shadow hard")
        ->check(CLI::IsMember({"on", "off"}))
        ->default_str("on");
    app.add_option_function<std::string>(
           "--lightmap-filter",
           [&](const std::string& text) { options.app.bicubic_light_maps = text == "bicubic"; },
           "how light maps are read: bilinear, or bicubic (a cubic B-spline: smoother, slightly "
           "blurred; levels prepared with luxel-prep --padding 2 suit it best)")
        ->check(CLI::IsMember({"bilinear", "bicubic"}))
        ->default_str("bilinear");
    app.add_option_function<std::string>(
           "--sky-edges", [&](const std::string& text) { options.app.sky_edges = text == "on"; },
           "where the level has a sky, mix sky and surfaces at their silhouettes by coverage "
           "(docs/METHOD.md 8.6)")
        ->check(CLI::IsMember({"on", "off"}))
        ->default_str("on");
    Size size;
    app.add_option_function<std::string>(
        "--size",
        [&](const std::string& text) {
            if (auto error = parse_size(text, size); !error.empty()) {
                throw CLI::ValidationError("--size", error);
            }
        },
        "framebuffer size WxH (default 640x360)");
    luxel::cli::add_threads(app, options.app.threads);
    luxel::cli::add_log_level(app);
    luxel::cli::add_load_limits(app, options.app.load_limits);
    luxel::cli::add_sky(app, options.app.sky);
    luxel::prep::add_auto_prep_flags(app, options.app.auto_prep);
    if (!luxel::cli::parse(app, argc, argv)) {
        return 0;
    }
    options.app.width = size.width;
    options.app.height = size.height;
    // Fail on a bad level before starting GL: the message should be about the level.
    (void)luxel::sandbox::resolve_level(options.app.level);
    luxel::JobSystem jobs(options.app.threads);
    luxel::GlContextOptions context_options;
    context_options.backend = luxel::parse_backend(options.gl);
    context_options.width = size.width;
    context_options.height = size.height;
    context_options.window_title = "luxel sandbox";
    auto context = luxel::create_gl_context(context_options);
    return context->has_window() ? luxel::sandbox::run_window(options, jobs, *context)
                                 : luxel::sandbox::run_headless(options, jobs, *context);
}

}  // namespace

int main(int argc, char** argv) {
    return luxel::run_tool("luxel-sandbox", run, argc, argv);
}
