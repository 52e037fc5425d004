// The GL loader first: GLFW and ImGui's backends must not pull in the system's gl.h.
#include "luxel/runtime/gl.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "exposure.hpp"
#include "luxel/runtime/clock.hpp"
#include "luxel/runtime/error.hpp"
#include "present_pass.hpp"
#include "runs.hpp"

namespace luxel::sandbox {
namespace {

/// WASD + mouse: move in the view's plane, look while the right button is held, shift for
/// speed, Q/E down and up.
class FreeCamera {
  public:
    explicit FreeCamera(const CameraPose& start) : eye_(start.eye), fov_(start.vertical_fov) {
        const glm::vec3 d = glm::normalize(start.target - start.eye);
        yaw_ = std::atan2(d.x, -d.z);
        pitch_ = std::asin(std::clamp(d.y, -1.0f, 1.0f));
    }

    void update(GLFWwindow* window, double dt, bool ui_wants_mouse) {
        double x = 0.0;
        double y = 0.0;
        glfwGetCursorPos(window, &x, &y);
        const bool looking =
            !ui_wants_mouse && glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
        if (looking && had_cursor_) {
            yaw_ += static_cast<float>(x - last_x_) * 0.003f;
            pitch_ = std::clamp(pitch_ - static_cast<float>(y - last_y_) * 0.003f, -1.5f, 1.5f);
        }
        had_cursor_ = looking;
        last_x_ = x;
        last_y_ = y;
        const glm::vec3 forward = direction();
        const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0.0f, 1.0f, 0.0f)));
        const bool fast = glfwGetKey(window, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS;
        const float step = static_cast<float>(dt) * (fast ? 6.0f : 1.5f);
        const auto held = [&](int key) { return glfwGetKey(window, key) == GLFW_PRESS; };
        eye_ +=
            step *
            (forward *
                 (static_cast<float>(held(GLFW_KEY_W)) - static_cast<float>(held(GLFW_KEY_S))) +
             right * (static_cast<float>(held(GLFW_KEY_D)) - static_cast<float>(held(GLFW_KEY_A))) +
             glm::vec3(0.0f, 1.0f, 0.0f) *
                 (static_cast<float>(held(GLFW_KEY_E)) - static_cast<float>(held(GLFW_KEY_Q))));
    }

    [[nodiscard]] renderer::FrameCamera camera(float aspect) const {
        return renderer::FrameCamera::look_at(eye_, eye_ + direction(), glm::vec3(0, 1, 0), fov_,
                                              aspect);
    }

  private:
    [[nodiscard]] glm::vec3 direction() const {
        return {std::sin(yaw_) * std::cos(pitch_), std::sin(pitch_),
                -std::cos(yaw_) * std::cos(pitch_)};
    }
    glm::vec3 eye_;
    float fov_;
    float yaw_ = 0.0f;
    float pitch_ = 0.0f;
    bool had_cursor_ = false;
    double last_x_ = 0.0;
    double last_y_ = 0.0;
};

/// Edge-triggered keys: true once per press.
class KeyPresses {
  public:
    bool pressed(GLFWwindow* window, int key) {
        const bool down = glfwGetKey(window, key) == GLFW_PRESS;
        const bool was = down_[static_cast<std::size_t>(key) % down_.size()];
        down_[static_cast<std::size_t>(key) % down_.size()] = down;
        return down && !was;
    }

  private:
    std::array<bool, 512> down_{};
};

void draw_panel(const SandboxApp& app, const RunReport::Frame& frame, double frame_ms,
                const renderer::FrameTerms& terms, bool frozen, float& budget) {
    ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowBgAlpha(0.75f);
    ImGui::Begin("luxel");
    ImGui::Text("%s | frame %.2f ms", app.level_name().c_str(), frame_ms);
    ImGui::SliderFloat("budget (ms)", &budget, 0.0f, 16.0f, "%.1f");
    ImGui::Text("lighting %.2f ms of %.1f ms (%.0f%%)", frame.lighting_ms, frame.budget_ms,
                frame.budget_ms > 0.0 ? 100.0 * frame.lighting_ms / frame.budget_ms : 0.0);
    if (ImGui::CollapsingHeader("GPU passes (ms)", ImGuiTreeNodeFlags_DefaultOpen)) {
        for (const auto& [name, ms] : frame.pass_ms) {
            ImGui::Text("%-10s %7.3f", name.c_str(), ms);
        }
    }
    if (ImGui::CollapsingHeader("work this frame", ImGuiTreeNodeFlags_DefaultOpen)) {
        for (const auto& [name, value] : frame.counters) {
            ImGui::Text("%-24s %10.0f", name.c_str(), value);
        }
        const auto& schedule = app.lighting().stats().schedule;
        for (std::size_t kind = 0; kind < lighting::kWorkKindCount; ++kind) {
            const auto& k = schedule.kinds[kind];
            ImGui::Text("%-14s %3u done %6.2f ms, %zu queued",
                        std::string(lighting::name(static_cast<lighting::WorkKind>(kind))).c_str(),
                        k.units_done, k.ms, k.pending_after);
        }
    }
    if (ImGui::CollapsingHeader("feature plan")) {
        ImGui::TextUnformatted(app.lighting().plan().describe().c_str());
    }
    ImGui::Text("terms [1-5]: %s %s %s %s %s%s", terms.direct ? "direct" : "-",
                terms.indirect ? "indirect" : "-", terms.caustics ? "caustics" : "-",
                terms.specular ? "specular" : "-", terms.emission ? "emission" : "-",
                frozen ? "  [F: frozen]" : "");
    ImGui::Text("WASD/QE move, right mouse look, shift fast, P screenshot");
    ImGui::End();
}

}  // namespace

