#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "luxel/runtime/gl_context.hpp"
#include "sandbox_app.hpp"

namespace luxel::sandbox {

struct RunOptions {
    AppSettings app;
    std::string gl = "auto";
    std::optional<int> frames;  ///< default: 150 headless, until closed in a window
    std::filesystem::path out = "out";
    std::optional<std::filesystem::path> report;  ///< default: <out>/report.json
    bool exr = false;
    /// Display exposure for PNG and the window; 0: automatic (metered per frame).
    double exposure = 0.0;
    int png_every = 1;  ///< write every n-th frame as PNG (0: last only)
    /// Headless camera: "path" follows the level's scripted path; "fixed" stays at its start
    /// (tests compare frames where only the objects move).
    std::string camera = "path";
    /// With camera "fixed": the time along the scripted path the camera stays at.
    double camera_at = 0.0;
    /// Lighting terms to draw (all by default): the README's pictures leave one out at a time.
    renderer::FrameTerms terms;
};

/// Headless: the level's scripted camera for N frames at a fixed 1/30 s step (repeatable);
/// PNG frames (and EXR on request) in `out`, a JSON report and a text summary on stdout.
int run_headless(const RunOptions& options, JobSystem& jobs, GlContext& context);

/// In a GLFW window: free camera (WASD + mouse with the right button held, shift for speed),
/// keys 1-5 toggle direct / indirect / caustics / specular / emission, F freezes motion, P
/// writes a screenshot to `out`, and a Dear ImGui panel shows timings, budget, queues, counters
/// and the FeaturePlan. Runs until closed or for --frames frames.
int run_window(const RunOptions& options, JobSystem& jobs, GlContext& context);

}  // namespace luxel::sandbox
