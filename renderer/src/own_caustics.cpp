#include "own_caustics.hpp"

#include "luxel/runtime/shader_library.hpp"

namespace luxel::renderer {

void OwnCaustics::sync_pass(const std::optional<lighting::CausticPassSettings>& settings,
                            const lighting::LightingSystem& lighting, glm::ivec2 viewport) {
    const bool wanted = settings.has_value() && lighting.plan().caustic_data();
    if (wanted && !pass_) {
        pass_.emplace(*settings, viewport, *shaders_);
    } else if (!wanted) {
        pass_.reset();
        layer_.reset();
    }
}

bool OwnCaustics::sync_layer(bool wanted, const lighting::LightingSystem& lighting) {
    if (!wanted || !pass_) {
        layer_.reset();
        return false;
    }
    // The layer bins the pass's photons: this frame's must be uploaded first (render() uploads
    // again, which writes only slices retraced since).
    pass_->upload(lighting.photons().caustics());
    if (!layer_) {
        layer_.emplace(*shaders_);
    }
    return layer_->sync(*pass_, lighting.maps());
}

CausticInput OwnCaustics::render(const FrameCamera& camera, glm::ivec2 viewport, GLuint depth,
                                 const lighting::LightingSystem& lighting) {
    pass_->upload(lighting.photons().caustics());
    lighting::CausticCamera caustic_camera;
    caustic_camera.view = camera.view;
    caustic_camera.projection = camera.projection;
    caustic_camera.viewport = viewport;
    pass_->render(caustic_camera, depth);
    return CausticInput{pass_->irradiance_texture(), true};
}

}  // namespace luxel::renderer
