#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/lighting/core/radiance_atlas.hpp"
#include "luxel/runtime/gl_objects.hpp"

namespace luxel::lighting {

/// A RadianceAtlas on the GPU: every page is one layer of an RGB32F 2D texture array (sized
/// for the largest page; smaller pages sit in the corner of their layer), sampled bilinearly.
/// A surface table, two vec4 per surface (layer or -1, page size / layer size, and the UV
/// clamp range that keeps both bilinear taps on the page; then the radiance the surface
/// emits), lets the shader find a surface's page: RadianceAtlas::sample's lookup, texel for
/// texel.
class RadianceTexture {
  public:
    /// Uploads what changed since the last call: the whole array when the page count or a page
    /// size changed, otherwise each page whose version (or storage) changed; the surface table
    /// when surface_page changed.
    void sync(const RadianceAtlas& atlas);

    [[nodiscard]] GLuint texture() const { return texture_.id(); }
    [[nodiscard]] GLuint surface_table() const { return surface_table_.id(); }
    /// Pages uploaded since construction (for tests of the version tracking).
    [[nodiscard]] std::uint64_t page_uploads() const { return page_uploads_; }

  private:
    struct PageState {
        int size = 0;
        std::uint64_t version = 0;
        const void* storage = nullptr;
    };

    void allocate(const RadianceAtlas& atlas);
    void upload_page(const RadiancePage& page, int layer);

    gl::Texture texture_;
    int layer_size_ = 0;
    std::vector<PageState> uploaded_;
    gl::Buffer surface_table_;
    std::vector<glm::vec4> table_;
    std::uint64_t page_uploads_ = 0;
};

}  // namespace luxel::lighting
