#pragma once

#include "frame_targets.hpp"
#include "luxel/lighting/gpu/irradiance_probe_textures.hpp"
#include "luxel/lighting/gpu/lightmap_textures.hpp"
#include "luxel/renderer/frame_camera.hpp"
#include "luxel/runtime/program_variants.hpp"

namespace luxel::renderer {

/// The indirect term per pixel (shaders/render/indirect.frag): the IIM pages at the pixel's
/// light-map UV, bilinear or bicubic (a variant each), and for receivers without a light map
/// the irradiance probes. The probes' variant runs only on the pixels the G-buffer pass marked
/// in its stencil (no light map): on a software rasteriser the probes' lookup would otherwise
/// cost every pixel it is compiled into (docs/PERFORMANCE.md, "Shader variants and masked
/// passes").
class IndirectPass {
  public:
    explicit IndirectPass(const ShaderLibrary& shaders);

    /// Draws into targets.indirect_target with a full-screen triangle; the caller binds the empty
    /// vertex array and restores state (FrameRenderer's StateGuard).
    void run(const FrameTargets& targets, const FrameCamera& camera, double now_seconds,
             bool bicubic, const lighting::LightmapTextures& lightmaps,
             const lighting::IrradianceProbeTextures& probes);

  private:
    ProgramVariants programs_;
};

}  // namespace luxel::renderer
