#include "frame_view.hpp"

#include <cmath>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/runtime/error.hpp"

namespace luxel::bench {
namespace {

renderer::FrameSettings frame_settings(const lighting::reference::ReferenceCamera& camera,
                                       const FrameChoices& choices) {
    renderer::FrameSettings settings;
    settings.anti_aliasing = choices.anti_aliasing;
    settings.bicubic_light_maps = choices.bicubic_light_maps;
    settings.sky_edge_coverage = choices.sky_edge_coverage;
    settings.caustics = lighting::CausticPassSettings{};
    settings.caustics->kernel = choices.kernel;
    settings.caustics->footprint_scale = choices.footprint_scale;
    settings.caustics->footprint_min_pixels = choices.footprint_min;
    settings.caustic_layer_in_view = choices.caustic_layer;
    settings.width = camera.width;
    settings.height = camera.height;
    // The timings reported are this frame's, not a frame still in flight.
    settings.wait_for_timings = true;
    // A checkpoint renders once where a game renders every frame: with all six faces per
    // render, the specular probes show what continuous rendering of the static scene would
    // have converged to (the sandbox spreads them, one face per frame).
    settings.specular_faces_per_frame = 6;
    return settings;
}

}  // namespace

std::unique_ptr<GlContext> make_headless_context() {
    GlContextOptions options;
    options.width = 16;  // headless: the frame renders into its own framebuffers
    options.height = 16;
    std::string failures;
    for (const GlBackend backend : {GlBackend::Egl, GlBackend::OsMesa}) {
        options.backend = backend;
        try {
            return create_gl_context(options);
        } catch (const GlContextError& e) {
            failures += std::string("\n  - ") + e.what();
        }
    }
    throw GlContextError(
        "the image error and the GPU gather backend need an OpenGL 4.5 context, and none could "
        "be created (--no-image runs without one):" +
        failures);
}

lighting::CausticKernel parse_kernel(const std::string& name) {
    if (name == "larsen") {
        return lighting::CausticKernel::Larsen;
    }
    if (name == "box") {
        return lighting::CausticKernel::Box;
    }
    if (name == "cone") {
        return lighting::CausticKernel::RoundCone;
    }
    if (name == "world") {
        return lighting::CausticKernel::WorldCone;
    }
    if (name == "mip") {
        return lighting::CausticKernel::MipLevels;
    }
    if (name == "footprints") {
        return lighting::CausticKernel::PhotonFootprints;
    }
    throw Error("kernel '" + name + "': expected larsen, box, cone, world, mip or footprints");
}

renderer::FrameCamera frame_camera(const lighting::reference::ReferenceCamera& camera) {
    // A perspective projection has -1 in [2][3] and 0 in [3][3]; an orthographic one 0 and 1.
    if (camera.projection[3][3] != 0.0f || !(camera.projection[1][1] > 0.0f)) {
        throw Error(
            "the level's camera is not a perspective camera, which the caustic pass needs "
            "(--no-image leaves the image error out)");
    }
    renderer::FrameCamera out;
    out.view = camera.view;
    out.projection = camera.projection;
    out.position = glm::vec3(glm::inverse(camera.view)[3]);
    out.yfov = 2.0f * std::atan(1.0f / camera.projection[1][1]);
    return out;
}

FrameView::FrameView(ecs::Registry& registry, const lighting::LightingSystem& lighting,
                     const lighting::reference::ReferenceCamera& camera,
                     const FrameChoices& choices, const ShaderLibrary& shaders)
    : camera_(frame_camera(camera)),
      renderer_(registry, lighting, frame_settings(camera, choices), shaders) {}

Image FrameView::render_caustics(double now_seconds) {
    const renderer::FrameTerms all = renderer_.terms();
    renderer_.set_terms({false, false, true, false, false});
    static_cast<void>(renderer_.render(camera_, now_seconds));
    Image image = renderer_.read(renderer::FrameImage::Frame);
    renderer_.set_terms(all);
    return image;
}

FrameShot FrameView::render(double now_seconds) {
    // As the sandbox: the renderer's own caustic pass runs between its G-buffer and its
    // composite while the FeaturePlan has caustic data, so this frame's caustics are in it.
    FrameShot shot;
    shot.frame_gpu_ms = renderer_.render(camera_, now_seconds).total();
    if (lighting::CausticPass* caustics = renderer_.caustic_pass(); caustics != nullptr) {
        const lighting::CausticPassStats& stats = caustics->stats();
        shot.caustic_gpu_ms = stats.splat_ms + stats.filter_ms;
    }
    shot.image = renderer_.read(renderer::FrameImage::Frame);
    const int w = shot.image.width;
    const int h = shot.image.height;
    std::vector<glm::vec4> lookup(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
    std::vector<glm::vec4> position(lookup.size());
    const auto bytes = static_cast<GLsizei>(lookup.size() * sizeof(glm::vec4));
    glGetTextureImage(renderer_.lightmap_texture(), 0, GL_RGBA, GL_FLOAT, bytes, lookup.data());
    glGetTextureImage(renderer_.position_texture(), 0, GL_RGBA, GL_FLOAT, bytes, position.data());
    shot.unmapped.assign(lookup.size(), 0);
    for (int y = 0; y < h; ++y) {
        // GL rows are bottom first, the image's top first.
        for (int x = 0; x < w; ++x) {
            const std::size_t gl =
                static_cast<std::size_t>(h - 1 - y) * static_cast<std::size_t>(w) +
                static_cast<std::size_t>(x);
            shot.unmapped[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) +
                          static_cast<std::size_t>(x)] =
                position[gl].w > 0.5f && lookup[gl].z < 0.0f ? 1 : 0;
        }
    }
    return shot;
}

}  // namespace luxel::bench
