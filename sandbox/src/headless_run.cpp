#include <cstdio>
#include <iostream>

#include "exposure.hpp"
#include "luxel/runtime/clock.hpp"
#include "luxel/runtime/error.hpp"
#include "luxel/runtime/gl.hpp"
#include "luxel/runtime/image.hpp"
#include "runs.hpp"

namespace luxel::sandbox {
namespace {

constexpr double kStep = 1.0 / 30.0;  // fixed: headless runs are repeatable

std::string frame_name(int frame, const char* extension) {
    char name[64];
    std::snprintf(name, sizeof(name), "frame_%04d.%s", frame, extension);
    return name;
}

}  // namespace

int run_headless(const RunOptions& options, JobSystem& jobs, GlContext& context) {
    std::error_code error;
    std::filesystem::create_directories(options.out, error);
    if (error || !std::filesystem::is_directory(options.out)) {
        throw Error("cannot create the output directory " + options.out.string() + ": " +
                    error.message());
    }
    const ShaderLibrary shaders;
    SandboxApp app(options.app, jobs, shaders);
    app.renderer().set_terms(options.terms);
    RunReport report;
    report.set_info("level", app.level_name());
    report.set_info("level_file", app.level_file().string());
    report.set_info("gl_renderer", context.info().renderer);
    report.set_info("gl_version", context.info().version);
    report.set_info("gl_backend", std::string(backend_name(context.backend())));
    report.set_info("size", {options.app.width, options.app.height});
    report.set_info("threads", jobs.thread_count());
    report.set_info("budget_ms", options.app.budget_ms);
    report.set_info("step_seconds", kStep);
    report.set_info("warm_up_ms", app.warm_up_ms());

    const int frames = options.frames.value_or(150);
    AutoExposure exposure;
    float last_exposure = 1.0f;
    const float aspect =
        static_cast<float>(options.app.width) / static_cast<float>(options.app.height);
    std::cout << "luxel-sandbox: level '" << app.level_name() << "', " << frames
              << " frames headless at " << options.app.width << "x" << options.app.height
              << ", lighting budget " << options.app.budget_ms << " ms, GL "
              << context.info().renderer << "\n";
    for (int frame = 0; frame < frames; ++frame) {
        const double time = frame * kStep;
        const CameraPose pose =
            app.camera_path().at(options.camera == "fixed" ? options.camera_at : time);
        const renderer::FrameCamera camera = renderer::FrameCamera::look_at(
            pose.eye, pose.target, glm::vec3(0.0f, 1.0f, 0.0f), pose.vertical_fov, aspect);
        const Stopwatch watch;
        SandboxApp::FrameResult result = app.frame(time, frame == 0 ? 0.0 : kStep, camera, false);
        glFinish();  // the frame time includes the GPU's work, not just its submission
        result.report.frame_ms = watch.elapsed_ms();

        const bool last = frame + 1 == frames;
        const bool png = last || (options.png_every > 0 && frame % options.png_every == 0);
        if (png || options.exr) {
            const Image linear = app.renderer().read(renderer::FrameImage::Frame);
            ToneMapSettings tone;
            tone.exposure = options.exposure > 0.0 ? static_cast<float>(options.exposure)
                                                   : exposure.update(linear);
            last_exposure = tone.exposure;
            if (png) {
                write_png(options.out / frame_name(frame, "png"), linear, tone);
            }
            if (options.exr) {
                write_exr(options.out / frame_name(frame, "exr"), linear);
            }
        }
        report.add_frame(std::move(result.report));
        if ((frame + 1) % 30 == 0 || last) {
            std::cerr << "  frame " << frame + 1 << "/" << frames << "\r" << std::flush;
        }
    }
    std::cerr << "\n";
    report.set_info("exposure", last_exposure);
    const std::filesystem::path report_file = options.report.value_or(options.out / "report.json");
    report.write(report_file);
    std::cout << report.summary() << "frames in " << options.out.string() << ", report in "
              << report_file.string() << "\n";
    return 0;
}

}  // namespace luxel::sandbox
