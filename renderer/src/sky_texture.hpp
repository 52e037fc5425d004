#pragma once

#include <memory>
#include <vector>

#include "luxel/lighting/core/radiance_atlas.hpp"
#include "luxel/runtime/gl_objects.hpp"

namespace luxel::renderer {

/// The sky the frame shows where nothing was drawn: the lighting system's skies (what its
/// gathers see, RadianceAtlas::skies) as one equirectangular RGB float texture, in
/// SkyRadiance's layout (row 0 the zenith; shaders/render/sky.glsl looks it up). Uploaded
/// again only when the skies change; absent (and no texture held) without a sky.
class SkyTexture {
  public:
    /// Follows `atlas`'s skies; returns whether a sky is present.
    bool sync(const lighting::RadianceAtlas& atlas);
    [[nodiscard]] bool present() const { return texture_.id() != 0; }
    [[nodiscard]] GLuint id() const { return texture_.id(); }

  private:
    std::vector<lighting::RadianceAtlas::Sky> shown_;
    gl::Texture texture_;
};

}  // namespace luxel::renderer