int run_window(const RunOptions& options, JobSystem& jobs, GlContext& context) {
    GLFWwindow* window = context.native_window();
    if (window == nullptr) {
        throw Error("window mode needs a window context");
    }
    const ShaderLibrary shaders;
    SandboxApp app(options.app, jobs, shaders);
    renderer::FrameTerms terms = options.terms;
    app.renderer().set_terms(terms);
    const PresentPass present(shaders);
    FreeCamera camera(app.camera_path().at(0.0));
    KeyPresses keys;
    AutoExposure exposure;

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to the user's files
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 450");

    FrameClock clock;
    bool frozen = false;
    double game_time = 0.0;
    float budget = static_cast<float>(options.app.budget_ms);
    int screenshots = 0;
    const int limit = options.frames.value_or(-1);
    RunReport report;
    for (int frame = 0; (limit < 0 || frame < limit) && !context.should_close(); ++frame) {
        context.poll_events();
        const FrameTime tick = clock.tick();
        const double dt = std::min(tick.delta_seconds, 0.1);
        const bool ui_mouse = ImGui::GetIO().WantCaptureMouse;
        camera.update(window, dt, ui_mouse);
        const int toggle_keys[5] = {GLFW_KEY_1, GLFW_KEY_2, GLFW_KEY_3, GLFW_KEY_4, GLFW_KEY_5};
        bool* toggles[5] = {&terms.direct, &terms.indirect, &terms.caustics, &terms.specular,
                            &terms.emission};
        for (int k = 0; k < 5; ++k) {
            if (keys.pressed(window, toggle_keys[k])) {
                *toggles[k] = !*toggles[k];
                app.renderer().set_terms(terms);
            }
        }
        if (keys.pressed(window, GLFW_KEY_F)) {
            frozen = !frozen;
        }
        const bool screenshot = keys.pressed(window, GLFW_KEY_P);
        if (!frozen) {
            game_time += dt;
        }
        app.set_budget_ms(budget);
        const int width = context.framebuffer_width();
        const int height = context.framebuffer_height();
        const float aspect = static_cast<float>(options.app.width) /
                             static_cast<float>(std::max(options.app.height, 1));
        const Stopwatch watch;
        SandboxApp::FrameResult result =
            app.frame(game_time, frozen ? 0.0 : dt, camera.camera(aspect), frozen);
        if (frame % 15 == 0 || screenshot) {
            exposure.update(app.renderer().read(renderer::FrameImage::Frame));
        }
        ToneMapSettings tone;
        tone.exposure = exposure.exposure();
        present.draw(app.renderer().frame_texture(), width, height, tone);

        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        draw_panel(app, result.report, watch.elapsed_ms(), terms, frozen, budget);
        ImGui::Render();
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        if (screenshot) {
            std::filesystem::create_directories(options.out);
            char name[64];
            std::snprintf(name, sizeof(name), "screenshot_%03d.png", screenshots++);
            write_png(options.out / name, app.renderer().read(renderer::FrameImage::Frame), tone);
            std::cout << "wrote " << (options.out / name).string() << "\n";
        }
        context.swap_buffers();
        result.report.frame_ms = watch.elapsed_ms();
        report.add_frame(std::move(result.report));
    }
    // With --frames (tests, scripted runs) the last frame is kept as a screenshot.
    if (limit > 0) {
        std::filesystem::create_directories(options.out);
        ToneMapSettings tone;
        tone.exposure = exposure.exposure();
        write_png(options.out / "window_last.png", app.renderer().read(renderer::FrameImage::Frame),
                  tone);
    }
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    if (options.report) {
        report.write(*options.report);
    }
    std::cout << report.summary();
    return 0;
}

}  // namespace luxel::sandbox
