#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "luxel/lighting/core/radiance_atlas.hpp"
#include "luxel/runtime/gl_objects.hpp"

namespace luxel::lighting {

/// The lighting system's skies (what its gathers see, RadianceAtlas::skies) as one
/// equirectangular RGB float texture, in SkyRadiance's layout (row 0 the zenith;
/// shaders/common/sky.glsl looks it up): what the hemi-plane gather's pixels that leave the
/// level read, and what the frame and its reflections show where nothing was drawn. Uploaded
/// again only when the skies change; absent (and no texture held) without a sky.
class SkyTexture {
  public:
    /// Follows `atlas`'s skies; returns whether a sky is present.
    bool sync(const RadianceAtlas& atlas);
    [[nodiscard]] bool present() const { return texture_.id() != 0; }
    [[nodiscard]] GLuint id() const { return texture_.id(); }
    /// How many times the texture changed (a sky added, changed or removed): a reader that
    /// keeps the count it last saw knows when to redraw what shows the sky.
    [[nodiscard]] std::uint64_t changes() const { return changes_; }

  private:
    std::vector<RadianceAtlas::Sky> shown_;
    std::uint64_t changes_ = 0;
    gl::Texture texture_;
};

}  // namespace luxel::lighting
