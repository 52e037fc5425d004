#pragma once

// The real-time frame for luxel-bench's image error: FrameRenderer and CausticPass on a
// headless GL context, composed as the sandbox composes them, from the reference's camera.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "luxel/ecs/registry.hpp"
#include "luxel/lighting/core/lighting_system.hpp"
#include "luxel/lighting/gpu/caustic_pass.hpp"
#include "luxel/lighting/reference/reference_frame.hpp"
#include "luxel/renderer/frame_camera.hpp"
#include "luxel/renderer/frame_renderer.hpp"
#include "luxel/runtime/gl_context.hpp"
#include "luxel/runtime/image.hpp"
#include "luxel/runtime/shader_library.hpp"

namespace luxel::bench {

/// A headless OpenGL 4.5 context: EGL, else OSMesa (the sandbox's headless order; never a
/// window). Throws GlContextError listing both attempts.
[[nodiscard]] std::unique_ptr<GlContext> make_headless_context();

/// "larsen", "box", "cone", "world", "mip" as CausticPass kernels. Throws luxel::Error
/// otherwise.
[[nodiscard]] lighting::CausticKernel parse_kernel(const std::string& name);

/// The renderer's camera with exactly the reference camera's view and projection (so both
/// frames see the same pixels). Throws luxel::Error for an orthographic projection: the caustic
/// pass needs a perspective one.
[[nodiscard]] renderer::FrameCamera frame_camera(
    const lighting::reference::ReferenceCamera& camera);

struct FrameShot {
    Image image;                  ///< the composed linear frame, rows top first
    double frame_gpu_ms = 0.0;    ///< FrameRenderer's passes (GPU timer queries)
    double caustic_gpu_ms = 0.0;  ///< CausticPass splat + filter (GPU); 0 without caustics
    /// Per pixel (rows top first), 1 where geometry without a light map is drawn: the
    /// receivers the irradiance probes light, where their error is measured on its own.
    std::vector<std::uint8_t> unmapped;
};

/// The knobs of a run that change only its frame (BenchConfig::kernel, aa, lightmap).
struct FrameChoices {
    lighting::CausticKernel kernel = lighting::CausticKernel::Larsen;
    bool anti_aliasing = true;
    bool bicubic_light_maps = false;
    bool sky_edge_coverage = true;
    /// kernel=layer: light-mapped pixels read the caustic layer of the light maps
    /// (FrameSettings::caustic_layer_in_view), the others `kernel`'s splat.
    bool caustic_layer = false;
    /// kernel=footprints: CausticPassSettings::footprint_scale and footprint_min_pixels.
    float footprint_scale = lighting::CausticPassSettings{}.footprint_scale;
    float footprint_min = lighting::CausticPassSettings{}.footprint_min_pixels;
};

/// One run's renderer. Needs the context current for its whole life.
class FrameView {
  public:
    FrameView(ecs::Registry& registry, const lighting::LightingSystem& lighting,
              const lighting::reference::ReferenceCamera& camera, const FrameChoices& choices,
              const ShaderLibrary& shaders);
    FrameView(const FrameView&) = delete;
    FrameView& operator=(const FrameView&) = delete;

    /// The frame at `now_seconds` (the clock given to LightingSystem::update) with this
    /// frame's caustics (FrameRenderer's caustic stage: not one frame late).
    [[nodiscard]] FrameShot render(double now_seconds);
    /// The same frame with the caustic term alone (FrameTerms: caustics only), linear, rows
    /// top first: what --caustic-pixels compares with the reference's pixel-resolution caustic.
    [[nodiscard]] Image render_caustics(double now_seconds);

  private:
    renderer::FrameCamera camera_;
    renderer::FrameRenderer renderer_;
};

}  // namespace luxel::bench
