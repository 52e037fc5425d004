#pragma once

#include <optional>

#include <glm/glm.hpp>

#include "luxel/lighting/core/lighting_system.hpp"
#include "luxel/lighting/gpu/caustic_light_maps.hpp"
#include "luxel/lighting/gpu/caustic_pass.hpp"
#include "luxel/renderer/frame_camera.hpp"
#include "luxel/renderer/frame_renderer.hpp"

namespace luxel {
class ShaderLibrary;
}

namespace luxel::renderer {

/// The caustics the renderer makes itself (FrameSettings::caustics): the screen-space
/// CausticPass, which exists exactly while the FeaturePlan has caustic data, and the caustic
/// layer of the light maps (docs/METHOD.md §7.7), which exists while the pass does and a view
/// reads it (the specular cube maps' faces, or the camera with
/// FrameSettings::caustic_layer_in_view). Both are created on the first frame that needs them
/// and freed when none does.
class OwnCaustics {
  public:
    explicit OwnCaustics(const ShaderLibrary& shaders) : shaders_(&shaders) {}

    /// Creates or frees the pass: `settings` nullopt, or a plan without caustic data, frees it.
    void sync_pass(const std::optional<lighting::CausticPassSettings>& settings,
                   const lighting::LightingSystem& lighting, glm::ivec2 viewport);
    /// Creates, updates or frees the layer (`wanted`: a view reads it this frame); returns
    /// whether it changed.
    bool sync_layer(bool wanted, const lighting::LightingSystem& lighting);
    /// This frame's photons splatted against `depth` (the frame's, `viewport` sized) from
    /// `camera`. Needs pass().
    [[nodiscard]] CausticInput render(const FrameCamera& camera, glm::ivec2 viewport, GLuint depth,
                                      const lighting::LightingSystem& lighting);
    /// The pass is made again at the frame's new size by the next frame that needs it.
    void drop_pass() { pass_.reset(); }

    [[nodiscard]] lighting::CausticPass* pass() { return pass_ ? &*pass_ : nullptr; }
    [[nodiscard]] bool has_pass() const { return pass_.has_value(); }
    /// The layer, or null while none exists or it has no page.
    [[nodiscard]] const lighting::CausticLightMaps* layer() const {
        return layer_ && !layer_->empty() ? &*layer_ : nullptr;
    }

  private:
    const ShaderLibrary* shaders_;
    std::optional<lighting::CausticPass> pass_;
    std::optional<lighting::CausticLightMaps> layer_;
};

}  // namespace luxel::renderer
