#pragma once

#include "frame_targets.hpp"
#include "luxel/lighting/gpu/caustic_light_maps.hpp"
#include "luxel/lighting/gpu/lightmap_textures.hpp"
#include "luxel/renderer/frame_camera.hpp"
#include "luxel/runtime/program.hpp"
#include "luxel/runtime/program_variants.hpp"

namespace luxel::renderer {

/// What the composite sums this frame (docs/METHOD.md §8.1): each term's toggle, and the
/// textures of the optional ones (0: absent).
struct CompositeInputs {
    bool direct = false;
    bool indirect = false;
    bool specular = false;
    bool emission = false;
    GLuint caustics = 0;               ///< the caustic term's texture
    bool caustics_irradiance = false;  ///< it holds irradiance W/m^2 (else radiance)
    /// Light-mapped pixels read the caustic layer (FrameSettings::caustic_layer_in_view), with
    /// the IIM pages' sizes from `lightmaps`.
    const lighting::CausticLightMaps* caustic_layer = nullptr;
    const lighting::LightmapTextures* lightmaps = nullptr;
    GLuint sky = 0;       ///< SkyTexture, behind everything drawn
    GLuint sky_mask = 0;  ///< SkyCoverage's mask, with its sub-samples per pixel along an axis
    int sky_mask_scale = 0;
    GLuint black = 0;  ///< a 1 x 1 black texture for the units of absent terms
};

/// The composite (shaders/render/composite.frag): the frame's terms summed per pixel in linear
/// radiance, the sky where nothing was drawn. Its variants compile out the caustic layer and the
/// sky where a frame has none. With a sky mask it draws twice, because the mixing at silhouettes
/// (a surface pixel with the sky over its share, an empty pixel with its neighbours' light)
/// costs tens of fetches a pixel and concerns a few: every pixel without it, then a stencil of
/// the pixels the mask mixes (shaders/render/sky_fill_mask.frag) and those pixels with it.
class CompositePass {
  public:
    explicit CompositePass(const ShaderLibrary& shaders);

    /// Draws into `framebuffer` (targets.frame_target or targets.composed_target) with a
    /// full-screen triangle; the caller binds the empty vertex array and restores state
    /// (FrameRenderer's StateGuard). Makes the targets' stencil on the first frame with a mask.
    void run(FrameTargets& targets, GLuint framebuffer, const FrameCamera& camera,
             const CompositeInputs& in);

  private:
    ProgramVariants programs_;
    gl::Program fill_mask_;
};

}  // namespace luxel::renderer
