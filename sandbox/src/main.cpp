// luxel-sandbox: the main job. Until the sandbox level lands it draws the built-in lit test
// scene, headless by default, and writes the last frame as PNG (tone-mapped) and EXR (linear).

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "luxel/runtime/clock.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/runtime/gl_context.hpp"
#include "luxel/runtime/image.hpp"
#include "luxel/runtime/jobs.hpp"
#include "luxel/runtime/log.hpp"
#include "luxel/runtime/render_target.hpp"
#include "luxel/runtime/shader_library.hpp"
#include "present_pass.hpp"
#include "test_scene.hpp"

namespace {

struct Size {
    int width = 640;
    int height = 360;
};

constexpr int kMaxFramebufferSize = 16384;
constexpr double kHeadlessFrameSeconds = 1.0 / 30.0;  // fixed step: headless runs are repeatable

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

double percentile(std::vector<double> values, double q) {
    if (values.empty()) {
        return 0.0;
    }
    std::sort(values.begin(), values.end());
    const auto index = static_cast<std::size_t>(q * static_cast<double>(values.size() - 1) + 0.5);
    return values[std::min(index, values.size() - 1)];
}

struct Options {
    std::string gl = "auto";
    std::optional<int> frames;
    std::filesystem::path out = "out";
    Size size;
    int threads = 0;
    std::string log_level;
};

int run(const Options& options) {
    if (!options.log_level.empty()) {
        luxel::log::set_level(luxel::log::parse_level(options.log_level));
    }
    luxel::JobSystem jobs(options.threads);

    luxel::GlContextOptions context_options;
    context_options.backend = luxel::parse_backend(options.gl);
    context_options.width = options.size.width;
    context_options.height = options.size.height;
    context_options.window_title = "luxel sandbox";
    auto context = luxel::create_gl_context(context_options);
    const bool windowed = context->has_window();
    std::cout << "GL renderer: " << context->info().renderer << " | " << context->info().version
              << " | backend " << luxel::backend_name(context->backend()) << " | "
              << jobs.thread_count() << " job threads\n";

    const luxel::ShaderLibrary shaders;
    const luxel::sandbox::TestScene scene(shaders);
    const luxel::gl::RenderTarget target(options.size.width, options.size.height);
    std::optional<luxel::sandbox::PresentPass> present;
    if (windowed) {
        present.emplace(shaders);
    }
    const luxel::ToneMapSettings tone_map;

    // Headless runs a fixed number of frames; a window runs until closed unless --frames is given.
    const int frame_limit = options.frames.value_or(windowed ? -1 : 30);
    luxel::FrameClock frame_clock;
    std::vector<double> frame_ms;
    for (int frame = 0; frame_limit < 0 || frame < frame_limit; ++frame) {
        const luxel::FrameTime time = frame_clock.tick();
        const luxel::Stopwatch stopwatch;
        const double scene_time =
            windowed ? time.total_seconds : static_cast<double>(frame) * kHeadlessFrameSeconds;
        scene.render(target, scene_time);
        if (windowed) {
            present->draw(target.color(), context->framebuffer_width(),
                          context->framebuffer_height(), tone_map);
            context->swap_buffers();
            context->poll_events();
            if (context->should_close()) {
                break;
            }
        } else {
            glFinish();  // so the frame time includes the GPU work, not just its submission
        }
        frame_ms.push_back(stopwatch.elapsed_ms());
    }

    const luxel::Image frame = target.read_color();
    const auto png = options.out / "test_scene.png";
    const auto exr = options.out / "test_scene.exr";
    luxel::write_png(png, frame, tone_map);
    luxel::write_exr(exr, frame);
    std::printf("%zu frames at %dx%d: median %.2f ms, p95 %.2f ms per frame\nwrote %s and %s\n",
                frame_ms.size(), options.size.width, options.size.height, percentile(frame_ms, 0.5),
                percentile(frame_ms, 0.95), png.c_str(), exr.c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "luxel sandbox: renders the built-in lit test scene (headless by default when "
        "there is no display) and writes the last frame as PNG and EXR."};
    Options options;
    app.add_option("--gl", options.gl, "OpenGL backend")
        ->check(CLI::IsMember({"auto", "egl", "osmesa", "window"}))
        ->capture_default_str();
    app.add_option("--frames", options.frames,
                   "frames to render (default 30 headless, until closed in a window)")
        ->check(CLI::Range(1, 1'000'000));
    app.add_option("--out", options.out, "output directory for PNG and EXR files")
        ->capture_default_str();
    app.add_option_function<std::string>(
        "--size",
        [&](const std::string& text) {
            if (auto error = parse_size(text, options.size); !error.empty()) {
                throw CLI::ValidationError("--size", error);
            }
        },
        "framebuffer size WxH (default 640x360)");
    app.add_option("--threads", options.threads, "job threads (0 = all cores)")
        ->check(CLI::Range(0, 1024))
        ->capture_default_str();
    app.add_option("--log-level", options.log_level, "trace, debug, info, warn, error or off");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }
    try {
        return run(options);
    } catch (const luxel::Error& e) {
        std::cerr << "luxel-sandbox: error: " << e.what() << "\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "luxel-sandbox: internal error: " << e.what() << "\n";
        return 2;
    }
}
